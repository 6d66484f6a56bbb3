// Rotation part R of the polar decomposition F = R U, for the co-rotational update.
// Higham's Newton iteration R <- (R + R^-T)/2 converges quadratically from F itself; for the
// small-strain, large-rotation states of brittle solids F is nearly orthogonal, so it takes
// two iterations on an elastic element (test_polar asserts it), more only under large strain.
// Returns false when det F <= 0 (inverted element).
#pragma once
#include <Eigen/Dense>

#include "core/types.hpp"

namespace dspdem {

/// R from F, whose determinant the caller has already computed as det (the element kernels
/// need it for their inversion check anyway); false, R untouched, when det <= 0.
/// `iterations`, if given, receives the Newton steps taken.
/// Always inlined: GCC kept it a call, for which F and R went through memory and each
/// kernel's element waited on it; inlined, the co-rotational tet4 kernel takes 0.67-0.77 of
/// the time (bench_internal_force), with the same operations and so the same bits.
[[gnu::always_inline]] inline bool polar_rotation(const Mat3& F, Real det, Mat3& R, int* iterations = nullptr) {
  if (!(det > 0.0)) return false;
  R = F;
  int it = 0;
  while (it < 30) {
    const Mat3 Rn = 0.5 * (R + R.inverse().transpose());
    const Real change = (Rn - R).squaredNorm();
    R = Rn;
    ++it;
    // Near the solution each step squares the error (to half of it): after a step that moved
    // R by |change| the error left is about |change|^2 / 2. Below |change| = 1e-8 that is
    // 5e-17 (Frobenius), under half the spacing of doubles near 1, the size of a rotation's
    // largest entries: a further step would move R by about its own rounding (a few units in
    // the last place of each entry). (The old bound, |change| < 1e-10, took that step on
    // nearly every element: a third of the decomposition's cost for no digit.)
    if (change < 1e-16) break;
  }
  if (iterations) *iterations = it;
  return true;
}

/// The same, computing det F itself.
inline bool polar_rotation(const Mat3& F, Mat3& R, int* iterations = nullptr) {
  return polar_rotation(F, F.determinant(), R, iterations);
}

}  // namespace dspdem
