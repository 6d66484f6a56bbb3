// Brazilian disc between two flat loading plates (paper section 2.2).
#include <fmt/format.h>
#include <gmsh.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "meshing/generator.hpp"

namespace dspdem::meshing {

void build_brazilian_disc(const Params& p) {
  namespace occ = gmsh::model::occ;
  const double D = p["diameter"], L = p["thickness"], h = p["size"];
  const double pw = p["plate_width"], pt = p["plate_thickness"], ph = p["plate_size"];
  if (h > 0.5 * L) param_error(p, "size", "larger than half the disc thickness: the disc would be one element thick");
  if (pw > D) param_error(p, "plate_width", "wider than the disc diameter");
  if (ph > pt * 2 && ph > pw) param_error(p, "plate_size", "larger than the plate");
  const bool plates = p["plates"] != 0, split = p["split_plane"] != 0;
  check_tet_count(p, "size", 0.25 * M_PI * D * D * L, h);
  if (plates) check_tet_count(p, "plate_size", 2 * pw * pt * L, ph);
  const double band = p["band_width"];
  if (band >= D) param_error(p, "band_width", "not narrower than the disc diameter");
  const double cap = p["cap_height"];
  if (cap >= D / 2) param_error(p, "cap_height", "not smaller than the disc radius");
  int disc = occ::addCylinder(0, 0, -L / 2, 0, 0, L, D / 2);
  // The loaded generator lines (x = 0, y = +-D/2) are mesh curves, so the faceted disc has
  // nodes exactly where flat plates first touch it: the load starts at zero approach and
  // acts on a line, as in the analytic solution. With split_plane the whole plane x = 0 is
  // cut in (it holds both lines); band planes x = +-band/2 cut the disc into slabs. Cutting
  // planes are rectangles larger than the disc; their parts outside it are removed.
  gmsh::vectorpair tools;
  auto add_plane = [&](double x) {
    const int r = occ::addRectangle(-0.6 * L, -0.6 * D, 0, 1.2 * L, 1.2 * D);
    occ::rotate({{2, r}}, 0, 0, 0, 0, 1, 0, M_PI / 2);  // (x, y, 0) -> (0, y, -x): the plane x = 0
    occ::translate({{2, r}}, x, 0, 0);
    tools.emplace_back(2, r);
  };
  if (split) {
    add_plane(0);
  } else {
    const int p0 = occ::addPoint(0, D / 2, -L / 2), p1 = occ::addPoint(0, D / 2, L / 2);
    const int p2 = occ::addPoint(0, -D / 2, -L / 2), p3 = occ::addPoint(0, -D / 2, L / 2);
    tools.emplace_back(1, occ::addLine(p0, p1)), tools.emplace_back(1, occ::addLine(p2, p3));
  }
  if (band > 0) add_plane(-band / 2), add_plane(band / 2);
  // Cap planes y = +-(D/2 - cap): the bearing zones under the loads as volumes of their own.
  auto add_cap_plane = [&](double y) {
    const int r = occ::addRectangle(-0.6 * D, -0.6 * L, 0, 1.2 * D, 1.2 * L);
    occ::rotate({{2, r}}, 0, 0, 0, 1, 0, 0, M_PI / 2);  // (x, y, 0) -> (x, 0, y): the plane y = 0
    occ::translate({{2, r}}, 0, y, 0);
    tools.emplace_back(2, r);
  };
  if (cap > 0) add_cap_plane(D / 2 - cap), add_cap_plane(-(D / 2 - cap));
  {
    gmsh::vectorpair out;
    std::vector<gmsh::vectorpair> map;
    occ::fragment({{3, disc}}, tools, out, map);
  }
  occ::synchronize();
  gmsh::vectorpair surfaces, outside;
  gmsh::model::getEntities(surfaces, 2);
  for (auto [dim, s] : surfaces) {
    std::vector<int> up, down;
    gmsh::model::getAdjacencies(2, s, up, down);
    if (up.empty()) outside.emplace_back(2, s);
  }
  occ::remove(outside, true);
  occ::synchronize();
  std::vector<int> vols, band_vols, side_vols, core_vols, cap_vols;
  {
    gmsh::vectorpair v;
    gmsh::model::getEntities(v, 3);
    for (auto [dim, t] : v) {
      double cx, cy, cz;
      occ::getCenterOfMass(3, t, cx, cy, cz);
      vols.push_back(t);
      (std::abs(cx) < band / 2 ? band_vols : side_vols).push_back(t);
      (std::abs(cy) < D / 2 - cap ? core_vols : cap_vols).push_back(t);
    }
  }
  const std::vector<int> l_top = entities_in_box(1, 0, D / 2, -L / 2, 0, D / 2, L / 2, 1e-3 * D);
  const std::vector<int> l_bot = entities_in_box(1, 0, -D / 2, -L / 2, 0, -D / 2, L / 2, 1e-3 * D);
  if (l_top.size() != 1 || l_bot.size() != 1)
    throw Error(fmt::format("brazilian_disc: the loaded generator lines were not imprinted ({} and {} curves found)",
                            l_top.size(), l_bot.size()));
  int top = -1, bot = -1;
  // Plates span the disc thickness and touch it along the top and bottom generator lines.
  if (plates) {
    top = occ::addBox(-pw / 2, D / 2, -L / 2, pw, pt, L);
    bot = occ::addBox(-pw / 2, -D / 2 - pt, -L / 2, pw, pt, L);
  }
  occ::synchronize();
  set_volume_size(vols, h);
  if (const double hl = p["load_size"]; hl > 0) {
    if (hl > h) param_error(p, "load_size", "larger than size: it refines the mesh at the loaded lines");
    check_graded_count(p, "load_size", 2 * L, hl, h, D / 4);
    namespace field = gmsh::model::mesh::field;
    field::add("Distance", 1);
    field::setNumbers(1, "CurvesList", {static_cast<double>(l_top[0]), static_cast<double>(l_bot[0])});
    field::setNumber(1, "NumPointsPerCurve", std::ceil(L / hl) * 4 + 1);
    set_graded_size(1, hl, h, D / 4, vols);
  }
  if (plates) set_volume_size({top, bot}, ph);
  gmsh::model::mesh::generate(3);
  add_group(3, vols, "disc");
  if (band > 0) add_group(3, band_vols, "disc_band"), add_group(3, side_vols, "disc_side");
  if (cap > 0) add_group(3, core_vols, "disc_core"), add_group(3, cap_vols, "disc_caps");
  add_group(1, l_top, "disc_top_line");
  add_group(1, l_bot, "disc_bottom_line");
  if (!plates) return;
  add_group(3, {top}, "plate_top");
  add_group(3, {bot}, "plate_bottom");
  add_group(2, entities_in_box(2, -pw / 2, D / 2 + pt, -L / 2, pw / 2, D / 2 + pt, L / 2), "plate_top_load");
  add_group(2, entities_in_box(2, -pw / 2, -D / 2 - pt, -L / 2, pw / 2, -D / 2 - pt, L / 2), "plate_bottom_load");
}

// Parameters of [mesh.brazilian_disc], declared beside the generator that uses them (the case reader
// validates them, `dspdem keys` documents them).
// clang-format off
const std::vector<schema::Key>& brazilian_disc_keys() {
  using T = schema::Type;
  constexpr double inf = std::numeric_limits<double>::infinity();
  static const std::vector<schema::Key> k = {
    {"mesh.brazilian_disc", "diameter", T::Real, "0.1427", 0, inf, true, false, "m", nullptr, "Disc diameter D. [NF] in the paper; chosen so that D L = 2 P/(pi sigma) = 0.0101759 m^2 from its 40.6 kN and 2.54 MPa, with L/D = 0.5 (thickness = radius, the ISRM suggestion)."},
    {"mesh.brazilian_disc", "thickness", T::Real, "0.0713", 0, inf, true, false, "m", nullptr, "Disc thickness L (along z). See diameter."},
    {"mesh.brazilian_disc", "target_elements", T::Int, "0", 0, 1e8, false, false, "", nullptr, "Element count wanted in the disc: when > 0 the size is rescaled (a few gmsh runs) until the count is within 3 %."},
    {"mesh.brazilian_disc", "size", T::Real, "0.0076", 0, inf, true, false, "m", nullptr, "Target element size in the disc; the default gives about the paper's 12335 tetrahedra."},
    {"mesh.brazilian_disc", "plates", T::Int, "1", 0, 1, false, false, "", nullptr, "1: mesh the two steel plates as bodies; 0: the disc alone (load it with rigid [[walls]])."},
    {"mesh.brazilian_disc", "load_size", T::Real, "0", 0, inf, false, false, "m", nullptr, "> 0: element size at the loaded generator lines, growing linearly to size at a distance D/4 from them, so the concentrated load's field (singular at the lines) is resolved; 0: size everywhere."},
    {"mesh.brazilian_disc", "split_plane", T::Int, "0", 0, 1, false, false, "", nullptr, "1: the loaded diametral plane (x = 0) is a surface of the mesh, so element faces lie on the crack path that the analytic solution predicts; 0: the mesh is unstructured across it and a facet crack must zigzag."},
    {"mesh.brazilian_disc", "cap_height", T::Real, "0", 0, inf, false, false, "m", nullptr, "> 0: planes y = +-(D/2 - cap_height) split the disc into the volume groups disc_caps (the two bearing zones under the loads) and disc_core; the group disc holds both. With fracture = \"groups\" and fracture_groups = [\"disc_core\"] the bearing zones stay intact, as the curved jaws and bearing strips of the standard tests intend: the splitting strength is read from the crack at the centre, not from crushing under a load that a faceted mesh concentrates on one element."},
    {"mesh.brazilian_disc", "band_width", T::Real, "0", 0, inf, false, false, "m", nullptr, "> 0: planes x = +-band_width/2 split the disc into the volume group disc_band (the central slab) and disc_side; the group disc holds both. With fracture = \"groups\" and fracture_groups = [\"disc_band\"] joints are made only in the band."},
    {"mesh.brazilian_disc", "plate_width", T::Real, "0.06", 0, inf, true, false, "m", nullptr, "Plate extent along x (the plates span the disc thickness along z)."},
    {"mesh.brazilian_disc", "plate_thickness", T::Real, "0.02", 0, inf, true, false, "m", nullptr, "Plate thickness along y."},
    {"mesh.brazilian_disc", "plate_size", T::Real, "0.01", 0, inf, true, false, "m", nullptr, "Element size in the plates."},
  };
  return k;
}
// clang-format on

}  // namespace dspdem::meshing
