// Sampling a field for comparison with a reference: the mean of a function over a
// tetrahedron (what a constant-stress element approximates) and the relative L2 error of
// samples. Pure functions, used by the scenes' reports.
#pragma once
#include <cmath>
#include <vector>

#include "core/types.hpp"

namespace dspdem::report {

/// Mean of f over the tetrahedron v[0..3]: midpoint (Bey) subdivision `levels` deep, 8
/// children of volume V/8 per level (4 corner tets, the inner octahedron cut along
/// m02-m13), f at each child's centroid. Exact for linear f; the error of the centroid rule
/// on smooth f falls about 4x per level.
template <class T, class F>
T tet_mean(const Vec3 v[4], const F& f, int levels) {
  if (levels == 0) return f(Vec3(0.25 * (v[0] + v[1] + v[2] + v[3])));
  const Vec3 m01 = 0.5 * (v[0] + v[1]), m02 = 0.5 * (v[0] + v[2]), m03 = 0.5 * (v[0] + v[3]);
  const Vec3 m12 = 0.5 * (v[1] + v[2]), m13 = 0.5 * (v[1] + v[3]), m23 = 0.5 * (v[2] + v[3]);
  const Vec3 kids[8][4] = {{v[0], m01, m02, m03}, {m01, v[1], m12, m13}, {m02, m12, v[2], m23}, {m03, m13, m23, v[3]},
                           {m01, m02, m03, m13},  {m01, m02, m12, m13},  {m02, m03, m13, m23},  {m02, m12, m13, m23}};
  T s = tet_mean<T>(kids[0], f, levels - 1);
  for (int k = 1; k < 8; ++k) s += tet_mean<T>(kids[k], f, levels - 1);
  return s / 8.0;
}

/// Relative L2 error sqrt(sum (a - b)^2 / sum b^2) of samples a against reference b.
inline Real relative_l2(const std::vector<Real>& a, const std::vector<Real>& b) {
  Real num = 0, den = 0;
  for (std::size_t i = 0; i < a.size() && i < b.size(); ++i) num += (a[i] - b[i]) * (a[i] - b[i]), den += b[i] * b[i];
  return den > 0 ? std::sqrt(num / den) : 0.0;
}

}  // namespace dspdem::report
