#include "scenes/registry.hpp"

#include "core/error.hpp"
#include "scenes/brazilian_disc/scene.hpp"
#include "scenes/galvez_beam/scene.hpp"
#include "scenes/murray_beam/scene.hpp"
#include "scenes/packing/scene.hpp"
#include "scenes/sphere_impact/scene.hpp"

namespace dspdem::scenes {

const std::vector<Scene>& all() {
  static const std::vector<Scene> s = {
      {"packing", "packing", "tetrahedra falling into a rigid box and coming to rest (paper 2.1)", packing_report},
      {"brazilian_disc", "brazilian_disc", "Brazilian disc split between two plates (paper 2.2)",
       brazilian_disc_report},
      {"galvez_beam", "galvez_beam", "Galvez mixed-mode notched beam (paper 2.3)", galvez_beam_report},
      {"murray_beam", "murray_beam", "plain concrete beam struck by two impactors (paper 2.4)", murray_beam_report},
      {"sphere_impact", "sphere_plate", "rock sphere striking a rigid plate, a sweep over speeds (paper 2.5)",
       sphere_impact_report},
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
