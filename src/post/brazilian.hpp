// Brazilian disc: the point-load solution along the loaded diameter (paper eqs. 24-25,
// refdata/brazilian_analytic.md) and the error measures of the report. Pure functions.
#pragma once
#include <cmath>
#include <vector>

#include "core/types.hpp"

namespace dspdem::post {

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

/// Relative L2 error sqrt(sum (a - b)^2 / sum b^2) of samples a against reference b.
inline Real relative_l2(const std::vector<Real>& a, const std::vector<Real>& b) {
  Real num = 0, den = 0;
  for (std::size_t i = 0; i < a.size() && i < b.size(); ++i) num += (a[i] - b[i]) * (a[i] - b[i]), den += b[i] * b[i];
  return den > 0 ? std::sqrt(num / den) : 0.0;
}

}  // namespace dspdem::post
