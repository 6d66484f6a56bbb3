// Element-level checks: patch tests on distorted meshes, rigid-body invariance, hex8
// stabilisation against the incompatible-mode element, absence of zero-energy modes.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include "fem/fem_model.hpp"
#include "fem/hex8.hpp"
#include "mesh/mesh.hpp"
#include "support/box_mesh.hpp"

using namespace dspdem;

namespace {
FemModel make_model(const Mesh& mesh, Kinematics kin, Real E = 30e9, Real nu = 0.25) {
  Material m;
  m.name = "m", m.E = E, m.nu = nu, m.density = 2500;
  const Index ne = mesh.n_elements();
  return build_fem_model(mesh, {m}, std::vector<Index>(ne, 0), std::vector<Index>(ne, 0), {kin});
}

bool on_boundary(const Mesh& mesh, Index n) {
  for (const auto& g : mesh.groups)
    if (g.dim == 2 && std::binary_search(g.nodes.begin(), g.nodes.end(), n)) return true;
  return false;
}

// Applies x = Q (I + eps) X to every node, evaluates forces and stresses, and checks:
// every element carries sigma = Q (C:eps) Q^T and interior nodes are in equilibrium.
void patch_test(CellType type, Kinematics kin, const Mat3& Q) {
  const Mesh mesh = testsupport::box_mesh(type, 4, 3, 3, Vec3(1.0, 0.8, 0.9), 0.25, 7);
  FemModel fm = make_model(mesh, kin);
  Mat3 eps;
  eps << 1.0e-3, 0.4e-3, -0.2e-3, 0.4e-3, -0.5e-3, 0.3e-3, -0.2e-3, 0.3e-3, 0.8e-3;
  std::vector<Real> x(mesh.x.size()), v(mesh.x.size(), 0.0), f(mesh.x.size()), s(6 * mesh.n_elements());
  for (Index n = 0; n < mesh.n_nodes(); ++n) {
    const Vec3 p = Q * (Mat3::Identity() + eps) * node_pos(mesh.x, n);
    for (int d = 0; d < 3; ++d) x[3 * n + d] = p(d);
  }
  const ForceStatus st = internal_forces(fm, x.data(), v.data(), f.data(), s.data());
  ASSERT_LT(st.inverted_element, 0);
  const LinearElastic el = LinearElastic::from_E_nu(30e9, 0.25);
  const Mat3 sig = Q * el.stress(eps) * Q.transpose();
  const Real ref = sig.norm();
  for (Index e = 0; e < mesh.n_elements(); ++e) {
    const Real* o = &s[6 * e];
    Mat3 se;
    se << o[0], o[3], o[5], o[3], o[1], o[4], o[5], o[4], o[2];
    // 1e-10 relative: the fields are exact, only round-off remains.
    ASSERT_LT((se - sig).norm() / ref, 1e-10) << cell_name(type) << " element " << e;
  }
  Real fmax = 0, fint = 0;
  for (Index n = 0; n < mesh.n_nodes(); ++n) {
    const Real fn = Vec3(f[3 * n], f[3 * n + 1], f[3 * n + 2]).norm();
    fmax = std::max(fmax, fn);
    if (!on_boundary(mesh, n)) fint = std::max(fint, fn);
  }
  EXPECT_LT(fint / fmax, 1e-10) << cell_name(type);
}

Mat3 rotation(Real angle, Vec3 axis) { return Eigen::AngleAxis<Real>(angle, axis.normalized()).toRotationMatrix(); }
}  // namespace

TEST(PatchTest, Tet4SmallStrainDistorted) { patch_test(CellType::Tet4, Kinematics::SmallStrain, Mat3::Identity()); }
TEST(PatchTest, Hex8SmallStrainDistorted) { patch_test(CellType::Hex8, Kinematics::SmallStrain, Mat3::Identity()); }
TEST(PatchTest, Tet4CorotationalRotated) {
  patch_test(CellType::Tet4, Kinematics::Corotational, rotation(1.1, Vec3(1, 2, 3)));
}
TEST(PatchTest, Hex8CorotationalRotated) {
  patch_test(CellType::Hex8, Kinematics::Corotational, rotation(2.3, Vec3(-1, 0.5, 2)));
}

TEST(Hex8, StabilisedEqualsIncompatibleModesOnParallelepiped) {
  // A sheared, stretched box: the decomposition into one-point and hourglass parts is exact.
  hex8::Coords X = hex8::natural_coords();
  Mat3 A;
  A << 0.6, 0.1, 0.05, 0.0, 0.3, 0.08, 0.0, 0.0, 0.45;
  X = (A * X).eval();
  const LinearElastic el = LinearElastic::from_E_nu(25.8e9, 0.15);
  const hex8::Reference r = hex8::setup(X, el);
  const hex8::Stiffness K = hex8::kernel_stiffness(r, el), Kim = hex8::incompatible_mode_stiffness(X, el);
  EXPECT_LT((K - Kim).norm() / Kim.norm(), 1e-12);
}

