// Brazilian disc: the point-load solution along the loaded diameter (paper eqs. 24-25,
// src/scenes/brazilian_disc/REFERENCE.md) and its mean over an element. Pure functions.
#pragma once
#include <cmath>
#include <vector>

#include "core/types.hpp"
#include "report/field_sampling.hpp"

namespace dspdem::disc {

/// Splitting (indirect tensile) strength 2 P / (pi D L) [Pa].
inline Real splitting_stress(Real P, Real D, Real L) { return 2 * P / (M_PI * D * L); }

/// sigma_xx at (0, y) under two line loads P along y: uniform tension 2P/(pi D L).
inline Real sigma_xx_diameter(Real P, Real D, Real L, Real /*y*/) { return splitting_stress(P, D, L); }

/// sigma_yy at (0, y): (2P/(pi D L)) (1 - 4 D^2 / (D^2 - 4 y^2)), -3x the tension at the centre.
inline Real sigma_yy_diameter(Real P, Real D, Real L, Real y) {
  return splitting_stress(P, D, L) * (1 - 4 * D * D / (D * D - 4 * y * y));
}

/// In-plane stress (sxx, syy, sxy) at (x, y) of the disc under the two line loads: two
/// Flamant radial fields, sigma_r = -(2P/(pi L)) cos(theta)/r from each load point, plus a
/// uniform biaxial tension 2P/(pi D L) that frees the rim (Timoshenko and Goodier, 3rd ed.,
/// section 41). On x = 0 it reduces to the two functions above; off the diameter it is what
/// an element whose centroid is not on x = 0 should be compared with.
struct PlaneStress {
  Real xx, yy, xy;
};
inline PlaneStress point_load_stress(Real P, Real D, Real L, Real x, Real y) {
  const Real s0 = splitting_stress(P, D, L), R = D / 2, k = -2 * P / (M_PI * L);
  PlaneStress s{s0, s0, 0};
  for (int side : {1, -1}) {  // load point (0, side R), pushing along -side y
    const Real dx = x, dy = y - side * R, r2 = dx * dx + dy * dy;
    const Real f = k * (-side * dy) / (r2 * r2);  // sigma_r / r^2 with cos(theta) = -side dy / r
    s.xx += f * dx * dx, s.yy += f * dy * dy, s.xy += f * dx * dy;
  }
  return s;
}

/// Mean of the two-load field over the tetrahedron v (its x, y; z does not enter). A
/// constant-stress element approximates the mean of the true field over its volume, not its
/// value at the centroid; within a few element sizes of a load point the two differ by a few
/// percent of 2P/(pi D L), from the field's curvature across the element.
inline PlaneStress tet_mean_point_load_stress(Real P, Real D, Real L, const Vec3 v[4], int levels = 3) {
  const Vec3 m = report::tet_mean<Vec3>(
      v,
      [&](const Vec3& p) {
        const PlaneStress s = point_load_stress(P, D, L, p(0), p(1));
        return Vec3(s.xx, s.yy, s.xy);
      },
      levels);
  return {m(0), m(1), m(2)};
}

}  // namespace dspdem::disc
