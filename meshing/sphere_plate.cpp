// Rock sphere above a plate (paper section 2.5).
#include <gmsh.h>

#include <limits>

#include "meshing/generator.hpp"

namespace dspdem::meshing {

void build_sphere_plate(const Params& p) {
  namespace occ = gmsh::model::occ;
  const double D = p["diameter"], h = p["size"], gap = p["gap"];
  const double pw = p["plate_width"], pt = p["plate_thickness"], ph = p["plate_size"];
  if (h > 0.25 * D) param_error(p, "size", "larger than a quarter of the diameter: the sphere cannot be meshed");
  if (pw < D) param_error(p, "plate_width", "narrower than the sphere");
  const double ytop = -D / 2 - gap;
  // The plate is meshed only when asked for: the paper's plate is rigid, a [[walls]] plane.
  const bool meshed_plate = p["plate"] != 0;
  const int sphere = occ::addSphere(0, 0, 0, D / 2);
  const int plate = meshed_plate ? occ::addBox(-pw / 2, ytop - pt, -pw / 2, pw, pt, pw) : -1;
  occ::synchronize();
  set_volume_size({sphere}, h);
  if (meshed_plate) set_volume_size({plate}, ph);
  gmsh::model::mesh::generate(3);
  add_group(3, {sphere}, "sphere");
  if (!meshed_plate) return;
  add_group(3, {plate}, "plate");
  add_group(2, entities_in_box(2, -pw / 2, ytop, -pw / 2, pw / 2, ytop, pw / 2), "plate_top");
  add_group(2, entities_in_box(2, -pw / 2, ytop - pt, -pw / 2, pw / 2, ytop - pt, pw / 2), "plate_bottom");
}

// Parameters of [mesh.sphere_plate], declared beside the generator that uses them (the case reader
// validates them, `dspdem keys` documents them).
// clang-format off
const std::vector<schema::Key>& sphere_plate_keys() {
  using T = schema::Type;
  constexpr double inf = std::numeric_limits<double>::infinity();
  static const std::vector<schema::Key> k = {
    {"mesh.sphere_plate", "diameter", T::Real, "0.2", 0, inf, true, false, "m", nullptr, "Sphere diameter [S]."},
    {"mesh.sphere_plate", "target_elements", T::Int, "0", 0, 1e8, false, false, "", nullptr, "Element count wanted in the sphere: when > 0 the size is rescaled (a few gmsh runs) until the count is within 3 %."},
    {"mesh.sphere_plate", "size", T::Real, "0.0168", 0, inf, true, false, "m", nullptr, "Element size in the sphere; the default gives about the paper's 4539 tetrahedra."},
    {"mesh.sphere_plate", "gap", T::Real, "0.0", 0, inf, false, false, "m", nullptr, "Gap between the sphere and the plate."},
    {"mesh.sphere_plate", "plate", T::Int, "1", 0, 1, false, false, "", nullptr, "1: mesh the steel plate under the sphere (groups plate, plate_top, plate_bottom); 0: the sphere alone (strike a rigid [[walls]] plane, as the paper's plate)."},
    {"mesh.sphere_plate", "plate_width", T::Real, "0.3", 0, inf, true, false, "m", nullptr, "Plate side (square, in x and z)."},
    {"mesh.sphere_plate", "plate_thickness", T::Real, "0.02", 0, inf, true, false, "m", nullptr, "Plate thickness."},
    {"mesh.sphere_plate", "plate_size", T::Real, "0.03", 0, inf, true, false, "m", nullptr, "Element size in the plate."},
  };
  return k;
}
// clang-format on

}  // namespace dspdem::meshing
