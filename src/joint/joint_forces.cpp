#include "joint/joint_forces.hpp"

#include <cmath>

#include "joint/coupled_law.hpp"

namespace dspdem::joint {

int face_quadrature(int npf, Quadrature rule, double N[4][4], double w[4]) {
  if (rule == Quadrature::Nodal) {
    for (int g = 0; g < npf; ++g) {
      for (int k = 0; k < 4; ++k) N[g][k] = g == k ? 1.0 : 0.0;
      w[g] = 1.0 / npf;
    }
    return npf;
  }
  if (npf == 3) {
    const double a = 2.0 / 3.0, b = 1.0 / 6.0;
    const double P[3][3] = {{a, b, b}, {b, a, b}, {b, b, a}};
    for (int g = 0; g < 3; ++g) {
      for (int k = 0; k < 3; ++k) N[g][k] = P[g][k];
      N[g][3] = 0;
      w[g] = 1.0 / 3.0;
    }
    return 3;
  }
  const double q = 1.0 / std::sqrt(3.0);
  const double xi[4] = {-q, q, q, -q}, eta[4] = {-q, -q, q, q};
  const double nx[4] = {-1, 1, 1, -1}, ny[4] = {-1, -1, 1, 1};
  for (int g = 0; g < 4; ++g) {
    for (int k = 0; k < 4; ++k) N[g][k] = 0.25 * (1 + nx[k] * xi[g]) * (1 + ny[k] * eta[g]);
    w[g] = 0.25;
  }
  return 4;
}

void add_joint_forces(JointSet& js, const Real* x, Real* f, std::vector<Real>& slots) {
  const Index nj = js.size();
  slots.resize(24 * static_cast<std::size_t>(nj));
  js.newly_failed.resize(nj);
#pragma omp parallel for schedule(static) if (nj > 1024)
  for (Index j = 0; j < nj; ++j) {
    const std::size_t js4 = 4 * static_cast<std::size_t>(j);
    const int npf = js.npf[j];
    Real* out = &slots[24 * static_cast<std::size_t>(j)];
    for (int k = 0; k < 24; ++k) out[k] = 0;
    js.newly_failed[j] = 0;
    if (js.released[j]) continue;
    Vec3 xa[4], xb[4], xm[4];
    for (int k = 0; k < npf; ++k) {
      xa[k] = node_pos_ptr(x, js.a[js4 + k]);
      xb[k] = node_pos_ptr(x, js.b[js4 + k]);
      xm[k] = 0.5 * (xa[k] + xb[k]);
    }
    Vec3 n = npf == 3 ? Vec3((xm[1] - xm[0]).cross(xm[2] - xm[0])) : Vec3((xm[2] - xm[0]).cross(xm[3] - xm[1]));
    const Real nl = n.norm();
    if (!(nl > 0)) continue;  // collapsed face: nothing sensible to apply (the element check reports it)
    n /= nl;
    double N[4][4], w[4];
    const int ng = face_quadrature(npf, js.rule(j), N, w);
    const CohesiveParams& p = js.params[js.param[j]];
    int broken = 0, touched = 0;
    for (int g = 0; g < ng; ++g) {
      Vec3 jump = Vec3::Zero();
      for (int k = 0; k < npf; ++k) jump += N[g][k] * (xb[k] - xa[k]);
      const Real dn = jump.dot(n);
      const Vec3 sv = jump - dn * n;
      const Real ds = sv.norm();
      CohesiveState& st = js.state[js4 + g];
      joint_law_update(p, dn, ds, st);
      broken += st.status == JointStatus::Broken;
      touched += st.status != JointStatus::Intact;
      // Traction on side B (force per area): pulls B back towards A in tension, resists slip.
      Vec3 t = -st.sn * n;
      if (ds > 0) t -= st.ss * (sv / ds);
      const Real wa = w[g] * js.area0[j];
      for (int k = 0; k < npf; ++k)
        for (int d = 0; d < 3; ++d) {
          out[3 * k + d] -= N[g][k] * wa * t(d);       // side A
          out[12 + 3 * k + d] += N[g][k] * wa * t(d);  // side B
        }
    }
    // A joint fails as a whole when any of its points fails: a facet is the crack's unit, and
    // a half-failed facet would otherwise hold two separated pieces together.
    if (broken > 0 && broken < ng)
      for (int g = 0; g < ng; ++g) force_break(js.state[js4 + g]);
    const JointStatus before = js.status[j];
    js.status[j] = broken > 0 ? JointStatus::Broken : touched > 0 ? JointStatus::Softening : JointStatus::Intact;
    js.newly_failed[j] = before != JointStatus::Broken && js.status[j] == JointStatus::Broken;
  }
  for (Index j = 0; j < nj; ++j) {
    const std::size_t js4 = 4 * static_cast<std::size_t>(j);
    const Real* s = &slots[24 * static_cast<std::size_t>(j)];
    if (js.newly_failed[j]) js.failed.push_back(j);
    for (int k = 0; k < js.npf[j]; ++k)
      for (int d = 0; d < 3; ++d) {
        f[3 * js.a[js4 + k] + d] += s[3 * k + d];
        f[3 * js.b[js4 + k] + d] += s[12 + 3 * k + d];
      }
  }
}

Real joint_elastic_energy(const JointSet& js, Index j) {
  double N[4][4], w[4];
  const int ng = face_quadrature(js.npf[j], js.rule(j), N, w);
  const CohesiveParams& p = js.params[js.param[j]];
  Real e = 0;
  for (int g = 0; g < ng; ++g)
    e += w[g] * js.area0[j] * js.state[4 * static_cast<std::size_t>(j) + g].elastic_energy(p);
  return e;
}

JointTotals joint_totals(const JointSet& js) {
  JointTotals t;
  double N[4][4], w[4];
  for (Index j = 0; j < js.size(); ++j) {
    const int ng = face_quadrature(js.npf[j], js.rule(j), N, w);
    const CohesiveParams& p = js.params[js.param[j]];
    for (int g = 0; g < ng; ++g) {
      const CohesiveState& s = js.state[4 * static_cast<std::size_t>(j) + g];
      const Real wa = w[g] * js.area0[j];
      if (!js.released[j]) t.elastic += wa * s.elastic_energy(p);
      t.fracture_I += wa * s.dissipated_I(p);
      t.fracture_II += wa * s.dissipated_II(p);
    }
    if (js.status[j] == JointStatus::Broken) ++t.broken, t.broken_area += js.area0[j];
  }
  t.fracture_II += js.released_energy;
  return t;
}

}  // namespace dspdem::joint
