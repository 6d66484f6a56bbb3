// Rotation part R of the polar decomposition F = R U, for the co-rotational update.
// Higham's Newton iteration R <- (R + R^-T)/2 converges quadratically from F itself; for the
// small-strain, large-rotation states of brittle solids F is nearly orthogonal, so it takes
// three or four iterations. Returns false when det F <= 0 (inverted element).
#pragma once
#include <Eigen/Dense>

#include "core/types.hpp"

namespace dspdem {

inline bool polar_rotation(const Mat3& F, Mat3& R) {
  if (!(F.determinant() > 0.0)) return false;
  R = F;
  for (int it = 0; it < 30; ++it) {
    const Mat3 Rn = 0.5 * (R + R.inverse().transpose());
    const Real change = (Rn - R).squaredNorm();
    R = Rn;
    if (change < 1e-20) break;  // |change| < 1e-10: the error left is ~|change|^2 / 2
  }
  return true;
}

}  // namespace dspdem
