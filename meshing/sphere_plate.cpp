// Rock sphere above a plate (paper section 2.5).
#include <gmsh.h>

#include "meshing/generator.hpp"

namespace dspdem::meshing {

void build_sphere_plate(const Params& p) {
  namespace occ = gmsh::model::occ;
  const double D = p["diameter"], h = p["size"], gap = p["gap"];
  const double pw = p["plate_width"], pt = p["plate_thickness"], ph = p["plate_size"];
  if (h > 0.25 * D) param_error(p, "size", "larger than a quarter of the diameter: the sphere cannot be meshed");
  if (pw < D) param_error(p, "plate_width", "narrower than the sphere");
  const double ytop = -D / 2 - gap;
  const int sphere = occ::addSphere(0, 0, 0, D / 2);
  const int plate = occ::addBox(-pw / 2, ytop - pt, -pw / 2, pw, pt, pw);
  occ::synchronize();
  set_volume_size({sphere}, h);
  set_volume_size({plate}, ph);
  gmsh::model::mesh::generate(3);
  add_group(3, {sphere}, "sphere");
  add_group(3, {plate}, "plate");
  add_group(2, entities_in_box(2, -pw / 2, ytop, -pw / 2, pw / 2, ytop, pw / 2), "plate_top");
  add_group(2, entities_in_box(2, -pw / 2, ytop - pt, -pw / 2, pw / 2, ytop - pt, pw / 2), "plate_bottom");
}

}  // namespace dspdem::meshing
