// Hex8 internal-force kernel: uniform-gradient one-point part plus hourglass
// stabilisation (see hex8.hpp). Per element, in the co-rotated frame:
//   eps = sym(R^T F) - I,  q = vec(R^T x_e Gamma^T) (hourglass coordinates, 12),
//   f = -R [ V sigma b + mat(K_hg (q + beta qdot)) Gamma ].
// Gamma annihilates rigid and linear fields, so q measures only hourglass deformation.
#include <Eigen/Dense>

#include "fem/fem_model.hpp"
#include "fem/linear_elastic.hpp"
#include "fem/polar.hpp"

namespace dspdem {

namespace {
template <bool Corot, bool Damped, bool Stress>
ForceStatus hex8_kernel(FemModel& m, const FemBlock& b, const Real* x, const Real* v, Real* stress_out,
                        ElementPass pass) {
  using M38 = Eigen::Matrix<Real, 3, 8>;
  using M34 = Eigen::Matrix<Real, 3, 4>;
  using V12 = Eigen::Matrix<Real, 12, 1>;
  const Index n = b.size();
  const Real* x0 = m.x0.data();
  Real* slots = m.slots.data() + b.slot0;
  Real* energy = m.elem_energy.data();
  Real* dpower = m.elem_dpower.data();
  Real min_det = 1.0;
#pragma omp parallel for schedule(static) reduction(min : min_det) if (n > 1024)  // tiny models: no fork-join cost
  for (Index e = 0; e < n; ++e) {
    if (!pass.takes(b.elem[e])) continue;
    const std::size_t es = static_cast<std::size_t>(e);
    const Index* c = &b.conn[8 * es];
    const Eigen::Map<const M38> grad(&b.grad[24 * es]);
    const Eigen::Map<const Eigen::Matrix<Real, 4, 8>> gamma(&b.gamma[32 * es]);
    const Eigen::Map<const Eigen::Matrix<Real, 12, 12>> khg(&b.khg[144 * es]);
    M38 u, xe;
    for (int i = 0; i < 8; ++i)
      for (int d = 0; d < 3; ++d) {
        xe(d, i) = x[3 * c[i] + d];
        u(d, i) = xe(d, i) - x0[3 * c[i] + d];
      }
    const Mat3 H = u * grad.transpose();
    const Mat3 F = Mat3::Identity() + H;
    const Real det = F.determinant();
    if (!(det > 0.0) && det < min_det) min_det = det;
    Mat3 R = Mat3::Identity();
    Mat3 eps;
    M34 Q;
    if constexpr (Corot) {
      polar_rotation(F, det, R);
      const Mat3 RtF = R.transpose() * F;
      eps = 0.5 * (RtF + RtF.transpose()) - Mat3::Identity();
      // Relative to node 0 to keep round-off independent of where the body sits.
      const M38 dx = xe.colwise() - xe.col(0);
      Q = R.transpose() * dx * gamma.transpose();
    } else {
      eps = 0.5 * (H + H.transpose());
      Q = u * gamma.transpose();
    }
    const LinearElastic law{b.lambda[e], b.mu[e]};
    const Real V = b.vol[e];
    Mat3 s = law.stress(eps);
    const V12 q = Eigen::Map<const V12>(Q.data());
    V12 kq = khg * q;
    energy[b.elem[e]] = V * law.energy_density(eps) + 0.5 * q.dot(kq);
    if constexpr (Damped) {
      M38 ve;
      for (int i = 0; i < 8; ++i)
        for (int d = 0; d < 3; ++d) ve(d, i) = v[3 * c[i] + d];
      Mat3 L = ve * grad.transpose();
      M34 Qd = ve * gamma.transpose();
      if constexpr (Corot) {
        L = R.transpose() * L;
        Qd = R.transpose() * Qd;
      }
      const Mat3 ed = 0.5 * (L + L.transpose());
      const Mat3 sd = law.stress(ed);
      const V12 qd = Eigen::Map<const V12>(Qd.data());
      const V12 kqd = khg * qd;
      const Real beta = b.beta[e];
      dpower[b.elem[e]] = beta * (V * (sd.array() * ed.array()).sum() + qd.dot(kqd));
      s += beta * sd;
      kq += beta * kqd;
    }
    const M38 fl = -(V * s * grad + Eigen::Map<const M34>(kq.data()) * gamma);
    Eigen::Map<M38>(slots + 24 * es) = R * fl;
    if constexpr (Stress) {
      const Mat3 se = law.stress(eps);
      const Mat3 sc = R * se * R.transpose();
      Real* o = stress_out + 6 * static_cast<std::size_t>(b.elem[e]);
      o[0] = sc(0, 0), o[1] = sc(1, 1), o[2] = sc(2, 2), o[3] = sc(0, 1), o[4] = sc(1, 2), o[5] = sc(0, 2);
    }
  }
  Index bad = -1;
  if (min_det <= 0.0) {
    for (Index e = 0; e < n && bad < 0; ++e) {
      if (!pass.takes(b.elem[e])) continue;
      const Index* c = &b.conn[8 * static_cast<std::size_t>(e)];
      const Eigen::Map<const M38> grad(&b.grad[24 * static_cast<std::size_t>(e)]);
      M38 xe;
      for (int i = 0; i < 8; ++i)
        for (int d = 0; d < 3; ++d) xe(d, i) = x[3 * c[i] + d];
      if (!((xe * grad.transpose()).determinant() > 0.0)) bad = b.elem[e];
    }
  }
  return {bad, min_det};
}

template <bool Corot>
ForceStatus dispatch_hex8(FemModel& m, const FemBlock& b, const Real* x, const Real* v, Real* s, ElementPass p) {
  if (b.damped)
    return s ? hex8_kernel<Corot, true, true>(m, b, x, v, s, p) : hex8_kernel<Corot, true, false>(m, b, x, v, s, p);
  return s ? hex8_kernel<Corot, false, true>(m, b, x, v, s, p) : hex8_kernel<Corot, false, false>(m, b, x, v, s, p);
}
}  // namespace

ForceStatus hex8_forces(FemModel& m, const FemBlock& b, const Real* x, const Real* v, Real* stress, ElementPass pass) {
  return b.kin == Kinematics::Corotational ? dispatch_hex8<true>(m, b, x, v, stress, pass)
                                           : dispatch_hex8<false>(m, b, x, v, stress, pass);
}

}  // namespace dspdem
