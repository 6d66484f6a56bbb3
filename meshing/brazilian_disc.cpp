// Brazilian disc between two flat loading plates (paper section 2.2).
#include <gmsh.h>

#include <string>

#include "meshing/generator.hpp"

namespace dspdem::meshing {

void build_brazilian_disc(const Params& p) {
  namespace occ = gmsh::model::occ;
  const double D = p["diameter"], L = p["thickness"], h = p["size"];
  const double pw = p["plate_width"], pt = p["plate_thickness"], ph = p["plate_size"];
  if (h > 0.5 * L) param_error(p, "size", "larger than half the disc thickness: the disc would be one element thick");
  if (pw > D) param_error(p, "plate_width", "wider than the disc diameter");
  if (ph > pt * 2 && ph > pw) param_error(p, "plate_size", "larger than the plate");
  const bool plates = p["plates"] != 0;
  int disc = occ::addCylinder(0, 0, -L / 2, 0, 0, L, D / 2);
  // The loaded generator lines (x = 0, y = +-D/2) are imprinted on the curved face (which
  // they split in two) so the faceted disc has nodes exactly where flat plates first touch
  // it: the load starts at zero approach and acts on a line, as in the analytic solution.
  const int p0 = occ::addPoint(0, D / 2, -L / 2), p1 = occ::addPoint(0, D / 2, L / 2);
  const int p2 = occ::addPoint(0, -D / 2, -L / 2), p3 = occ::addPoint(0, -D / 2, L / 2);
  int l_top = occ::addLine(p0, p1), l_bot = occ::addLine(p2, p3);
  {
    gmsh::vectorpair out;
    std::vector<gmsh::vectorpair> map;
    occ::fragment({{3, disc}}, {{1, l_top}, {1, l_bot}}, out, map);
    disc = map[0].at(0).second;
    l_top = map[1].at(0).second, l_bot = map[2].at(0).second;
  }
  int top = -1, bot = -1;
  // Plates span the disc thickness and touch it along the top and bottom generator lines.
  if (plates) {
    top = occ::addBox(-pw / 2, D / 2, -L / 2, pw, pt, L);
    bot = occ::addBox(-pw / 2, -D / 2 - pt, -L / 2, pw, pt, L);
  }
  occ::synchronize();
  set_volume_size({disc}, h);
  if (plates) set_volume_size({top, bot}, ph);
  gmsh::model::mesh::generate(3);
  add_group(3, {disc}, "disc");
  add_group(1, {l_top}, "disc_top_line");
  add_group(1, {l_bot}, "disc_bottom_line");
  if (!plates) return;
  add_group(3, {top}, "plate_top");
  add_group(3, {bot}, "plate_bottom");
  add_group(2, entities_in_box(2, -pw / 2, D / 2 + pt, -L / 2, pw / 2, D / 2 + pt, L / 2), "plate_top_load");
  add_group(2, entities_in_box(2, -pw / 2, -D / 2 - pt, -L / 2, pw / 2, -D / 2 - pt, L / 2), "plate_bottom_load");
}

}  // namespace dspdem::meshing
