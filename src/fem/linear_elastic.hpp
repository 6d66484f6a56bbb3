// Isotropic linear elasticity (Hooke's law) in Lame form:
//   sigma = lambda tr(eps) I + 2 mu eps                      [Pa]
//   W     = lambda/2 tr(eps)^2 + mu eps:eps                  [J/m^3]
// with lambda = E nu / ((1+nu)(1-2nu)), mu = E / (2(1+nu)).
#pragma once
#include "core/types.hpp"

namespace dspdem {

struct LinearElastic {
  Real lambda = 0.0;  ///< first Lame parameter [Pa]
  Real mu = 0.0;      ///< shear modulus [Pa]

  /// Builds from Young's modulus E [Pa] and Poisson's ratio nu. Assumes validated input
  /// (E > 0, -1 < nu < 0.5): the case reader checks those with the key names.
  static LinearElastic from_E_nu(Real E, Real nu) {
    return {E * nu / ((1.0 + nu) * (1.0 - 2.0 * nu)), E / (2.0 * (1.0 + nu))};
  }
  /// P-wave modulus lambda + 2 mu [Pa]: sets the dilatational wave speed.
  Real p_modulus() const { return lambda + 2.0 * mu; }

  /// Stress from a symmetric small-strain tensor.
  Mat3 stress(const Mat3& eps) const { return lambda * eps.trace() * Mat3::Identity() + 2.0 * mu * eps; }
  /// Strain energy density.
  Real energy_density(const Mat3& eps) const {
    const Real tr = eps.trace();
    return 0.5 * lambda * tr * tr + mu * eps.squaredNorm();
  }
  /// 6x6 Voigt matrix, engineering shear strains, order xx yy zz xy yz xz.
  Eigen::Matrix<Real, 6, 6> voigt() const {
    Eigen::Matrix<Real, 6, 6> C = Eigen::Matrix<Real, 6, 6>::Zero();
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) C(i, j) = lambda;
      C(i, i) += 2.0 * mu;
      C(i + 3, i + 3) = mu;
    }
    return C;
  }
};

/// Von Mises equivalent stress of a symmetric tensor.
inline Real von_mises(const Mat3& s) {
  const Real a = s(0, 0) - s(1, 1), b = s(1, 1) - s(2, 2), c = s(2, 2) - s(0, 0);
  return std::sqrt(0.5 * (a * a + b * b + c * c) + 3.0 * (s(0, 1) * s(0, 1) + s(1, 2) * s(1, 2) + s(0, 2) * s(0, 2)));
}

}  // namespace dspdem
