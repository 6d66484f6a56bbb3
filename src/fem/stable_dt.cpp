#include "fem/stable_dt.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <limits>

#include "fem/hex8.hpp"

namespace dspdem {

namespace {
template <int N>
Real max_frequency(const Eigen::Matrix<Real, N, N>& K, const Eigen::Matrix<Real, N, 1>& minv_sqrt) {
  const Eigen::Matrix<Real, N, N> A = minv_sqrt.asDiagonal() * K * minv_sqrt.asDiagonal();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix<Real, N, N>> es(A, Eigen::EigenvaluesOnly);
  return std::sqrt(std::max<Real>(es.eigenvalues().maxCoeff(), 0.0));
}

Real damped_step(Real w, Real beta) {
  const Real xi = 0.5 * beta * w;
  // sqrt(1 + xi^2) - xi loses digits to cancellation as xi grows (about xi^2 eps of them), and
  // past xi^2's overflow read as an infinite step (a damping_beta of 1e300: "nothing limits
  // the time step", a probe's). Above xi = 1e4 it is taken as 1 / (hypot(1, xi) + xi), the same
  // quantity without the cancellation. The dampings of real cases give xi of order 1, below the
  // switch: their steps keep their bits.
  if (xi > 1e4) return (2.0 / w) / (std::hypot(1.0, xi) + xi);
  return (2.0 / w) * (std::sqrt(1.0 + xi * xi) - xi);
}

Eigen::Matrix<Real, 6, 3> b_rows(const Vec3& g) {
  Eigen::Matrix<Real, 6, 3> B = Eigen::Matrix<Real, 6, 3>::Zero();
  B(0, 0) = g(0), B(1, 1) = g(1), B(2, 2) = g(2);
  B(3, 0) = g(1), B(3, 1) = g(0);
  B(4, 1) = g(2), B(4, 2) = g(1);
  B(5, 0) = g(2), B(5, 2) = g(0);
  return B;
}
}  // namespace

StableStep element_stable_step(const FemModel& m, const std::vector<Material>& materials,
                               std::vector<Real>* per_element) {
  std::vector<Real> dt(m.n_elements, std::numeric_limits<Real>::infinity());
  for (const auto& b : m.blocks) {
    if (b.kin == Kinematics::Rigid) continue;  // rigid elements have no stiffness to limit the step
    const Index n = b.size();
#pragma omp parallel for schedule(dynamic, 256)
    for (Index e = 0; e < n; ++e) {
      const std::size_t es = static_cast<std::size_t>(e);
      const Index g = b.elem[e];
      const Real rho = materials[m.elem_material[g]].density;
      const LinearElastic el{b.lambda[e], b.mu[e]};
      if (b.type == CellType::Tet4) {
        const Eigen::Map<const Eigen::Matrix<Real, 3, 4>> grad(&b.grad[12 * es]);
        Eigen::Matrix<Real, 6, 12> B;
        for (int i = 0; i < 4; ++i) B.block<6, 3>(0, 3 * i) = b_rows(grad.col(i));
        const Eigen::Matrix<Real, 12, 12> K = b.vol[e] * B.transpose() * el.voigt() * B;
        const Eigen::Matrix<Real, 12, 1> ms = Eigen::Matrix<Real, 12, 1>::Constant(1.0 / std::sqrt(rho * b.vol[e] / 4));
        dt[g] = damped_step(max_frequency<12>(K, ms), b.beta[e]);
      } else {
        hex8::Reference r;
        r.b = Eigen::Map<const hex8::Grad>(&b.grad[24 * es]);
        r.volume = b.vol[e];
        r.gamma = Eigen::Map<const hex8::HgVec>(&b.gamma[32 * es]);
        r.k_hg = Eigen::Map<const hex8::HgStiff>(&b.khg[144 * es]);
        const hex8::Stiffness K = hex8::kernel_stiffness(r, el);
        // Equal nodal shares: exact for parallelepipeds (row-sum lumping gives 1/8 each);
        // for distorted hexes the row-sum shares differ by a few per cent.
        const Eigen::Matrix<Real, 24, 1> ms = Eigen::Matrix<Real, 24, 1>::Constant(1.0 / std::sqrt(rho * b.vol[e] / 8));
        dt[g] = damped_step(max_frequency<24>(K, ms), b.beta[e]);
      }
    }
  }
  StableStep s;
  s.dt = std::numeric_limits<Real>::infinity();
  for (Index g = 0; g < m.n_elements; ++g)
    if (dt[g] < s.dt) s.dt = dt[g], s.element = g;
  if (per_element) *per_element = std::move(dt);
  return s;
}

}  // namespace dspdem
