// Galvez et al. (1998) notched beam for mixed-mode fracture (paper section 2.3): a beam with
// a mid-span notch from the bottom; the support and loading lines across the width and the
// two notch-mouth edges (for the CMOD) are mesh lines and named curves.
#include <gmsh.h>

#include <cmath>

#include "meshing/generator.hpp"

namespace dspdem::meshing {

void build_galvez_beam(const Params& p) {
  namespace occ = gmsh::model::occ;
  const double L = p["length"], D = p["depth"], B = p["thickness"];
  const double a = p["notch_depth"], w = p["notch_width"], h = p["size"], hn = p["notch_size"];
  const double xs[4] = {p["support_left_x"], p["support_right_x"], p["load_inner_x"], p["load_outer_x"]};
  const char* names[4] = {"support_left_x", "support_right_x", "load_inner_x", "load_outer_x"};
  if (a >= D) param_error(p, "notch_depth", "the notch must be shallower than the beam depth");
  if (w >= L / 4) param_error(p, "notch_width", "too wide for the beam");
  if (h > D / 3) param_error(p, "size", "larger than a third of the beam depth");
  for (int i = 0; i < 4; ++i) {
    if (std::abs(xs[i]) >= L / 2) param_error(p, names[i], "outside the beam (|x| must be < length/2)");
    if (std::abs(xs[i]) <= w / 2) param_error(p, names[i], "on the notch");
  }
  // The crack region: a slab x0 < x < x1 (through the depth and width) as a volume of its
  // own, meshed at band_size, so joints can be put there only and refined there alone.
  const double x0 = p["band_min_x"], x1 = p["band_max_x"], hb = p["band_size"] > 0 ? p["band_size"] : h;
  const bool band = x1 > x0;
  if (band && (x0 <= -L / 2 || x1 >= L / 2)) param_error(p, "band_max_x", "the band must lie inside the beam");
  if (band && (x0 >= -w / 2 || x1 <= w / 2)) param_error(p, "band_min_x", "the band must contain the notch");
  gmsh::vectorpair parts;
  if (band) {
    parts = {{3, occ::addBox(-L / 2, 0, -B / 2, x0 + L / 2, D, B)},
             {3, occ::addBox(x0, 0, -B / 2, x1 - x0, D, B)},
             {3, occ::addBox(x1, 0, -B / 2, L / 2 - x1, D, B)}};
    gmsh::vectorpair glued;
    std::vector<gmsh::vectorpair> gmap;
    occ::fragment({parts[0]}, {parts[1], parts[2]}, glued, gmap);  // shared faces between the slabs
    parts = glued;
  } else {
    parts = {{3, occ::addBox(-L / 2, 0, -B / 2, L, D, B)}};
  }
  const int notch = occ::addBox(-w / 2, -D, -B, w, D + a, 2 * B);  // from below, through the width
  gmsh::vectorpair cut_out;
  std::vector<gmsh::vectorpair> map;
  occ::cut(parts, {{3, notch}}, cut_out, map);
  // Lines across the width at the supports (bottom) and load points (top), embedded by a
  // fragment so that they become mesh lines of the beam's faces.
  gmsh::vectorpair lines;
  auto line = [&](double x, double y) {
    const int p0 = occ::addPoint(x, y, -B / 2), p1 = occ::addPoint(x, y, B / 2);
    lines.emplace_back(1, occ::addLine(p0, p1));
  };
  line(xs[0], 0), line(xs[1], 0), line(xs[2], D), line(xs[3], D);
  gmsh::vectorpair frag_out;
  occ::fragment(cut_out, lines, frag_out, map);
  occ::synchronize();
  const std::vector<int> vols = entities_in_box(3, -L / 2, 0, -B / 2, L / 2, D, B / 2);
  std::vector<int> band_vols, side_vols;
  for (int t : vols) {
    double cx, cy, cz;
    occ::getCenterOfMass(3, t, cx, cy, cz);
    (band && cx > x0 && cx < x1 ? band_vols : side_vols).push_back(t);
  }
  set_volume_size(side_vols, h);
  if (!band_vols.empty()) set_volume_size(band_vols, hb);
  // Refine around the notch tip, where the crack starts.
  gmsh::vectorpair tip_pts;
  gmsh::model::getEntitiesInBoundingBox(-w / 2 - 1e-9, a - 1e-9, -B, w / 2 + 1e-9, a + 1e-9, B, tip_pts, 0);
  gmsh::model::mesh::setSize(tip_pts, hn);
  gmsh::model::mesh::generate(3);
  add_group(3, vols, "beam");
  if (band) add_group(3, band_vols, "beam_band"), add_group(3, side_vols, "beam_side");
  const char* groups[4] = {"support_left", "support_right", "load_inner", "load_outer"};
  const double ys[4] = {0, 0, D, D};
  for (int i = 0; i < 4; ++i) add_group(1, entities_in_box(1, xs[i], ys[i], -B / 2, xs[i], ys[i], B / 2), groups[i]);
  add_group(1, entities_in_box(1, -w / 2, 0, -B / 2, -w / 2, 0, B / 2), "cmod_left");
  add_group(1, entities_in_box(1, w / 2, 0, -B / 2, w / 2, 0, B / 2), "cmod_right");
}

}  // namespace dspdem::meshing
