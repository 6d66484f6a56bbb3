// The joint kernel as plainly as it can be written: one joint after another, its quadrature
// computed on the spot, its forces added to the nodes at once. The oracle of the optimised
// add_joint_forces (tests/unit/test_joint_kernel.cpp): both must agree bit for bit.
#include "joint/joint_forces.hpp"
#include "joint/joint_law.hpp"

namespace dspdem::joint {

void add_joint_forces_reference(JointSet& js, const Real* x, Real* f) {
  const Index nj = js.size();
  js.newly_failed.assign(nj, 0);
  for (Index j = 0; j < nj; ++j) {
    const std::size_t js4 = 4 * static_cast<std::size_t>(j);
    const int npf = js.npf[j];
    if (js.inactive(j)) continue;
    Vec3 xa[4], xb[4], xm[4];
    for (int k = 0; k < npf; ++k) {
      xa[k] = node_pos_ptr(x, js.a[js4 + k]);
      xb[k] = node_pos_ptr(x, js.b[js4 + k]);
      xm[k] = 0.5 * (xa[k] + xb[k]);
    }
    Vec3 n = npf == 3 ? Vec3((xm[1] - xm[0]).cross(xm[2] - xm[0])) : Vec3((xm[2] - xm[0]).cross(xm[3] - xm[1]));
    const Real nl = n.norm();
    if (!(nl > 0)) continue;
    n /= nl;
    double N[4][4], w[4];
    const int ng = face_quadrature(npf, js.rule(j), N, w);
    const CohesiveParams& p = js.params[js.param[j]];
    const FaceFrame frame(FaceFrame::line(npf, xm), n);
    Real out[24] = {};
    int broken = 0, touched = 0;
    for (int g = 0; g < ng; ++g) {
      Vec3 jump = Vec3::Zero();
      for (int k = 0; k < npf; ++k) jump += N[g][k] * (xb[k] - xa[k]);
      Real dn = jump.dot(n);
      Vec3 sv = jump - dn * n;
      if (!js.offset.empty()) apply_offset(&js.offset[4 * (js4 + g)], frame, dn, sv);
      const Real ds = sv.norm();
      CohesiveState& st = js.full_point(js4 + g);  // the oracle keeps every point in full
      joint_law_update(p, dn, frame.slip(sv, ds), st);
      broken += st.status == JointStatus::Broken;
      touched += st.status != JointStatus::Intact;
      Vec3 t = -st.sn * n;
      if (st.status == JointStatus::Broken)
        t -= frame.vector(st.fu, st.fv);
      else if (ds > 0)
        t -= (st.ss / ds) * sv;
      const Real wa = w[g] * js.area0[j];
      for (int k = 0; k < npf; ++k)
        for (int d = 0; d < 3; ++d) {
          out[3 * k + d] -= N[g][k] * wa * t(d);
          out[12 + 3 * k + d] += N[g][k] * wa * t(d);
        }
    }
    if (broken > 0 && broken < ng)
      for (int g = 0; g < ng; ++g) joint_force_break(p, js.full_point(js4 + g));
    const JointStatus before = js.status[j];
    js.status[j] = broken > 0 ? JointStatus::Broken : touched > 0 ? JointStatus::Softening : JointStatus::Intact;
    js.newly_failed[j] = before != JointStatus::Broken && js.status[j] == JointStatus::Broken;
    if (js.newly_failed[j]) js.failed.push_back(j);
    for (int k = 0; k < npf; ++k)
      for (int d = 0; d < 3; ++d) {
        f[3 * js.a[js4 + k] + d] += out[3 * k + d];
        f[3 * js.b[js4 + k] + d] += out[12 + 3 * k + d];
      }
  }
}

}  // namespace dspdem::joint
