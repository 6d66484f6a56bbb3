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
// Every rule has as many points as the face has nodes (joint_kernel relies on it).
struct QuadratureTables {
  double N[2][2][4][4], w[2][2][4];
  QuadratureTables() {
    for (int q = 0; q < 2; ++q)
      for (int r = 0; r < 2; ++r) face_quadrature(q == 0 ? 3 : 4, static_cast<Quadrature>(r), N[q][r], w[q][r]);
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
  // Joint order: side A before side B within a joint is the serial loop's order too. A slot
  // is stored as 2 x (offset of side A's force) + side: side B's force is exactly -A's, so
  // only A's is kept and side B's nodes subtract it (f - a is f + (-a) to the bit).
  for (Index j = 0; j < nj; ++j)
    for (int side = 0; side < 2; ++side)
      for (int k = 0; k < js.npf[j]; ++k) {
        const Index n = (side == 0 ? js.a : js.b)[4 * static_cast<std::size_t>(j) + k];
        js.gather_slot[fill[row[n]]++] = 2 * (12 * j + 3 * k) + side;
      }
  js.gather_joints = nj;
}

// One joint of NPF nodes (and NPF points, Gauss or nodal): side A's nodal forces into
// out[0..3 NPF) (side B's are exactly their opposite). The face size and the rule are template
// parameters so that every loop has a fixed trip count and nodal quadrature skips its zero
// shape values. The arithmetic, and its order, is add_joint_forces_reference's; with nodal
// quadrature the skipped terms are products with 0 and 1, which change no bit of the sums
// (the first term is written 0 - y, as the oracle's +0 - y, so that no -0 appears).
template <int NPF, bool NODAL>
void joint_kernel(JointSet& js, Index j, const Real* x, const double (&N)[4][4], const double (&w)[4], Real* out) {
  const std::size_t js4 = 4 * static_cast<std::size_t>(j);
  Vec3 xa[NPF], dx[NPF], xm[NPF];
  for (int k = 0; k < NPF; ++k) {
    xa[k] = node_pos_ptr(x, js.a[js4 + k]);
    const Vec3 xb = node_pos_ptr(x, js.b[js4 + k]);
    dx[k] = xb - xa[k];
    xm[k] = 0.5 * (xa[k] + xb);
  }
  Vec3 n = NPF == 3 ? Vec3((xm[1] - xm[0]).cross(xm[2] - xm[0])) : Vec3((xm[2] - xm[0]).cross(xm[3] - xm[1]));
  const Real nl = n.norm();
  if (!(nl > 0)) {  // collapsed face: nothing sensible to apply (the element check reports it)
    for (int k = 0; k < 3 * NPF; ++k) out[k] = 0;
    return;
  }
  n /= nl;
  const CohesiveParams& p = js.params[js.param[j]];
  Real fa[3 * NPF] = {};
  int broken = 0, touched = 0;
  for (int g = 0; g < NPF; ++g) {
    Vec3 jump;
    if constexpr (NODAL) {
      jump = dx[g];
    } else {
      jump = Vec3::Zero();
      for (int k = 0; k < NPF; ++k) jump += N[g][k] * dx[k];
    }
    const Real dn = jump.dot(n);
    const Vec3 sv = jump - dn * n;
    const Real ds = sv.norm();
    // An elastic point stays lean (lean_point.hpp); any other runs its law on the full state.
    Real sn, ss;
    if (js.full[js4 + g] || !lean_update(p, dn, ds, js.lean[js4 + g], sn, ss)) {
      CohesiveState& st = js.full_point(js4 + g);
      joint_law_update(p, dn, ds, st);
      broken += st.status == JointStatus::Broken;
      touched += st.status != JointStatus::Intact;
      sn = st.sn, ss = st.ss;
    }
    // Traction on side B (force per area): pulls B back towards A in tension, resists slip.
    Vec3 t = -sn * n;
    if (ds > 0) t -= (ss / ds) * sv;
    const Real wa = w[g] * js.area0[j];
    if constexpr (NODAL) {
      for (int d = 0; d < 3; ++d) fa[3 * g + d] = 0.0 - wa * t(d);
    } else {
      for (int k = 0; k < NPF; ++k)
        for (int d = 0; d < 3; ++d) fa[3 * k + d] -= N[g][k] * wa * t(d);
    }
  }
  for (int k = 0; k < 3 * NPF; ++k) out[k] = fa[k];
  // A joint fails as a whole when any of its points fails: a facet is the crack's unit, and
  // a half-failed facet would otherwise hold two separated pieces together.
  if (broken > 0 && broken < NPF)
    for (int g = 0; g < NPF; ++g) force_break(js.full_point(js4 + g));
  const JointStatus before = js.status[j];
  js.status[j] = broken > 0 ? JointStatus::Broken : touched > 0 ? JointStatus::Softening : JointStatus::Intact;
  js.newly_failed[j] = before != JointStatus::Broken && js.status[j] == JointStatus::Broken;
}

// The node positions joint j will read, asked for ahead of time: after the Hilbert order the
// nodes of nearby joints are close, but not in the cache when the joint comes up.
inline void prefetch_joint(const JointSet& js, Index j, const Real* x) {
  const std::size_t js4 = 4 * static_cast<std::size_t>(j);
  for (int k = 0; k < js.npf[j]; ++k) {
    __builtin_prefetch(x + 3 * static_cast<std::size_t>(js.a[js4 + k]));
    __builtin_prefetch(x + 3 * static_cast<std::size_t>(js.b[js4 + k]));
  }
}
}  // namespace

