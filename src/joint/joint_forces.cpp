#include "joint/joint_forces.hpp"

#include <algorithm>
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

namespace {
// The four quadrature rules (triangle/quadrilateral x Gauss/nodal), computed once.
struct QuadratureTables {
  double N[2][2][4][4], w[2][2][4];
  int ng[2][2];
  QuadratureTables() {
    for (int q = 0; q < 2; ++q)
      for (int r = 0; r < 2; ++r)
        ng[q][r] = face_quadrature(q == 0 ? 3 : 4, static_cast<Quadrature>(r), N[q][r], w[q][r]);
  }
};
const QuadratureTables& quadrature_tables() {
  static const QuadratureTables t;
  return t;
}

// For each node a joint touches, its slots in joint order (see JointSet::gather_*).
void build_gather(JointSet& js) {
  const Index nj = js.size();
  Index n_max = 0;
  for (Index j = 0; j < nj; ++j)
    for (int k = 0; k < js.npf[j]; ++k)
      n_max = std::max(
          {n_max, js.a[4 * static_cast<std::size_t>(j) + k] + 1, js.b[4 * static_cast<std::size_t>(j) + k] + 1});
  std::vector<Index> count(static_cast<std::size_t>(n_max), 0);
  for (Index j = 0; j < nj; ++j)
    for (int k = 0; k < js.npf[j]; ++k)
      ++count[js.a[4 * static_cast<std::size_t>(j) + k]], ++count[js.b[4 * static_cast<std::size_t>(j) + k]];
  std::vector<Index> row(static_cast<std::size_t>(n_max), -1);
  js.gather_node.clear();
  js.gather_ptr.assign(1, 0);
  for (Index n = 0; n < n_max; ++n)
    if (count[n] > 0) {
      row[n] = static_cast<Index>(js.gather_node.size());
      js.gather_node.push_back(n);
      js.gather_ptr.push_back(js.gather_ptr.back() + count[n]);
    }
  js.gather_slot.assign(static_cast<std::size_t>(js.gather_ptr.back()), 0);
  std::vector<Index> fill(js.gather_ptr.begin(), js.gather_ptr.end() - 1);
  // Joint order: side A before side B within a joint is the serial loop's order too.
  for (Index j = 0; j < nj; ++j)
    for (int side = 0; side < 2; ++side)
      for (int k = 0; k < js.npf[j]; ++k) {
        const Index n = (side == 0 ? js.a : js.b)[4 * static_cast<std::size_t>(j) + k];
        js.gather_slot[fill[row[n]]++] = 24 * j + 12 * side + 3 * k;
      }
  js.gather_joints = nj;
}
}  // namespace

void add_joint_forces(JointSet& js, const Real* x, Real* f, std::vector<Real>& slots) {
  const Index nj = js.size();
  if (nj == 0) return;
  if (js.gather_joints != nj) build_gather(js);
  slots.resize(24 * static_cast<std::size_t>(nj));
  js.newly_failed.resize(nj);
  const QuadratureTables& qt = quadrature_tables();
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
    const int qi = npf == 3 ? 0 : 1, ri = static_cast<int>(js.rule(j));
    const auto& N = qt.N[qi][ri];
    const auto& w = qt.w[qi][ri];
    const int ng = qt.ng[qi][ri];
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
  for (Index j = 0; j < nj; ++j)
    if (js.newly_failed[j]) js.failed.push_back(j);
  // Each node its slots in joint order: the serial loop's sums, in parallel over nodes.
  const Index ng_nodes = static_cast<Index>(js.gather_node.size());
  const Real* s = slots.data();
#pragma omp parallel for schedule(static) if (ng_nodes > 4096)
  for (Index i = 0; i < ng_nodes; ++i) {
    Real* fn = f + 3 * static_cast<std::size_t>(js.gather_node[i]);
    Real f0 = fn[0], f1 = fn[1], f2 = fn[2];
    for (Index q = js.gather_ptr[i]; q < js.gather_ptr[i + 1]; ++q) {
      const Real* sq = s + js.gather_slot[q];
      f0 += sq[0], f1 += sq[1], f2 += sq[2];
    }
    fn[0] = f0, fn[1] = f1, fn[2] = f2;
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
