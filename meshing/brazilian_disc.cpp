// Brazilian disc between two flat loading plates (paper section 2.2).
#include <gmsh.h>

#include "meshing/generator.hpp"

namespace dspdem::meshing {

void build_brazilian_disc(const Params& p) {
  namespace occ = gmsh::model::occ;
  const double D = p["diameter"], L = p["thickness"], h = p["size"];
  const double pw = p["plate_width"], pt = p["plate_thickness"], ph = p["plate_size"];
  if (h > 0.5 * L) param_error(p, "size", "larger than half the disc thickness: the disc would be one element thick");
  if (pw > D) param_error(p, "plate_width", "wider than the disc diameter");
  if (ph > pt * 2 && ph > pw) param_error(p, "plate_size", "larger than the plate");
  const int disc = occ::addCylinder(0, 0, -L / 2, 0, 0, L, D / 2);
  // Plates span the disc thickness and touch it along the top and bottom generator lines.
  const int top = occ::addBox(-pw / 2, D / 2, -L / 2, pw, pt, L);
  const int bot = occ::addBox(-pw / 2, -D / 2 - pt, -L / 2, pw, pt, L);
  occ::synchronize();
  set_volume_size({disc}, h);
  set_volume_size({top, bot}, ph);
  gmsh::model::mesh::generate(3);
  add_group(3, {disc}, "disc");
  add_group(3, {top}, "plate_top");
  add_group(3, {bot}, "plate_bottom");
  add_group(2, entities_in_box(2, -pw / 2, D / 2 + pt, -L / 2, pw / 2, D / 2 + pt, L / 2), "plate_top_load");
  add_group(2, entities_in_box(2, -pw / 2, -D / 2 - pt, -L / 2, pw / 2, -D / 2 - pt, L / 2), "plate_bottom_load");
}

}  // namespace dspdem::meshing
