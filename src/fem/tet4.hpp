// Linear tetrahedron (constant strain). Shape-function gradients b_I = dN_I/dX in the
// reference configuration, so that grad u = sum_I u_I (x) b_I and the nodal internal force
// is f_I = V sigma b_I (Zienkiewicz & Taylor, The FEM vol. 1, ch. 6).
#pragma once
#include <Eigen/Dense>

#include "core/types.hpp"

namespace dspdem::tet4 {

using Grad = Eigen::Matrix<Real, 3, 4>;  ///< column I is b_I
using Coords = Eigen::Matrix<Real, 3, 4>;

/// Gradients and volume of a tet from its reference corner coordinates (columns).
inline void gradients(const Coords& X, Grad& b, Real& volume) {
  Mat3 J;
  J.col(0) = X.col(1) - X.col(0);
  J.col(1) = X.col(2) - X.col(0);
  J.col(2) = X.col(3) - X.col(0);
  volume = J.determinant() / 6.0;
  const Mat3 Jinv = J.inverse();  // rows are dN_{1,2,3}/dX
  for (int i = 0; i < 3; ++i) b.col(i + 1) = Jinv.row(i).transpose();
  b.col(0) = -(b.col(1) + b.col(2) + b.col(3));
}

}  // namespace dspdem::tet4
