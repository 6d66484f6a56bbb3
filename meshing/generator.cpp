#include "meshing/generator.hpp"

#include <fcntl.h>
#include <gmsh.h>
#include <sys/file.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <mutex>
#include <string_view>

#include "core/error.hpp"
#include "core/log.hpp"
#include "mesh/gmsh_reader.hpp"

namespace dspdem::meshing {

namespace fs = std::filesystem;

// One translation unit per generator; each defines its build function.
void build_brazilian_disc(const Params&);
const std::vector<schema::Key>& brazilian_disc_keys();
void build_galvez_beam(const Params&);
const std::vector<schema::Key>& galvez_beam_keys();
void build_murray_beam(const Params&);
const std::vector<schema::Key>& murray_beam_keys();
void build_sphere_plate(const Params&);
const std::vector<schema::Key>& sphere_plate_keys();
void build_packing(const Params&);
const std::vector<schema::Key>& packing_keys();

double Params::operator[](const std::string& key) const {
  auto it = num.find(key);
  DSPDEM_CHECK(it != num.end(), "internal: generator '{}' has no numeric parameter '{}'", generator, key);
  return it->second;
}

const std::string& Params::text(const std::string& key) const {
  auto it = str.find(key);
  DSPDEM_CHECK(it != str.end(), "internal: generator '{}' has no text parameter '{}'", generator, key);
  return it->second;
}

std::string Params::canonical() const {
  std::string s = "generator=" + generator;
  for (const auto& [k, v] : num) s += fmt::format(";{}={:.17g}", k, v);
  for (const auto& [k, v] : str) s += fmt::format(";{}={}", k, v);
  return s;
}

void param_error(const Params& p, const std::string& key, const std::string& why) {
  auto it = p.num.find(key);
  const std::string val =
      it != p.num.end() ? fmt::format("{:g}", it->second) : (p.str.count(key) ? p.str.at(key) : std::string("?"));
  fail("mesh.{}.{} = {}: {}", p.generator, key, val, why);
}

void check_count(const Params& p, const std::string& key, double count, const std::string& how) {
  if (!(count <= kMostElements))
    param_error(p, key,
                fmt::format("about {:.2g} elements ({}), more than dspdem meshes ({:.0e}); a mistyped size or count?",
                            count, how, kMostElements));
}

void check_tet_count(const Params& p, const std::string& key, double volume, double h) {
  check_count(p, key, 4 * volume / (h * h * h), fmt::format("4 tetrahedra a size cubed over {:.3g} m^3", volume));
}

void check_graded_count(const Params& p, const std::string& key, double length, double fine, double coarse,
                        double reach) {
  // The integral of 4 / s(r)^3 over pi r dr, s = fine + (coarse - fine) r / reach, from 0 to
  // reach: 2 pi reach^2 / (fine coarse^2) a unit length.
  check_count(p, key, 2 * M_PI * length * reach * reach / (fine * coarse * coarse),
              fmt::format("4 tetrahedra a size cubed, the size growing from {:.3g} m at {:.3g} m of lines to {:.3g} m "
                          "at {:.3g} m from them",
                          fine, length, coarse, reach));
}

const std::vector<Generator>& registry() {
  static const std::vector<Generator> r = {
      {"brazilian_disc",
       "Disc (axis z, diameter D, thickness L, centred at the origin) between two flat loading plates above and "
       "below (load along y), each plate a separate body touching the disc (plates = 0: the disc alone, for rigid "
       "[[walls]] as plates). Volumes: disc, plate_top, plate_bottom. Surfaces: plate_top_load (top face of the top "
       "plate), plate_bottom_load (bottom face of the bottom plate). Curves: disc_top_line, disc_bottom_line (the "
       "loaded generator lines, meshed with nodes). Options: split_plane (the loaded diametral plane x = 0 as a mesh "
       "surface), band_width (volumes disc_band, the slab |x| < band_width/2, and disc_side), cap_height (volumes "
       "disc_caps, "
       "the two segments within cap_height of the loaded lines, and disc_core).",
       build_brazilian_disc, "disc", brazilian_disc_keys},
      {"galvez_beam",
       "Galvez et al. (1998) notched beam for mixed-mode fracture (four-point shear): beam along x (bottom at y = 0, "
       "mid-thickness at z = 0) with a notch at mid-span from the bottom. Volume: beam. Curves across the width: "
       "support_left, support_right (bottom), load_inner, load_outer (top). Curves: cmod_left, cmod_right (the two "
       "notch-mouth edges).",
       build_galvez_beam, "beam", galvez_beam_keys},
      {"murray_beam",
       "Murray et al. (2007) plain concrete beam for impact: box along x (centred at the origin, depth along y, width "
       "along z), structured hexahedra, split at the support and impactor lines. Volumes: beam, impactor_left, "
       "impactor_right, support_left, support_right (cylinders along z). Curves: midspan_bottom. Surfaces: "
       "beam_bottom, beam_top.",
       build_murray_beam, nullptr, murray_beam_keys},
      {"sphere_plate",
       "Sphere (centre at the origin) above a plate below it (-y), touching or with a gap. Volumes: sphere, plate. "
       "Surfaces: plate_top, plate_bottom.",
       build_sphere_plate, "sphere", sphere_plate_keys},
      {"packing",
       "Open-top rigid box (inner size lx x ly(height) x lz, floor at y = 0) made of five wall slabs, and N "
       "tetrahedral particles (one tet4 each, or 8^refine when refine > 0: small meshed polyhedra; randomly oriented, "
       "edge length uniform in [size_min, size_max], vertices jittered by 'irregularity') on a lattice inside and "
       "above it, without overlaps; deterministic for a seed. Volumes: container, particles (each particle is a "
       "connected component: use split_components = true).",
       build_packing, nullptr, packing_keys},
  };
  return r;
}

const Generator& find_generator(const std::string& name) {
  std::string names;
  for (const auto& g : registry()) {
    if (name == g.name) return g;
    names += (names.empty() ? "" : ", ") + std::string(g.name);
  }
  fail("unknown mesh generator '{}' (known: {})", name, names);
}

namespace {
// One gmsh model built by the generator; the mesh stays loaded in gmsh for writing.
Mesh build_once(const Generator& g, const Params& p) {
  gmsh::clear();
  gmsh::model::add(p.generator);
  gmsh::option::setNumber("General.NumThreads", 1);  // deterministic meshes
  gmsh::option::setNumber("Mesh.Algorithm3D", 1);    // Delaunay
  gmsh::option::setNumber("Mesh.MeshSizeFromCurvature", 0);
  gmsh::option::setNumber("Mesh.MeshSizeExtendFromBoundary", 1);
  g.build(p);
  std::string err;
  gmsh::logger::getLastError(err);
  DSPDEM_CHECK(err.empty(), "mesh generator '{}': gmsh reported: {}", p.generator, err);
  return mesh_from_gmsh_model("generator " + p.generator);
}

Index group_count(const Mesh& m, const std::string& group) {
  const Group* grp = m.find_group(group);
  DSPDEM_CHECK(grp != nullptr, "internal: generator has no group '{}'", group);
  Index n = 0;
  for (const auto& e : grp->elements) n += static_cast<Index>(e.size());
  return n;
}
}  // namespace

namespace {
std::mutex g_now_mutex;
std::string g_now;
}  // namespace

std::string meshing_now() {
  const std::lock_guard<std::mutex> lock(g_now_mutex);
  return g_now;
}

Mesh generate(const Params& p_in, const std::string& msh_path) {
  const Generator& g = find_generator(p_in.generator);
  struct Now {
    explicit Now(const Params& p) {
      const std::lock_guard<std::mutex> lock(g_now_mutex);
      const auto size = p.num.find("size");
      g_now = size == p.num.end() ? fmt::format("[mesh] generator = '{}'", p.generator)
                                  : fmt::format("[mesh] generator = '{}', mesh.{}.size = {:g} m", p.generator,
                                                p.generator, size->second);
    }
    ~Now() {
      const std::lock_guard<std::mutex> lock(g_now_mutex);
      g_now.clear();
    }
  } now(p_in);
  GmshSession session;
  Params p = p_in;
  Mesh m = build_once(g, p);
  // Element-count target: rescale the size by (count / target)^(1/3) until within 3 %.
  // gmsh's count jumps with the size, so keep the closest mesh and damp later steps.
  auto target = p.num.find("target_elements");
  if (target != p.num.end() && target->second > 0 && g.count_group) {
    const double want = target->second;
    double best_err = std::abs(group_count(m, g.count_group) / want - 1.0), best_size = p.num["size"];
    for (int it = 0; it < 12 && best_err > 0.03; ++it) {
      const double n = group_count(m, g.count_group);
      const double damp = it < 3 ? 1.0 : 0.5;
      p.num["size"] *= std::pow(n / want, damp / 3.0) * (it >= 6 ? 1.0 + 0.01 * ((it % 2) ? 1 : -1) : 1.0);
      m = build_once(g, p);
      const double err = std::abs(group_count(m, g.count_group) / want - 1.0);
      if (err < best_err) best_err = err, best_size = p.num["size"];
    }
    if (p.num["size"] != best_size) {
      p.num["size"] = best_size;
      m = build_once(g, p);
    }
    if (best_err > 0.03)
      log::warn("mesh generator '{}': target_elements = {} reached only within {:.1f} %", p.generator, want,
                100 * best_err);
    log::info("  mesh: {} elements in '{}' for target_elements = {} (size {:.4g} m)", group_count(m, g.count_group),
              g.count_group, want, p.num["size"]);
  }
  if (!msh_path.empty()) {
    gmsh::option::setNumber("Mesh.MshFileVersion", 4.1);
    gmsh::option::setNumber("Mesh.Binary", 0);
    // A name of this process's own: runs started together (a study, parallel jobs) may
    // generate the same mesh at once; each renames its complete file into place.
    const std::string tmp = fmt::format("{}.{}.tmp.msh", msh_path, static_cast<long>(::getpid()));
    // Held locked while gmsh writes it (gmsh truncates the same file): a run that finds it
    // unlocked knows its writer has gone, whatever host or PID namespace it ran in.
    const int fd = ::open(tmp.c_str(), O_CREAT | O_RDWR | O_CLOEXEC, 0644);
    if (fd >= 0) (void)::flock(fd, LOCK_EX);
    try {
      gmsh::write(tmp);
    } catch (...) {
      std::error_code ec;
      fs::remove(tmp, ec);
      if (fd >= 0) ::close(fd);
      throw;
    }
    fs::rename(tmp, msh_path);
    if (fd >= 0) ::close(fd);
  }
  return m;
}

namespace {
std::uint64_t fnv1a(const std::string& s) {
  std::uint64_t h = 1469598103934665603ull;
  for (unsigned char c : s) h = (h ^ c) * 1099511628211ull;
  return h;
}
// Bump when a generator's output changes for the same parameters.
constexpr const char* kGeneratorsVersion = "1";
}  // namespace

std::string default_cache_dir() {
  if (const char* d = std::getenv("DSPDEM_MESH_CACHE")) return d;
  if (const char* x = std::getenv("XDG_CACHE_HOME")) return (fs::path(x) / "dspdem/meshes").string();
  if (const char* h = std::getenv("HOME")) return (fs::path(h) / ".cache/dspdem/meshes").string();
  return (fs::temp_directory_path() / "dspdem-meshes").string();
}

namespace {
// A process killed while gmsh wrote into the cache (a signal during the set-up exits at once,
// SIGKILL, a power cut) leaves its NAME.PID.tmp.msh behind; nothing else would ever remove it.
// The next run that meshes into the folder removes those no writer holds locked: a writer
// holds its file's lock until it has renamed it into place (its PID says nothing across
// hosts sharing a home folder, or across containers), and the lock ends with its process.
void remove_abandoned_writes(const fs::path& cache_dir) {
  std::error_code ec;
  for (fs::directory_iterator it(cache_dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    constexpr std::string_view tail = ".tmp.msh";
    if (name.size() <= tail.size() || name.compare(name.size() - tail.size(), tail.size(), tail) != 0) continue;
    const int fd = ::open(it->path().c_str(), O_RDWR | O_CLOEXEC);
    if (fd < 0) continue;
    if (::flock(fd, LOCK_EX | LOCK_NB) == 0) {
      std::error_code rm;
      fs::remove(it->path(), rm);
    }
    ::close(fd);
  }
}
}  // namespace

Mesh load_or_generate(const Params& p, const std::string& cache_dir, bool* cached, std::string* path) {
  const std::string key = p.canonical() + ";gmsh=" + GMSH_API_VERSION + ";generators=" + kGeneratorsVersion;
  const fs::path file = fs::path(cache_dir) / fmt::format("{}-{:016x}.msh", p.generator, fnv1a(key));
  if (path) *path = file.string();
  if (fs::exists(file)) {
    try {
      Mesh m = read_gmsh(file.string());
      if (cached) *cached = true;
      return m;
    } catch (const Error& e) {
      log::warn("cached mesh '{}' unreadable ({}); generating it again", file.string(), e.what());
    }
  }
  std::error_code ec;
  fs::create_directories(cache_dir, ec);
  if (cached) *cached = false;
  if (ec) {
    log::warn("mesh cache folder '{}' cannot be created ({}); not caching", cache_dir, ec.message());
    return generate(p);
  }
  remove_abandoned_writes(cache_dir);
  // The run gets the mesh as read back from the file, exactly as every later (cached) run
  // will: the in-memory mesh carries more digits than the file, and the same input must give
  // the same result whether the cache was warm or not.
  generate(p, file.string());
  return read_gmsh(file.string());
}

void add_group(int dim, const std::vector<int>& tags, const std::string& name) {
  DSPDEM_CHECK(!tags.empty(), "internal: physical group '{}' would be empty", name);
  const int t = gmsh::model::addPhysicalGroup(dim, tags);
  gmsh::model::setPhysicalName(dim, t, name);
}

std::vector<int> entities_in_box(int dim, double x0, double y0, double z0, double x1, double y1, double z1,
                                 double eps) {
  gmsh::vectorpair dt;
  gmsh::model::getEntitiesInBoundingBox(x0 - eps, y0 - eps, z0 - eps, x1 + eps, y1 + eps, z1 + eps, dt, dim);
  std::vector<int> tags;
  for (auto [d, t] : dt) tags.push_back(t);
  return tags;
}

void set_volume_size(const std::vector<int>& volumes, double size) {
  gmsh::vectorpair in, pts;
  for (int v : volumes) in.emplace_back(3, v);
  gmsh::model::getBoundary(in, pts, false, false, true);
  std::vector<std::pair<int, int>> points;
  for (auto [d, t] : pts)
    if (d == 0) points.emplace_back(d, t);
  gmsh::model::mesh::setSize(points, size);
}

void set_graded_size(int distance, double size_min, double size_max, double dist_max, const std::vector<int>& volumes) {
  namespace field = gmsh::model::mesh::field;
  const int threshold = 100, restrict = 101;
  field::add("Threshold", threshold);
  field::setNumber(threshold, "InField", distance);
  field::setNumber(threshold, "SizeMin", size_min), field::setNumber(threshold, "SizeMax", size_max);
  field::setNumber(threshold, "DistMin", 0), field::setNumber(threshold, "DistMax", dist_max);
  // Restricted to the volumes, their faces and curves (a refined line or point on the
  // boundary must be refined there first): meshed plates beside them keep their own size.
  field::add("Restrict", restrict);
  field::setNumber(restrict, "InField", threshold);
  gmsh::vectorpair vd, faces, curves;
  for (int v : volumes) vd.emplace_back(3, v);
  gmsh::model::getBoundary(vd, faces, false, false, false);
  gmsh::model::getBoundary(faces, curves, false, false, false);
  std::vector<double> fl, cl;
  for (auto [dim, t] : faces) fl.push_back(t);
  for (auto [dim, t] : curves) cl.push_back(t);
  field::setNumbers(restrict, "VolumesList", std::vector<double>(volumes.begin(), volumes.end()));
  field::setNumbers(restrict, "SurfacesList", fl);
  field::setNumbers(restrict, "CurvesList", cl);
  field::setAsBackgroundMesh(restrict);
}

}  // namespace dspdem::meshing
