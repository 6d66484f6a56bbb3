// Tet4 internal-force kernel. Per element:
//   F = I + sum_I u_I (x) b_I,   R = polar rotation of F (identity for small strain),
//   eps = sym(R^T F) - I,  epsdot = sym(R^T sum_I v_I (x) b_I),
//   sigma = C : (eps + beta epsdot),   f_I = -V R sigma b_I.
// With an isotropic law sigma is coaxial with U, so f is the exact gradient of the strain
// energy V W(eps) for the co-rotational path too.
#include <Eigen/Dense>

#include "fem/fem_model.hpp"
#include "fem/linear_elastic.hpp"
#include "fem/polar.hpp"

namespace dspdem {

namespace {
template <bool Corot, bool Damped, bool Stress>
ForceStatus tet4_kernel(FemModel& m, const FemBlock& b, const Real* x, const Real* v, Real* stress_out,
                        ElementPass pass) {
  const Index n = b.size();
  const Real* x0 = m.x0.data();
  Real* slots = m.slots.data() + b.slot0;
  Real* energy = m.elem_energy.data();
  Real* dpower = m.elem_dpower.data();
  Index bad = -1;
  Real min_det = 1.0;
#pragma omp parallel for schedule(static) reduction(min : min_det) if (n > 1024)  // tiny models: no fork-join cost
  for (Index e = 0; e < n; ++e) {
    if (!pass.takes(b.elem[e])) continue;
    const Index* c = &b.conn[4 * static_cast<std::size_t>(e)];
    const Eigen::Map<const Eigen::Matrix<Real, 3, 4>> grad(&b.grad[12 * static_cast<std::size_t>(e)]);
    Eigen::Matrix<Real, 3, 4> u;
    for (int i = 0; i < 4; ++i)
      for (int d = 0; d < 3; ++d) u(d, i) = x[3 * c[i] + d] - x0[3 * c[i] + d];
    const Mat3 H = u * grad.transpose();
    const Mat3 F = Mat3::Identity() + H;
    Mat3 R = Mat3::Identity();
    Mat3 eps;
    const Real det = F.determinant();
    if constexpr (Corot) {
      polar_rotation(F, det, R);
      const Mat3 RtF = R.transpose() * F;
      eps = 0.5 * (RtF + RtF.transpose()) - Mat3::Identity();
    } else {
      eps = 0.5 * (H + H.transpose());
    }
    if (!(det > 0.0) && det < min_det) min_det = det;
    const LinearElastic law{b.lambda[e], b.mu[e]};
    const Real V = b.vol[e];
    Mat3 s = law.stress(eps);
    energy[b.elem[e]] = V * law.energy_density(eps);
    if constexpr (Damped) {
      Eigen::Matrix<Real, 3, 4> ve;
      for (int i = 0; i < 4; ++i)
        for (int d = 0; d < 3; ++d) ve(d, i) = v[3 * c[i] + d];
      Mat3 L = ve * grad.transpose();
      if constexpr (Corot) L = R.transpose() * L;
      const Mat3 ed = 0.5 * (L + L.transpose());
      const Mat3 sd = law.stress(ed);
      dpower[b.elem[e]] = V * b.beta[e] * (sd.array() * ed.array()).sum();
      s += b.beta[e] * sd;
    }
    const Eigen::Matrix<Real, 3, 4> fl = -V * (R * s) * grad;
    Eigen::Map<Eigen::Matrix<Real, 3, 4>>(slots + 12 * static_cast<std::size_t>(e)) = fl;
    if constexpr (Stress) {
      // Output stress is the elastic part only: damping stress is not a material state.
      const Mat3 se = law.stress(eps);
      const Mat3 sc = R * se * R.transpose();
      Real* o = stress_out + 6 * static_cast<std::size_t>(b.elem[e]);
      o[0] = sc(0, 0), o[1] = sc(1, 1), o[2] = sc(2, 2), o[3] = sc(0, 1), o[4] = sc(1, 2), o[5] = sc(0, 2);
    }
  }
  if (min_det <= 0.0) {
    // Serial pass to name the first inverted element deterministically.
    for (Index e = 0; e < n && bad < 0; ++e) {
      if (!pass.takes(b.elem[e])) continue;
      const Index* c = &b.conn[4 * static_cast<std::size_t>(e)];
      Vec3 p[4];
      for (int i = 0; i < 4; ++i) p[i] = Vec3(x[3 * c[i]], x[3 * c[i] + 1], x[3 * c[i] + 2]);
      if (!((p[1] - p[0]).cross(p[2] - p[0]).dot(p[3] - p[0]) > 0.0)) bad = b.elem[e];
    }
  }
  return {bad, min_det};
}

template <bool Corot>
ForceStatus dispatch_tet4(FemModel& m, const FemBlock& b, const Real* x, const Real* v, Real* s, ElementPass p) {
  if (b.damped)
    return s ? tet4_kernel<Corot, true, true>(m, b, x, v, s, p) : tet4_kernel<Corot, true, false>(m, b, x, v, s, p);
  return s ? tet4_kernel<Corot, false, true>(m, b, x, v, s, p) : tet4_kernel<Corot, false, false>(m, b, x, v, s, p);
}
}  // namespace

ForceStatus tet4_forces(FemModel& m, const FemBlock& b, const Real* x, const Real* v, Real* stress, ElementPass pass) {
  return b.kin == Kinematics::Corotational ? dispatch_tet4<true>(m, b, x, v, stress, pass)
                                           : dispatch_tet4<false>(m, b, x, v, stress, pass);
}

}  // namespace dspdem
