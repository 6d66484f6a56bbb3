#include "app/mesh_command.hpp"

#include <filesystem>
#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "core/file.hpp"
#include "core/log.hpp"
#include "core/timer.hpp"
#include "io/staging.hpp"
#include "mesh/gmsh_reader.hpp"
#include "meshing/generator.hpp"
#include "meshing/quality.hpp"
#include "run/case_mesh.hpp"

namespace dspdem {

int mesh_command(const CaseConfig& c, const std::string& out_dir) {
  namespace fs = std::filesystem;
  Timer t;
  std::error_code ec;
  DSPDEM_CHECK(!fs::exists(out_dir, ec) || fs::is_directory(out_dir, ec),
               "mesh --out {}: a file is there, not a folder: give --out a folder", out_dir);
  fs::create_directories(out_dir, ec);
  DSPDEM_CHECK(!ec, "mesh --out {}: cannot make the folder: {}", out_dir, ec.message());
  const std::string msh = (fs::path(out_dir) / (c.name + ".msh")).string();
  // Written over its own source, a .msh would be lost (gmsh writes what it read as 4.1, and
  // without the elements outside every physical group).
  DSPDEM_CHECK(c.mesh_file.empty() || !fs::exists(msh, ec) || !fs::equivalent(msh, c.mesh_file, ec),
               "mesh: {} is the case's own mesh file, which writing the mesh there would replace: give --out another "
               "folder",
               msh);
  // quality.json is replaced whole: only one that dspdem mesh wrote (a file of that name from
  // elsewhere was lost).
  const fs::path quality = fs::path(out_dir) / "quality.json";
  if (fs::exists(quality, ec)) {
    const auto old = nlohmann::json::parse(read_file(quality.string(), "quality file"), nullptr, false);
    DSPDEM_CHECK(old.is_object() && old.contains("quality_measure") && old.contains("slivers"),
                 "mesh: {} is not a quality.json that dspdem mesh wrote, which writing the mesh's would replace: "
                 "give --out another folder",
                 quality.string());
  }
  Mesh m;
  std::string source;
  if (c.mesh_generator.empty()) {
    // The mesh gmsh made or read, not the source file: a .geo copied under the name .msh
    // was its script, which no mesh reader takes.
    m = read_gmsh(c.mesh_file, msh, c.mesh_time_limit);
    source = c.mesh_file;
  } else {
    // Inverted elements are refused inside (check_element_volumes); nothing is written then.
    m = meshing::generate(generator_params(c), msh);
    source = "generator " + c.mesh_generator;
  }
  const meshing::Quality q = meshing::mesh_quality(m);
  std::string params;
  for (const auto& [k, v] : c.mesh_num) params += fmt::format("{}\"{}\": {:.10g}", params.empty() ? "" : ", ", k, v);
  const std::string extra =
      fmt::format("  \"case\": \"{}\",\n  \"source\": \"{}\",\n  \"parameters\": {{{}}},\n  \"nodes\": {},\n", c.name,
                  source, params, m.n_nodes());
  write_file_atomic((fs::path(out_dir) / "quality.json").string(), meshing::quality_json(q, extra));
  log::info("dspdem mesh: case '{}': {} nodes, {} tet4, {} hex8 in {:.2f} s", c.name, m.n_nodes(), q.n_tet4, q.n_hex8,
            t.seconds());
  for (const auto& [g, n] : q.elements_per_group) log::info("  {}: {} elements", g, n);
  log::info("  dihedral angles {:.1f} to {:.1f} deg; quality min {:.3f}, 1st percentile {:.3f}, mean {:.3f}",
            q.min_dihedral_deg, q.max_dihedral_deg, q.quality_min, q.quality_p01, q.quality_mean);
  if (q.n_slivers > 0)
    log::warn("{} sliver tetrahedra (gamma < {}) in the mesh of case '{}'", q.n_slivers, q.sliver_threshold, c.name);
  log::info("  wrote {} and {}/quality.json", msh, out_dir);
  return 0;
}

}  // namespace dspdem
