// Galvez et al. (1998) notched beam for mixed-mode fracture (paper section 2.3): a beam with
// a mid-span notch from the bottom; the support and loading lines across the width and the
// two notch-mouth edges (for the CMOD) are mesh lines and named curves.
#include <gmsh.h>

#include <cmath>
#include <limits>

#include "meshing/generator.hpp"

namespace dspdem::meshing {

void build_galvez_beam(const Params& p) {
  namespace occ = gmsh::model::occ;
  const double L = p["length"], D = p["depth"], B = p["thickness"];
  const double a = p["notch_depth"], w = p["notch_width"], h = p["size"], hn = p["notch_size"];
  const double xs[4] = {p["support_left_x"], p["support_right_x"], p["load_inner_x"], p["load_outer_x"]};
  const char* names[4] = {"support_left_x", "support_right_x", "load_inner_x", "load_outer_x"};
  if (a >= D) param_error(p, "notch_depth", "the notch must be shallower than the beam depth");
  check_tet_count(p, "size", L * D * B, h);
  if (p["band_size"] > 0 && p["band_max_x"] > p["band_min_x"])
    check_tet_count(p, "band_size", (p["band_max_x"] - p["band_min_x"]) * D * B, p["band_size"]);
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

// Parameters of [mesh.galvez_beam], declared beside the generator that uses them (the case reader
// validates them, `dspdem keys` documents them).
// clang-format off
const std::vector<schema::Key>& galvez_beam_keys() {
  using T = schema::Type;
  constexpr double inf = std::numeric_limits<double>::infinity();
  static const std::vector<schema::Key> k = {
    {"mesh.galvez_beam", "length", T::Real, "0.675", 0, inf, true, false, "m", nullptr, "Beam length (4.5 D). The Galvez et al. geometry was not found in a readable source [NF]: the defaults are the medium size D = 150 mm as we chose it (src/scenes/galvez_beam/REFERENCE.md)."},
    {"mesh.galvez_beam", "depth", T::Real, "0.15", 0, inf, true, false, "m", nullptr, "Beam depth D (along y)."},
    {"mesh.galvez_beam", "thickness", T::Real, "0.05", 0, inf, true, false, "m", nullptr, "Beam thickness (along z)."},
    {"mesh.galvez_beam", "notch_depth", T::Real, "0.075", 0, inf, true, false, "m", nullptr, "Notch depth from the bottom face (D/2)."},
    {"mesh.galvez_beam", "notch_width", T::Real, "0.002", 0, inf, true, false, "m", nullptr, "Notch width."},
    {"mesh.galvez_beam", "target_elements", T::Int, "0", 0, 1e8, false, false, "", nullptr, "Element count wanted in the beam: when > 0 the size is rescaled (a few gmsh runs) until the count is within 3 %."},
    {"mesh.galvez_beam", "size", T::Real, "0.01", 0, inf, true, false, "m", nullptr, "Element size away from the notch."},
    {"mesh.galvez_beam", "notch_size", T::Real, "0.004", 0, inf, true, false, "m", nullptr, "Element size at the notch tip."},
    {"mesh.galvez_beam", "band_min_x", T::Real, "0", -inf, inf, false, false, "m", nullptr, "With band_max_x > band_min_x: the slab band_min_x < x < band_max_x (it must contain the notch) is the volume group beam_band (the rest beam_side; beam holds both), meshed at band_size: joints there only with fracture_groups = [\"beam_band\"]."},
    {"mesh.galvez_beam", "band_max_x", T::Real, "0", -inf, inf, false, false, "m", nullptr, "See band_min_x."},
    {"mesh.galvez_beam", "band_size", T::Real, "0", 0, inf, false, false, "m", nullptr, "Element size in the band (0: size)."},
    {"mesh.galvez_beam", "support_left_x", T::Real, "-0.3", -inf, inf, false, false, "m", nullptr, "Bottom support line, x from the notch (span 4 D). [NF]: chosen."},
    {"mesh.galvez_beam", "support_right_x", T::Real, "0.3", -inf, inf, false, false, "m", nullptr, "Bottom support line, x from the notch. [NF]: chosen."},
    {"mesh.galvez_beam", "load_inner_x", T::Real, "0.075", -inf, inf, false, false, "m", nullptr, "Top loading line carrying the actuator load, x from the notch (D/2). [NF]: chosen."},
    {"mesh.galvez_beam", "load_outer_x", T::Real, "-0.075", -inf, inf, false, false, "m", nullptr, "Second top line (the spring-held point of the nonproportional test). [NF]: chosen."},
  };
  return k;
}
// clang-format on

}  // namespace dspdem::meshing
