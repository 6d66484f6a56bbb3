// Trilinear hexahedron with one-point (uniform-gradient) integration and physical
// hourglass stabilisation derived from the incompatible-mode element.
//
// Why this element: a fully integrated hex8 locks in bending (parasitic shear), and a
// one-point hex8 without stabilisation hourglasses. We integrate the constant-strain part
// with the Flanagan-Belytschko uniform gradient b_I = (1/V) int dN_I/dX dV (exact patch test
// on distorted meshes) and add a stabilisation energy 1/2 q^T K_hg q in the 12 hourglass
// coordinates q_{i,a} = gamma_a . u_i (Flanagan & Belytschko 1981, IJNME 17:679). K_hg is
// computed once per element from the Wilson-Taylor incompatible-mode stiffness (Taylor,
// Beresford & Wilson 1976, IJNME 10:1211) projected on the hourglass modes. For a
// parallelepiped the result equals the incompatible-mode element exactly, which is free of
// shear locking and exact in pure bending; like Puso's (2000, IJNME 49:1029) enhanced
// stabilisation it costs one 12x12 product per element per step.
#pragma once
#include <Eigen/Dense>

#include "core/types.hpp"
#include "fem/linear_elastic.hpp"

namespace dspdem::hex8 {

using Coords = Eigen::Matrix<Real, 3, 8>;
using Grad = Eigen::Matrix<Real, 3, 8>;         ///< column I is b_I
using HgVec = Eigen::Matrix<Real, 4, 8>;        ///< row a is gamma_a
using HgStiff = Eigen::Matrix<Real, 12, 12>;    ///< index i + 3a
using Stiffness = Eigen::Matrix<Real, 24, 24>;  ///< dof 3I + i

/// Natural coordinates of the 8 nodes in gmsh order (columns).
const Coords& natural_coords();
/// dN_I/dxi at a natural point (column I).
Grad shape_derivatives(const Vec3& xi);
/// Smallest Jacobian determinant over the 8 corners; <= 0 means inverted or degenerate.
Real min_corner_jacobian(const Coords& X);

/// What the kernel needs per element, computed once in the reference configuration.
struct Reference {
  Grad b;                                   ///< uniform gradient
  Real volume = 0;                          ///< exact volume
  HgVec gamma;                              ///< hourglass shape vectors (annihilate linear fields)
  HgStiff k_hg;                             ///< stabilisation stiffness [N/m]
  Eigen::Matrix<Real, 8, 1> mass_fraction;  ///< row-sum lumped mass shares (sum 1)
};

Reference setup(const Coords& X, const LinearElastic& mat);

/// Full 24x24 stiffness of the incompatible-mode element (static condensation). Used in
/// setup and by tests.
Stiffness incompatible_mode_stiffness(const Coords& X, const LinearElastic& mat);

/// Stiffness the kernel actually applies: one-point part + Gamma^T K_hg Gamma.
Stiffness kernel_stiffness(const Reference& ref, const LinearElastic& mat);

}  // namespace dspdem::hex8
