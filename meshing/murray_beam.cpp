// Plain concrete beam struck by two impactors (paper section 2.4, Murray et al. 2007):
// structured hexahedra, with the box split at the support, impactor and mid-span lines so
// that those lines are mesh lines and named curves.
#include <gmsh.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/error.hpp"
#include "meshing/generator.hpp"

namespace dspdem::meshing {

void build_murray_beam(const Params& p) {
  namespace occ = gmsh::model::occ;
  const double L = p["length"], H = p["depth"], W = p["width"];
  const double span = p["span"], gap = p["impactor_spacing"], r = p["cylinder_radius"];
  const int nx = static_cast<int>(p["nx"]), ny = static_cast<int>(p["ny"]), nz = static_cast<int>(p["nz"]);
  check_count(p, "nx", static_cast<double>(nx) * ny * nz, "nx x ny x nz hexahedra");
  if (p["cylinders"] != 0) check_tet_count(p, "cylinder_size", 4 * M_PI * r * r * W, p["cylinder_size"]);
  if (span >= L) param_error(p, "span", "must be shorter than the beam length");
  if (gap >= span) param_error(p, "impactor_spacing", "must be smaller than the span");
  if (r >= span / 4) param_error(p, "cylinder_radius", "too large for the span");
  // Segment ends along x: beam ends, supports, impactors, mid-span.
  const std::vector<double> xs = {-L / 2, -span / 2, -gap / 2, 0.0, gap / 2, span / 2, L / 2};
  std::vector<int> counts(xs.size() - 1);
  int used = 0;
  for (std::size_t i = 0; i + 1 < xs.size(); ++i) {
    counts[i] = std::max(1, static_cast<int>(std::lround(nx * (xs[i + 1] - xs[i]) / L)));
    used += counts[i];
  }
  // Put any rounding difference into the two middle segments, keeping the mesh symmetric.
  const int diff = nx - used;
  if (diff % 2 != 0) param_error(p, "nx", "must give an even number of elements across the symmetric segments");
  counts[2] += diff / 2, counts[3] += diff / 2;
  if (counts[2] < 1) param_error(p, "nx", "too small for the segment layout");

  gmsh::vectorpair boxes;
  for (std::size_t i = 0; i + 1 < xs.size(); ++i)
    boxes.emplace_back(3, occ::addBox(xs[i], -H / 2, -W / 2, xs[i + 1] - xs[i], H, W));
  gmsh::vectorpair out;
  std::vector<gmsh::vectorpair> map;
  occ::fragment({boxes.front()}, gmsh::vectorpair(boxes.begin() + 1, boxes.end()), out, map);
  // Cylinders along z, touching the beam: impactors on top, supports below. Meshed only
  // when asked for: the case strikes the beam with analytic rigid cylinders ([[walls]]).
  const bool cylinders = p["cylinders"] != 0;
  const double cl = W;
  int imp_l = -1, imp_r = -1, sup_l = -1, sup_r = -1;
  if (cylinders) {
    imp_l = occ::addCylinder(-gap / 2, H / 2 + r, -cl / 2, 0, 0, cl, r);
    imp_r = occ::addCylinder(gap / 2, H / 2 + r, -cl / 2, 0, 0, cl, r);
    sup_l = occ::addCylinder(-span / 2, -H / 2 - r, -cl / 2, 0, 0, cl, r);
    sup_r = occ::addCylinder(span / 2, -H / 2 - r, -cl / 2, 0, 0, cl, r);
  }
  occ::synchronize();

  const std::vector<int> beam = entities_in_box(3, -L / 2, -H / 2, -W / 2, L / 2, H / 2, W / 2);
  DSPDEM_CHECK(beam.size() == xs.size() - 1, "internal: murray_beam expected {} beam segments, got {}", xs.size() - 1,
               beam.size());
  // Transfinite lines: count by direction (and by x segment).
  // Every curve of the beam lies inside its bounding box; the cylinders' curves do not.
  gmsh::vectorpair curves;
  for (int c : entities_in_box(1, -L / 2, -H / 2, -W / 2, L / 2, H / 2, W / 2)) curves.emplace_back(1, c);
  for (auto [d, c] : curves) {
    double x0, y0, z0, x1, y1, z1;
    gmsh::model::getBoundingBox(1, c, x0, y0, z0, x1, y1, z1);
    int n = 0;
    const double dx = x1 - x0, dy = y1 - y0, dz = z1 - z0;  // OCC pads boxes: use the longest
    const double tol = 1e-3 * std::min({L, H, W});
    if (dx > dy && dx > dz) {
      for (std::size_t i = 0; i + 1 < xs.size(); ++i)
        if (std::abs(0.5 * (x0 + x1) - 0.5 * (xs[i] + xs[i + 1])) < tol) n = counts[i];
    } else if (dy > dz) {
      n = ny;
    } else {
      n = nz;
    }
    DSPDEM_CHECK(n > 0, "internal: murray_beam could not classify curve {}", c);
    gmsh::model::mesh::setTransfiniteCurve(c, n + 1);
  }
  for (int v : beam) {
    gmsh::vectorpair b;
    gmsh::model::getBoundary({{3, v}}, b, false, false, false);
    for (auto [d, s] : b) {
      gmsh::model::mesh::setTransfiniteSurface(std::abs(s));
      gmsh::model::mesh::setRecombine(2, std::abs(s));
    }
    gmsh::model::mesh::setTransfiniteVolume(v);
  }
  if (cylinders) set_volume_size({imp_l, imp_r, sup_l, sup_r}, p["cylinder_size"]);
  gmsh::model::mesh::generate(3);

  add_group(3, beam, "beam");
  // The beam between the supports (where the paper's joints matter) and its two overhangs.
  add_group(3, entities_in_box(3, -span / 2, -H / 2, -W / 2, span / 2, H / 2, W / 2), "beam_span");
  add_group(3, entities_in_box(3, -L / 2, -H / 2, -W / 2, -span / 2, H / 2, W / 2), "overhang_left");
  add_group(3, entities_in_box(3, span / 2, -H / 2, -W / 2, L / 2, H / 2, W / 2), "overhang_right");
  if (cylinders) {
    add_group(3, {imp_l}, "impactor_left");
    add_group(3, {imp_r}, "impactor_right");
    add_group(3, {sup_l}, "support_left");
    add_group(3, {sup_r}, "support_right");
  }
  // Lines across the width where the cylinders touch: impactor lines on top, support lines below.
  add_group(1, entities_in_box(1, -gap / 2, H / 2, -W / 2, -gap / 2, H / 2, W / 2), "impact_line_left");
  add_group(1, entities_in_box(1, gap / 2, H / 2, -W / 2, gap / 2, H / 2, W / 2), "impact_line_right");
  add_group(1, entities_in_box(1, -span / 2, -H / 2, -W / 2, -span / 2, -H / 2, W / 2), "support_line_left");
  add_group(1, entities_in_box(1, span / 2, -H / 2, -W / 2, span / 2, -H / 2, W / 2), "support_line_right");
  add_group(1, entities_in_box(1, 0, -H / 2, -W / 2, 0, -H / 2, W / 2), "midspan_bottom");
  add_group(2, entities_in_box(2, -L / 2, -H / 2, -W / 2, L / 2, -H / 2, W / 2), "beam_bottom");
  add_group(2, entities_in_box(2, -L / 2, H / 2, -W / 2, L / 2, H / 2, W / 2), "beam_top");
}

// Parameters of [mesh.murray_beam], declared beside the generator that uses them (the case reader
// validates them, `dspdem keys` documents them).
// clang-format off
const std::vector<schema::Key>& murray_beam_keys() {
  using T = schema::Type;
  constexpr double inf = std::numeric_limits<double>::infinity();
  static const std::vector<schema::Key> k = {
    {"mesh.murray_beam", "length", T::Real, "1.524", 0, inf, true, false, "m", nullptr, "Beam length (60 in) [S]."},
    {"mesh.murray_beam", "depth", T::Real, "0.1143", 0, inf, true, false, "m", nullptr, "Beam depth along y (4.5 in) [S]."},
    {"mesh.murray_beam", "width", T::Real, "0.1", 0, inf, true, false, "m", nullptr, "Beam width along z [S]."},
    {"mesh.murray_beam", "span", T::Real, "1.4224", 0, inf, true, false, "m", nullptr, "Support span. [NF]: 1/3 of the FHWA full-scale span 4267.2 mm, the tests being 1/3-scale."},
    {"mesh.murray_beam", "impactor_spacing", T::Real, "0.2032", 0, inf, true, false, "m", nullptr, "Distance between the two impactor lines. [NF]: 1/3 of the full-scale 609.6 mm."},
    {"mesh.murray_beam", "cylinder_radius", T::Real, "0.016", 0, inf, true, false, "m", nullptr, "Radius of the impactor and support cylinders [S]."},
    {"mesh.murray_beam", "cylinders", T::Int, "0", 0, 1, false, false, "", nullptr, "1: mesh the two impactor and two support cylinders as volumes (impactor_left/right, support_left/right); 0: the beam alone, struck through analytic cylinder [[walls]]."},
    {"mesh.murray_beam", "cylinder_size", T::Real, "0.006", 0, inf, true, false, "m", nullptr, "Element size in the cylinders."},
    {"mesh.murray_beam", "nx", T::Int, "68", 2, 100000, false, false, "", nullptr, "Hexahedra along the length (68 x 6 x 10 = 4080, the paper's count)."},
    {"mesh.murray_beam", "ny", T::Int, "6", 1, 100000, false, false, "", nullptr, "Hexahedra through the depth."},
    {"mesh.murray_beam", "nz", T::Int, "10", 1, 100000, false, false, "", nullptr, "Hexahedra across the width."},
  };
  return k;
}
// clang-format on

}  // namespace dspdem::meshing
