#include "fem/hex8.hpp"

#include <array>

namespace dspdem::hex8 {

const Coords& natural_coords() {
  static const Coords c = [] {
    Coords m;
    m << -1, 1, 1, -1, -1, 1, 1, -1,  //
        -1, -1, 1, 1, -1, -1, 1, 1,   //
        -1, -1, -1, -1, 1, 1, 1, 1;
    return m;
  }();
  return c;
}

Grad shape_derivatives(const Vec3& xi) {
  const Coords& n = natural_coords();
  Grad d;
  for (int I = 0; I < 8; ++I) {
    const Real a = 1 + n(0, I) * xi(0), b = 1 + n(1, I) * xi(1), c = 1 + n(2, I) * xi(2);
    d(0, I) = 0.125 * n(0, I) * b * c;
    d(1, I) = 0.125 * a * n(1, I) * c;
    d(2, I) = 0.125 * a * b * n(2, I);
  }
  return d;
}

static Eigen::Matrix<Real, 8, 1> shape_values(const Vec3& xi) {
  const Coords& n = natural_coords();
  Eigen::Matrix<Real, 8, 1> N;
  for (int I = 0; I < 8; ++I) N(I) = 0.125 * (1 + n(0, I) * xi(0)) * (1 + n(1, I) * xi(1)) * (1 + n(2, I) * xi(2));
  return N;
}

Real min_corner_jacobian(const Coords& X) {
  Real m = std::numeric_limits<Real>::infinity();
  for (int I = 0; I < 8; ++I) {
    const Mat3 J = X * shape_derivatives(natural_coords().col(I)).transpose();
    m = std::min(m, J.determinant());
  }
  return m;
}

namespace {
const std::array<Vec3, 8>& gauss_points() {
  static const std::array<Vec3, 8> g = [] {
    std::array<Vec3, 8> p;
    const Real a = 1.0 / std::sqrt(3.0);
    for (int I = 0; I < 8; ++I) p[I] = a * natural_coords().col(I);
    return p;
  }();
  return g;
}

// Voigt strain-displacement rows for one gradient vector g (engineering shear).
Eigen::Matrix<Real, 6, 3> b_block(const Vec3& g) {
  Eigen::Matrix<Real, 6, 3> B = Eigen::Matrix<Real, 6, 3>::Zero();
  B(0, 0) = g(0);
  B(1, 1) = g(1);
  B(2, 2) = g(2);
  B(3, 0) = g(1), B(3, 1) = g(0);
  B(4, 1) = g(2), B(4, 2) = g(1);
  B(5, 0) = g(2), B(5, 2) = g(0);
  return B;
}

// The four hourglass base vectors h_a (xi*eta, eta*zeta, zeta*xi, xi*eta*zeta at the nodes).
Eigen::Matrix<Real, 8, 4> hourglass_base() {
  const Coords& n = natural_coords();
  Eigen::Matrix<Real, 8, 4> h;
  for (int I = 0; I < 8; ++I) {
    h(I, 0) = n(0, I) * n(1, I);
    h(I, 1) = n(1, I) * n(2, I);
    h(I, 2) = n(2, I) * n(0, I);
    h(I, 3) = n(0, I) * n(1, I) * n(2, I);
  }
  return h;
}
}  // namespace

Stiffness incompatible_mode_stiffness(const Coords& X, const LinearElastic& mat) {
  const Eigen::Matrix<Real, 6, 6> C = mat.voigt();
  const Mat3 J0 = X * shape_derivatives(Vec3::Zero()).transpose();
  const Real det0 = J0.determinant();
  const Mat3 J0invT = J0.inverse().transpose();
  Stiffness Kuu = Stiffness::Zero();
  Eigen::Matrix<Real, 24, 9> Kua = Eigen::Matrix<Real, 24, 9>::Zero();
  Eigen::Matrix<Real, 9, 9> Kaa = Eigen::Matrix<Real, 9, 9>::Zero();
  for (const Vec3& xi : gauss_points()) {
    const Grad dN = shape_derivatives(xi);
    const Mat3 J = X * dN.transpose();
    const Real detJ = J.determinant();
    const Grad g = J.inverse().transpose() * dN;
    Eigen::Matrix<Real, 6, 24> B;
    for (int I = 0; I < 8; ++I) B.block<6, 3>(0, 3 * I) = b_block(g.col(I));
    // Incompatible modes 1-xi^2, 1-eta^2, 1-zeta^2 with Taylor's constant-Jacobian
    // correction so that the element passes the patch test when distorted.
    Eigen::Matrix<Real, 6, 9> G;
    for (int k = 0; k < 3; ++k) {
      Vec3 dxi = Vec3::Zero();
      dxi(k) = -2.0 * xi(k);
      G.block<6, 3>(0, 3 * k) = b_block((det0 / detJ) * (J0invT * dxi));
    }
    Kuu += B.transpose() * C * B * detJ;
    Kua += B.transpose() * C * G * detJ;
    Kaa += G.transpose() * C * G * detJ;
  }
  return Kuu - Kua * Kaa.ldlt().solve(Kua.transpose());
}

Reference setup(const Coords& X, const LinearElastic& mat) {
  Reference r;
  // Exact volume and uniform gradient by 2x2x2 Gauss (the integrands are polynomials of
  // degree <= 2 per direction).
  r.volume = 0;
  Grad bint = Grad::Zero();
  Eigen::Matrix<Real, 8, 1> nint = Eigen::Matrix<Real, 8, 1>::Zero();
  for (const Vec3& xi : gauss_points()) {
    const Grad dN = shape_derivatives(xi);
    const Mat3 J = X * dN.transpose();
    const Real detJ = J.determinant();
    r.volume += detJ;
    bint += J.inverse().transpose() * dN * detJ;
    nint += shape_values(xi) * detJ;
  }
  r.b = bint / r.volume;
  r.mass_fraction = nint / r.volume;

  // gamma_a = (h_a - sum_j (h_a . X_j) b_j) / 8 annihilates constants and linear fields.
  const Eigen::Matrix<Real, 8, 4> h = hourglass_base();
  for (int a = 0; a < 4; ++a) {
    Eigen::Matrix<Real, 8, 1> gam = h.col(a);
    for (int j = 0; j < 3; ++j) gam -= (h.col(a).dot(X.row(j).transpose())) * r.b.row(j).transpose();
    r.gamma.row(a) = gam.transpose() / 8.0;
  }
  // Hourglass fields dual to gamma: htilde = h (gamma h)^-1, so gamma htilde = I.
  const Eigen::Matrix<Real, 4, 4> gh = r.gamma * h;
  const Eigen::Matrix<Real, 8, 4> ht = h * gh.inverse();

  const Stiffness K = incompatible_mode_stiffness(X, mat);
  for (int a = 0; a < 4; ++a)
    for (int i = 0; i < 3; ++i)
      for (int bb = 0; bb < 4; ++bb)
        for (int j = 0; j < 3; ++j) {
          Real s = 0;
          for (int I = 0; I < 8; ++I)
            for (int J = 0; J < 8; ++J) s += ht(I, a) * K(3 * I + i, 3 * J + j) * ht(J, bb);
          r.k_hg(i + 3 * a, j + 3 * bb) = s;
        }
  r.k_hg = 0.5 * (r.k_hg + r.k_hg.transpose()).eval();
  return r;
}

Stiffness kernel_stiffness(const Reference& ref, const LinearElastic& mat) {
  const Eigen::Matrix<Real, 6, 6> C = mat.voigt();
  Eigen::Matrix<Real, 6, 24> B;
  for (int I = 0; I < 8; ++I) B.block<6, 3>(0, 3 * I) = b_block(ref.b.col(I));
  Stiffness K = ref.volume * B.transpose() * C * B;
  // q = P u with P(i + 3a, 3I + i) = gamma(a, I)
  Eigen::Matrix<Real, 12, 24> P = Eigen::Matrix<Real, 12, 24>::Zero();
  for (int a = 0; a < 4; ++a)
    for (int I = 0; I < 8; ++I)
      for (int i = 0; i < 3; ++i) P(i + 3 * a, 3 * I + i) = ref.gamma(a, I);
  K += P.transpose() * ref.k_hg * P;
  return K;
}

}  // namespace dspdem::hex8
