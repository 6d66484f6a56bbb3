#include "scenes/registry.hpp"

#include "core/error.hpp"
#include "scenes/brazilian_disc/scene.hpp"
#include "scenes/galvez_beam/scene.hpp"
#include "scenes/murray_beam/scene.hpp"
#include "scenes/packing/scene.hpp"
#include "scenes/sphere_impact/scene.hpp"

namespace dspdem::scenes {

const std::vector<Scene>& all() {
  // quick_args: the CI-sized run of `dspdem figures --quick` (each about a minute on 2 cores
  // or less). The scene's tests read that very run (tests/support/quick_report.hpp): a change
  // here changes what they check.
  static const std::vector<Scene> s = {
      {"packing",
       "packing",
       "tetrahedra falling into a rigid box and coming to rest (paper 2.1)",
       packing_report,
       "cases/packing.toml",
       {"--set", "mesh.packing.count=200", "--set", "time.end=3.0"}},
      {"brazilian_disc",
       "brazilian_disc",
       "Brazilian disc split between two plates (paper 2.2)",
       brazilian_disc_report,
       "cases/brazilian_disc.toml",
       {"--no-stress-check", "--set", "mesh.brazilian_disc.size=0.02"}},
      {"galvez_beam",
       "galvez_beam",
       "Galvez mixed-mode notched beam (paper 2.3)",
       galvez_beam_report,
       "cases/galvez_beam.toml",
       {"--set", "time.stop_fraction=0.5", "--set", "time.stop_delay=5e-4"}},
      {"murray_beam",
       "murray_beam",
       "plain concrete beam struck by two impactors (paper 2.4)",
       murray_beam_report,
       "cases/murray_beam.toml",
       {"--set", "mesh.murray_beam.nx=34", "--set", "mesh.murray_beam.ny=3", "--set", "mesh.murray_beam.nz=5", "--set",
        "time.end=4e-3"}},
      {"sphere_impact",
       "sphere_plate",
       "rock sphere striking a rigid plate, a sweep over speeds (paper 2.5)",
       sphere_impact_report,
       "cases/sphere_impact.toml",
       // Its frames at a quarter of the pixels: drawing 3 x 3 views of 155 frames at 1280 x 720
       // was 170 of its 200 s in CI (llvmpipe's time goes with the pixels: one speed's 135
       // images and animations in 27 s, 8 s at 640 x 360, 2-core 2.0 GHz Xeon). The montage,
       // which its test compares, has its own panel size.
       {"--set", "mesh.sphere_plate.size=0.04", "--speeds", "2.5,7.5,20", "--set", "render.width=640", "--set",
        "render.height=360"},
       true},
  };
  return s;
}

const Scene& of_case(const CaseConfig& c) {
  std::string known;
  for (const auto& s : all()) known += (known.empty() ? "" : ", ") + s.name;
  if (!c.scene.empty()) {
    for (const auto& s : all())
      if (s.name == c.scene) return s;
    fail("{}: [case] scene = \"{}\" is not a scene dspdem knows (known: {})", c.path, c.scene, known);
  }
  for (const auto& s : all())
    if (!s.generator.empty() && s.generator == c.mesh_generator) return s;
  fail(
      "{}: dspdem report needs a benchmark scene: set [case] scene (known: {}); this case's mesh ({}) has no scene of "
      "its own",
      c.path, known, c.mesh_generator.empty() ? c.mesh_file : c.mesh_generator);
}

}  // namespace dspdem::scenes
