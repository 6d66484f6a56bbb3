#include "scenes/brazilian_disc/loading.hpp"

#include <fmt/format.h>

namespace dspdem {

bool loads_through_jaws(const CaseConfig& c) {
  bool jaws = !c.walls.empty();
  for (const auto& w : c.walls) jaws = jaws && w.wall.type == contact::Wall::Type::Jaw;
  return jaws;
}

std::vector<std::string> flat_plate_overrides(const CaseConfig& c) {
  const Real R = 0.5 * c.mesh_num.at("diameter");
  std::vector<std::string> sets;
  for (std::size_t i = 0; i < c.walls.size(); ++i) {
    const contact::Wall& wl = c.walls[i].wall;
    const Real side = (wl.centre(1) + wl.radius * wl.normal0(1)) > 0 ? 1.0 : -1.0;  // where the jaw's face is
    const Vec3& v = wl.velocity_target;
    sets.push_back(fmt::format(
        "walls.{}={{name = \"{}\", type = \"box\", point = [0.0, {:.17g}, 0.0], half_size = [0.03, 0.01, 0.06], "
        "velocity = [{:.17g}, {:.17g}, {:.17g}], ramp = {:.17g}{}{}}}",
        i, wl.name, side * (R + 0.01), v(0), v(1), v(2), wl.ramp,
        wl.mu >= 0 ? fmt::format(", friction = {:.17g}", wl.mu) : "",
        wl.kn >= 0 ? fmt::format(", kn = {:.17g}", wl.kn) : ""));
  }
  return sets;
}

std::vector<std::string> curved_jaw_overrides(const CaseConfig& c) {
  const Real R = 0.5 * c.mesh_num.at("diameter"), Rj = 1.5 * R;
  std::vector<std::string> sets;
  for (std::size_t i = 0; i < c.walls.size(); ++i) {
    const Real side = c.walls[i].wall.centre(1) > 0 ? 1.0 : -1.0;
    const std::string w = fmt::format("walls.{}.", i);
    sets.insert(sets.end(),
                {override_of(w + "type", std::string("jaw")), override_of(w + "point", Vec3(0, side * (R - Rj), 0)),
                 override_of(w + "normal", Vec3(0, side, 0)), override_of(w + "radius", Rj),
                 override_of(w + "half_size", Vec3(0, 0, 0))});
  }
  return sets;
}

}  // namespace dspdem