void add_joint_forces(JointSet& js, const Real* x, Real* f, std::vector<Real>& slots) {
  const Index nj = js.size();
  if (nj == 0) return;
  if (js.gather_joints != nj) build_gather(js);
  slots.resize(12 * static_cast<std::size_t>(nj));
  js.newly_failed.resize(nj);
  const QuadratureTables& qt = quadrature_tables();
  constexpr Index ahead = 8;  // joints between a prefetch and its use
#pragma omp parallel for schedule(static) if (nj > 1024)
  for (Index j = 0; j < nj; ++j) {
    if (j + ahead < nj) prefetch_joint(js, j + ahead, x);
    Real* out = &slots[12 * static_cast<std::size_t>(j)];
    js.newly_failed[j] = 0;
    if (js.released[j]) {
      for (int k = 0; k < 12; ++k) out[k] = 0;
      continue;
    }
    const int ri = static_cast<int>(js.rule(j));
    const bool nodal = js.rule(j) == Quadrature::Nodal;
    if (js.npf[j] == 3)
      nodal ? joint_kernel<3, true>(js, j, x, qt.N[0][ri], qt.w[0][ri], out)
            : joint_kernel<3, false>(js, j, x, qt.N[0][ri], qt.w[0][ri], out);
    else
      nodal ? joint_kernel<4, true>(js, j, x, qt.N[1][ri], qt.w[1][ri], out)
            : joint_kernel<4, false>(js, j, x, qt.N[1][ri], qt.w[1][ri], out);
  }
  for (Index j = 0; j < nj; ++j)
    if (js.newly_failed[j]) js.failed.push_back(j);
  // Each node its slots in joint order: the serial loop's sums, in parallel over nodes.
  // Side B's slots hold side A's force: subtracted, which is adding its opposite exactly.
  const Index ng_nodes = static_cast<Index>(js.gather_node.size());
  const Real* s = slots.data();
#pragma omp parallel for schedule(static) if (ng_nodes > 4096)
  for (Index i = 0; i < ng_nodes; ++i) {
    Real* fn = f + 3 * static_cast<std::size_t>(js.gather_node[i]);
    Real f0 = fn[0], f1 = fn[1], f2 = fn[2];
    for (Index q = js.gather_ptr[i]; q < js.gather_ptr[i + 1]; ++q) {
      const Index e = js.gather_slot[q];
      const Real* sq = s + (e >> 1);
      if (e & 1)
        f0 -= sq[0], f1 -= sq[1], f2 -= sq[2];
      else
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
    e += w[g] * js.area0[j] * js.point_state(4 * static_cast<std::size_t>(j) + g).elastic_energy(p);
  return e;
}

JointTotals joint_totals(const JointSet& js) {
  JointTotals t;
  double N[4][4], w[4];
  for (Index j = 0; j < js.size(); ++j) {
    const int ng = face_quadrature(js.npf[j], js.rule(j), N, w);
    const CohesiveParams& p = js.params[js.param[j]];
    for (int g = 0; g < ng; ++g) {
      const CohesiveState s = js.point_state(4 * static_cast<std::size_t>(j) + g);
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