TEST(Hex8, NoZeroEnergyModesBeyondRigidBody) {
  hex8::Coords X = hex8::natural_coords();
  for (int I = 0; I < 8; ++I) X.col(I) += Vec3(0.07 * std::sin(3.0 * I), 0.05 * std::cos(2.0 * I), 0.06 * std::sin(I));
  const LinearElastic el = LinearElastic::from_E_nu(30e9, 0.2);
  const hex8::Stiffness K = hex8::kernel_stiffness(hex8::setup(X, el), el);
  Eigen::SelfAdjointEigenSolver<hex8::Stiffness> es(K);
  const auto ev = es.eigenvalues();
  // Six rigid-body modes (zero up to round-off), then 18 strictly positive: no hourglass.
  for (int i = 0; i < 6; ++i) EXPECT_LT(std::abs(ev(i)) / ev(23), 1e-12);
  EXPECT_GT(ev(6) / ev(23), 1e-4);
}

TEST(Hex8, PureBendingExactOnRectangularElement) {
  // u_x = kappa x z (pure bending about y), u_z = -kappa x^2/2 ... The incompatible-mode
  // element reproduces pure bending exactly: strain energy = 1/2 E I kappa^2 L for nu = 0.
  const Real a = 0.5, b = 0.2, c = 0.1;  // half lengths
  hex8::Coords X = hex8::natural_coords();
  X.row(0) *= a, X.row(1) *= b, X.row(2) *= c;
  const LinearElastic el = LinearElastic::from_E_nu(10e9, 0.0);
  const hex8::Stiffness K = hex8::kernel_stiffness(hex8::setup(X, el), el);
  const Real kappa = 1e-3;
  Eigen::Matrix<Real, 24, 1> u;
  for (int I = 0; I < 8; ++I) {
    const Real x = X(0, I), z = X(2, I);
    u.segment<3>(3 * I) = Vec3(-kappa * x * z, 0, 0.5 * kappa * x * x);
  }
  const Real W = 0.5 * u.dot(K * u);
  const Real I = (2 * b) * std::pow(2 * c, 3) / 12.0;
  const Real exact = 0.5 * 10e9 * I * kappa * kappa * (2 * a);
  EXPECT_NEAR(W / exact, 1.0, 1e-10);
}

TEST(Kinematics, RigidRotationIsStressFreeOnlyWhenCorotational) {
  const Mesh mesh = testsupport::box_mesh(CellType::Tet4, 2, 2, 2, Vec3(1, 1, 1));
  for (Kinematics kin : {Kinematics::Corotational, Kinematics::SmallStrain}) {
    FemModel fm = make_model(mesh, kin);
    const Mat3 R = rotation(0.8, Vec3(0.3, 1, -0.2));
    std::vector<Real> x(mesh.x.size()), v(mesh.x.size(), 0.0), f(mesh.x.size()), s(6 * mesh.n_elements());
    for (Index n = 0; n < mesh.n_nodes(); ++n) {
      const Vec3 p = R * node_pos(mesh.x, n) + Vec3(5, -3, 2);
      for (int d = 0; d < 3; ++d) x[3 * n + d] = p(d);
    }
    internal_forces(fm, x.data(), v.data(), f.data(), s.data());
    Real smax = 0;
    for (Real si : s) smax = std::max(smax, std::abs(si));
    if (kin == Kinematics::Corotational)
      EXPECT_LT(smax, 1e-6 * 30e9 * 1e-6);
    else
      EXPECT_GT(smax, 1e-2 * 30e9);  // a 0.8 rad rotation reads as ~30 % strain
  }
}

TEST(Hex8, MeshCornerJacobianMatchesTheShapeFunctions) {
  // The mesh checks hexahedra without the FEM layer (edge triple products at the corners);
  // it must agree with the Jacobian of the shape functions at every corner, for distorted
  // and for inverted elements.
  std::srand(7);
  const Real nat[8][3] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                          {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};
  for (int trial = 0; trial < 50; ++trial) {
    hex8::Coords X;
    Vec3 xs[8];
    const Real amp = trial < 40 ? 0.2 : 1.2;  // the last ten are often inverted
    for (int i = 0; i < 8; ++i) {
      xs[i] = 0.5 * Vec3(nat[i][0], nat[i][1], nat[i][2]) + amp * Vec3::Random() * 0.5;
      X.col(i) = xs[i];
    }
    EXPECT_NEAR(hex8_min_corner_jacobian(xs), hex8::min_corner_jacobian(X), 1e-12) << "trial " << trial;
  }
}
