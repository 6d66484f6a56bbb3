#include "mesh/gmsh_reader.hpp"

#include <gmsh.h>
#include <omp.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <unordered_map>

#include "core/error.hpp"
#include "core/file.hpp"
#include "core/log.hpp"
#include "core/sandbox.hpp"
#include "mesh/geo_check.hpp"
#include "mesh/gmsh_model_data.hpp"
#include "mesh/msh_check.hpp"

namespace dspdem {

namespace {
constexpr int kGmshTet4 = 4;
constexpr int kGmshHex8 = 5;
constexpr int kGmshTri3 = 2;
constexpr int kGmshQuad4 = 3;

std::string gmsh_last_error() {
  std::string err;
  try {
    gmsh::logger::getLastError(err);
  } catch (...) {
  }
  return err;
}

}  // namespace

// gmsh sets the OpenMP thread count to its own General.NumThreads (1) on initialise and
// on some calls; the solver's count is restored when the session ends.
GmshSession::GmshSession() : omp_threads_(omp_get_max_threads()) {
  // gmsh 4.8 has no isInitialized(); the library stays initialised for the process.
  static const bool initialised = [] {
    gmsh::initialize(0, nullptr, false);
    return true;
  }();
  (void)initialised;
  gmsh::option::setNumber("General.Terminal", log::level() >= log::Level::Debug ? 1 : 0);
  // One meshing thread, every session: otherwise gmsh meshes a .geo with the solver's
  // OpenMP threads (the first session of a process had 1, from initialise; later ones 2),
  // and its threaded mesher is not deterministic: the same .geo gave 7758 nodes, then 7755
  // and 7672 in one process, and a restart found another model than its checkpoint's.
  gmsh::option::setNumber("General.NumThreads", 1);
  // A batch tool: gmsh must not stop to ask on stdin (a size that gives a very large mesh
  // asks whether to go on; with no popups it takes the default answer and goes on).
  gmsh::option::setNumber("General.NoPopup", 1);
  gmsh::clear();
}

GmshSession::~GmshSession() {
  try {
    gmsh::clear();
  } catch (...) {
  }
  omp_set_num_threads(omp_threads_);
}

namespace {
std::string element_type_name(int type) {
  try {
    std::string name;
    int d, order, nn, npn;
    std::vector<double> lc;
    gmsh::model::mesh::getElementProperties(type, name, d, order, nn, lc, npn);
    return name;
  } catch (...) {
    return fmt::format("gmsh type {}", type);
  }
}
}  // namespace

Mesh mesh_from_model_data(const GmshModelData& model, const std::string& source) {
  Mesh mesh;
  mesh.source = source;
  auto garbled = [&](bool ok) {
    DSPDEM_CHECK(ok, "mesh '{}': the mesh read in its own process came back garbled", source);
  };
  std::map<std::pair<int, int>, const GmshEntity*> entity;
  for (const GmshEntity& e : model.entities) entity[{e.dim, e.tag}] = &e;

  // Volume cells first: they decide which nodes the model uses.
  ElementBlock tets{CellType::Tet4, {}, {}}, hexes{CellType::Hex8, {}, {}};
  std::unordered_map<std::size_t, Index> node_index;
  std::vector<std::size_t> used_tags;
  auto local = [&](std::size_t tag) {
    auto [it, inserted] = node_index.try_emplace(tag, static_cast<Index>(used_tags.size()));
    if (inserted) used_tags.push_back(tag);
    return it->second;
  };
  // A node's index among the cells' nodes, or -1 for a node no cell uses.
  auto cell_node = [&](std::size_t tag) -> Index {
    const auto n = node_index.find(tag);
    return n == node_index.end() ? Index{-1} : n->second;
  };
  // entity tag -> (block, first, count) ranges so volume groups can list their elements
  struct Range {
    int block;
    Index first, count;
  };
  std::unordered_map<int, std::vector<Range>> entity_ranges;
  bool any_volume = false;
  for (const GmshEntity& v : model.entities) {
    if (v.dim != 3) continue;
    any_volume = true;
    for (std::size_t k = 0; k < v.types.size(); ++k) {
      const auto& etags = v.elem_tags[k];
      ElementBlock* blk = nullptr;
      int b = -1;
      if (v.types[k] == kGmshTet4) {
        blk = &tets;
        b = 0;
      } else if (v.types[k] == kGmshHex8) {
        blk = &hexes;
        b = 1;
      } else {
        fail(
            "mesh '{}': volume {} holds {} element(s) of type '{}' (e.g. tag {}); only linear tetrahedra "
            "and hexahedra are supported",
            source, v.tag, etags.size(), element_type_name(v.types[k]), etags.empty() ? 0 : etags[0]);
      }
      const std::size_t npe = static_cast<std::size_t>(blk->npe());
      garbled(v.elem_nodes[k].size() == etags.size() * npe);
      entity_ranges[v.tag].push_back({b, blk->size(), static_cast<Index>(etags.size())});
      for (std::size_t e = 0; e < etags.size(); ++e) {
        blk->tag.push_back(etags[e]);
        for (std::size_t i = 0; i < npe; ++i) blk->conn.push_back(local(v.elem_nodes[k][e * npe + i]));
      }
    }
  }
  DSPDEM_CHECK(any_volume, "mesh '{}': no volume entities (a 3D mesh is needed)", source);
  DSPDEM_CHECK(tets.size() + hexes.size() > 0, "mesh '{}': no tetrahedra or hexahedra found", source);
  mesh.blocks.push_back(std::move(tets));
  mesh.blocks.push_back(std::move(hexes));

  // Coordinates of the used nodes only: geometry points not attached to cells carry no mass.
  mesh.x.assign(3 * used_tags.size(), 0.0);
  std::vector<char> seen(used_tags.size(), 0);
  for (const GmshEntity& e : model.entities)
    for (std::size_t i = 0; i < e.node_tags.size(); ++i) {
      const Index n = cell_node(e.node_tags[i]);
      if (n < 0) continue;
      for (int d = 0; d < 3; ++d) mesh.x[3 * static_cast<std::size_t>(n) + d] = e.coord[3 * i + d];
      seen[static_cast<std::size_t>(n)] = 1;
    }
  for (std::size_t i = 0; i < seen.size(); ++i)
    DSPDEM_CHECK(seen[i], "mesh '{}': element refers to node {} which has no coordinates", source, used_tags[i]);
  mesh.node_tag = std::move(used_tags);

  // Physical groups.
  for (const GmshPhysical& p : model.physicals) {
    Group g;
    g.dim = p.dim;
    g.name = p.name.empty() ? std::to_string(p.tag) : p.name;
    // As a .msh's check names them (a .geo's were written into a .msh that its check refused).
    DSPDEM_CHECK(std::none_of(g.name.begin(), g.name.end(),
                              [](char c) { return c == '"' || static_cast<unsigned char>(c) < 32 || c == 127; }),
                 "mesh '{}': physical group name '{}' holds a quote or a control character", source,
                 log::printable(g.name));
    DSPDEM_CHECK(mesh.find_group(g.name) == nullptr, "mesh '{}': physical group name '{}' used twice", source, g.name);
    if (p.dim == 3) {
      g.elements.resize(mesh.blocks.size());
      for (int ent : p.entities)
        for (const auto& r : entity_ranges[ent])
          for (Index e = r.first; e < r.first + r.count; ++e) g.elements[r.block].push_back(e);
      for (std::size_t b = 0; b < mesh.blocks.size(); ++b)
        for (Index e : g.elements[b]) {
          const auto& blk = mesh.blocks[b];
          for (int i = 0; i < blk.npe(); ++i) g.nodes.push_back(blk.conn[static_cast<std::size_t>(e) * blk.npe() + i]);
        }
    } else {
      // The nodes of the group's elements (as gmsh's getNodesForPhysicalGroup), and a
      // surface's faces, on the nodes that cells use.
      for (int ent : p.entities) {
        const auto it = entity.find({p.dim, ent});
        if (it == entity.end()) continue;
        const GmshEntity& e = *it->second;
        const auto add_nodes = [&](const std::vector<std::size_t>& tags) {
          for (const std::size_t t : tags)
            if (const Index n = cell_node(t); n >= 0) g.nodes.push_back(n);
        };
        if (p.dim == 0) add_nodes(e.node_tags);  // a point's own node, with or without a point element (as gmsh)
        for (std::size_t k = 0; k < e.types.size(); ++k) {
          add_nodes(e.elem_nodes[k]);
          auto* dst = p.dim != 2                 ? nullptr
                      : e.types[k] == kGmshTri3  ? &g.tri
                      : e.types[k] == kGmshQuad4 ? &g.quad
                                                 : nullptr;
          if (!dst) continue;
          garbled(e.elem_nodes[k].size() == e.elem_tags[k].size() * (dst == &g.tri ? 3 : 4));
          for (const std::size_t t : e.elem_nodes[k]) {
            const Index n = cell_node(t);
            DSPDEM_CHECK(n >= 0, "mesh '{}': surface group '{}' has a face node {} not on any cell", source, g.name, t);
            dst->push_back(n);
          }
        }
      }
    }
    std::sort(g.nodes.begin(), g.nodes.end());
    g.nodes.erase(std::unique(g.nodes.begin(), g.nodes.end()), g.nodes.end());
    mesh.groups.push_back(std::move(g));
  }
  check_element_volumes(mesh);
  return mesh;
}

Mesh mesh_from_gmsh_model(const std::string& source) { return mesh_from_model_data(gmsh_model_data(), source); }

namespace {
// The child's part (core/sandbox.hpp): gmsh opens the file, a .geo's script runs and is
// meshed, and the model comes back whole. Its messages follow "mesh file '<path>': ".
// The parent's GmshSession has set gmsh up (and cleared it, which removes gmsh's temporary
// file: a call the child may not make).
std::string open_in_child(const std::string& path, bool geo) {
  try {
    gmsh::open(path);
  } catch (...) {
    const std::string err = gmsh_last_error();
    fail("gmsh could not read it: {}", err.empty() ? "gmsh gave no reason" : err);
  }
  const std::string err = gmsh_last_error();
  DSPDEM_CHECK(err.empty(), "gmsh reported: {}", err);
  if (geo) {
    std::vector<std::size_t> t;
    std::vector<double> c, p;
    gmsh::model::mesh::getNodes(t, c, p, 3, -1, true, false);
    if (t.empty()) {
      try {
        gmsh::model::mesh::generate(3);
      } catch (...) {
        fail("gmsh could not mesh it: {}", gmsh_last_error());
      }
    }
  }
  return to_bytes(gmsh_model_data());
}
}  // namespace

Mesh read_gmsh(const std::string& path, const std::string& save_as, double time_limit) {
  namespace fs = std::filesystem;
  try {
    DSPDEM_CHECK(fs::exists(path), "mesh file '{}' does not exist", path);
    const auto ext = fs::path(path).extension().string();
    DSPDEM_CHECK(ext == ".msh" || ext == ".geo", "mesh file '{}': expected a .msh or .geo file", path);
    const std::string text = read_file(path, "mesh file");
    if (ext == ".msh") {
      // gmsh trusts the file (a missing node crashes it): the text is checked first, and
      // its faults are named by line.
      check_msh_text(path, text);  // which also refuses a first line gmsh would run as a script
    } else {
      // Refused by line before anything runs (a .geo holding a mesh too: gmsh would read it as
      // one, past the mesh's check); the sandbox (read_gmsh_unchecked) stops what gets past.
      check_geo_script(path, text);
    }
    check_gmsh_option_file(path);  // gmsh runs "<file>.opt" beside the file it opens
  } catch (const fs::filesystem_error& e) {
    // A name too long, a loop of links: said as the file's fault, not as dspdem's.
    fail("mesh file '{}': {}: {}", path, e.path1().string(), e.code().message());
  }
  return read_gmsh_unchecked(path, save_as, time_limit);
}

Mesh read_gmsh_unchecked(const std::string& path, const std::string& save_as, double time_limit) {
  namespace fs = std::filesystem;
  const bool geo = fs::path(path).extension() == ".geo";
  // gmsh opens the file in a child process that cannot start programs, write files or open
  // sockets, and that is stopped after time_limit: a .geo is a program, and a file that
  // crashes gmsh then ends that process, not this one. It also keeps this process's gmsh
  // clear of the reader's state after an error (its "busy" lock ignored every later open).
  // gmsh is initialised here first: at its first start it writes FLTK's preferences file,
  // which the child may not.
  GmshSession session;
  const SandboxResult got = run_sandboxed([&] { return open_in_child(path, geo); }, time_limit);
  switch (got.status) {
    case SandboxResult::Status::Done:
      break;
    case SandboxResult::Status::Failed:
      fail("mesh file '{}': {}", path, got.message);
    case SandboxResult::Status::Refused:
      fail(
          "mesh file '{}': gmsh was stopped at {} that reading it made: a mesh file may not start programs, write, "
          "remove or change files, open sockets or signal other processes",
          path, got.message.empty() ? std::string("a system call") : "the system call " + got.message);
    case SandboxResult::Status::TimedOut:
      fail("mesh file '{}': gmsh {} ([mesh] time_limit; a larger mesh may need more)", path, got.message);
    case SandboxResult::Status::Ended:
      fail("mesh file '{}': gmsh ended before it had read the mesh ({}): a script's Exit ends it so, or a crash", path,
           got.message);
  }
  const GmshModelData model = from_bytes(got.bytes, path);
  Mesh mesh = mesh_from_model_data(model, path);
  if (!save_as.empty()) {
    // Loaded into this process's gmsh to be written, with the file's own write options for
    // this write only (gmsh keeps options for the process).
    try {
      load_into_gmsh(model);
    } catch (...) {
      fail("mesh file '{}': gmsh could not take the mesh back to write it: {}", path, gmsh_last_error());
    }
    GmshOptions before;
    for (const auto& [name, value] : model.write_options) {
      double v = 0;
      gmsh::option::getNumber(name, v);
      before.emplace_back(name, v);
      gmsh::option::setNumber(name, value);
    }
    // gmsh picks the format from the extension: the temporary name ends in .msh too.
    const fs::path dst(save_as), tmp = dst.parent_path() / fmt::format(".{}.tmp.msh", dst.stem().string());
    std::string write_error;
    try {
      gmsh::write(tmp.string());
    } catch (...) {
      write_error = gmsh_last_error();
    }
    for (const auto& [name, value] : before) gmsh::option::setNumber(name, value);
    DSPDEM_CHECK(write_error.empty(), "cannot write mesh '{}': {}", tmp.string(), write_error);
    fs::rename(tmp, dst);
  }
  return mesh;
}

}  // namespace dspdem
