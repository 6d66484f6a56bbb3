#include "joint/joint_forces.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

#include "joint/joint_law.hpp"
#include "joint/lane4.hpp"

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
  js.gather_active.resize(static_cast<std::size_t>(nj));
  for (Index j = 0; j < nj; ++j) js.gather_active[j] = !js.inactive(j);
  Index n_max = 0;
  for (Index j = 0; j < nj; ++j)
    for (int k = 0; k < js.npf[j]; ++k)
      n_max = std::max(
          {n_max, js.a[4 * static_cast<std::size_t>(j) + k] + 1, js.b[4 * static_cast<std::size_t>(j) + k] + 1});
  std::vector<Index> count(static_cast<std::size_t>(n_max), 0);
  for (Index j = 0; j < nj; ++j)
    for (int k = 0; k < js.npf[j] && js.gather_active[j]; ++k)
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
    for (int side = 0; side < 2 && js.gather_active[j]; ++side)
      for (int k = 0; k < js.npf[j]; ++k) {
        const Index n = (side == 0 ? js.a : js.b)[4 * static_cast<std::size_t>(j) + k];
        js.gather_slot[fill[row[n]]++] = 2 * (12 * j + 3 * k) + side;
      }
  js.gather_joints = nj;
}

// B consecutive joints of NPF nodes each (and NPF points, Gauss or nodal): side A's nodal
// forces of joint j0 + b into out[12 b ..) (side B's are exactly their opposite). The joints
// are taken phase by phase (geometry, then the points' kinematics, then the laws, then the
// forces), so that the square roots and divisions of different joints are independent and
// overlap: one joint alone is a single chain of them, and its latency was the kernel's cost.
// The face size and the rule are template parameters so that every loop has a fixed trip
// count and nodal quadrature skips its zero shape values. The arithmetic of each joint, and
// its order, is add_joint_forces_reference's; with nodal quadrature the skipped terms are
// products with 0 and 1, which change no bit of the sums (the first term is written 0 - y, as
// the oracle's +0 - y, so that no -0 appears).
template <int NPF, bool NODAL, int B>
void joint_kernel(JointSet& js, Index j0, const Real* x, const double (&N)[4][4], const double (&w)[4], Real* out) {
  Vec3 dx[B][NPF], n[B], edge[B];
  bool live[B];
  // The face's frame: for every live joint when there are extrinsic offsets (they are kept on
  // it), else at first need: only a point kept in full needs it (a lean point's law takes the
  // slip's magnitude alone). (Its emplace is compiled out of line, 3.5 % of the sphere's run at
  // 7.5 m/s; a plain array with a flag instead ran that run at 1.01-1.26 times the wall time,
  // median 1.03 over three pairs, session 106, and made frames early 1.04-1.09, session 105.)
  std::optional<FaceFrame> frame[B];
  for (int b = 0; b < B; ++b) {
    const std::size_t js4 = 4 * static_cast<std::size_t>(j0 + b);
    Vec3 xm[NPF];
    for (int k = 0; k < NPF; ++k) {
      const Vec3 xa = node_pos_ptr(x, js.a[js4 + k]), xb = node_pos_ptr(x, js.b[js4 + k]);
      dx[b][k] = xb - xa;
      xm[k] = 0.5 * (xa + xb);
    }
    edge[b] = FaceFrame::line(NPF, xm);  // for the face's frame, if a point needs it
    n[b] = NPF == 3 ? Vec3((xm[1] - xm[0]).cross(xm[2] - xm[0])) : Vec3((xm[2] - xm[0]).cross(xm[3] - xm[1]));
    const Real nl = n[b].norm();
    live[b] = nl > 0;  // a collapsed face: nothing sensible to apply (the element check reports it)
    if (live[b]) n[b] /= nl;
    if (live[b] && !js.offset.empty()) frame[b].emplace(edge[b], n[b]);  // the offsets are on it
  }
  Real dn[B][NPF], ds[B][NPF];
  Vec3 sv[B][NPF];
  for (int b = 0; b < B; ++b)
    for (int g = 0; g < NPF; ++g) {
      Vec3 jump;
      if constexpr (NODAL) {
        jump = dx[b][g];
      } else {
        jump = Vec3::Zero();
        for (int k = 0; k < NPF; ++k) jump += N[g][k] * dx[b][k];
      }
      dn[b][g] = jump.dot(n[b]);
      sv[b][g] = jump - dn[b][g] * n[b];
      if (!js.offset.empty() && live[b])  // (a collapsed face's law is not run)
        apply_offset(&js.offset[16 * static_cast<std::size_t>(j0 + b) + 4 * g], *frame[b], dn[b][g], sv[b][g]);
      ds[b][g] = sv[b][g].norm();
    }
  Real sn[B][NPF], ss[B][NPF];
  // A broken point's friction, a vector on the face's frame; fr: the point has one.
  Real fu[B][NPF], fv[B][NPF];
  bool fr[B][NPF] = {};
  int broken[B] = {}, touched[B] = {};
  for (int b = 0; b < B; ++b) {
    if (!live[b]) continue;
    const std::size_t js4 = 4 * static_cast<std::size_t>(j0 + b);
    const CohesiveParams& p = js.params[js.param[j0 + b]];
    for (int g = 0; g < NPF; ++g)
      // An elastic point stays lean (lean_point.hpp); any other runs its law on the full state.
      if (js.full[js4 + g] || !lean_update(p, dn[b][g], ds[b][g], js.lean[js4 + g], sn[b][g], ss[b][g])) {
        CohesiveState& st = js.full_point(js4 + g);
        if (!frame[b]) frame[b].emplace(edge[b], n[b]);
        const Slip sl = frame[b]->slip(sv[b][g], ds[b][g]);
        // A broken point's update is the same under every law, and small: called here, inlined
        // (the laws' dispatch is not, cohesive_law.hpp).
        if (st.status == JointStatus::Broken)
          broken_update(p, dn[b][g], sl, st);
        else
          joint_law_update(p, dn[b][g], sl, st);
        broken[b] += st.status == JointStatus::Broken;
        touched[b] += st.status != JointStatus::Intact;
        sn[b][g] = st.sn, ss[b][g] = st.ss;
        fr[b][g] = st.status == JointStatus::Broken, fu[b][g] = st.fu, fv[b][g] = st.fv;
      }
  }
  for (int b = 0; b < B; ++b) {
    const Index j = j0 + b;
    Real* o = out + 12 * b;
    if (!live[b]) {
      for (int k = 0; k < 3 * NPF; ++k) o[k] = 0;
      continue;
    }
    Real fa[3 * NPF] = {};
    for (int g = 0; g < NPF; ++g) {
      // Traction on side B (force per area): pulls B back towards A in tension, resists slip.
      Vec3 t = -sn[b][g] * n[b];
      if (fr[b][g])
        t -= frame[b]->vector(fu[b][g], fv[b][g]);
      else if (ds[b][g] > 0)
        t -= (ss[b][g] / ds[b][g]) * sv[b][g];
      const Real wa = w[g] * js.area0[j];
      if constexpr (NODAL) {
        for (int d = 0; d < 3; ++d) fa[3 * g + d] = 0.0 - wa * t(d);
      } else {
        for (int k = 0; k < NPF; ++k)
          for (int d = 0; d < 3; ++d) fa[3 * k + d] -= N[g][k] * wa * t(d);
      }
    }
    for (int k = 0; k < 3 * NPF; ++k) o[k] = fa[k];
    // A joint fails as a whole when any of its points fails: a facet is the crack's unit, and
    // a half-failed facet would otherwise hold two separated pieces together.
    const std::size_t js4 = 4 * static_cast<std::size_t>(j);
    if (broken[b] > 0 && broken[b] < NPF)
      for (int g = 0; g < NPF; ++g) {
        // A lean point keeps the slip's magnitude alone: a forced break needs its components
        // too (its friction starts along the slip, and the dropped shear's work is booked
        // along it at the next update).
        const bool lean = !js.full[js4 + g];
        CohesiveState& st = js.full_point(js4 + g);
        if (lean) {
          if (!frame[b]) frame[b].emplace(edge[b], n[b]);
          const Slip sl = frame[b]->slip(sv[b][g], ds[b][g]);
          st.su = sl.u, st.sv = sl.v;
        }
        joint_force_break(js.params[js.param[j]], st);
      }
    const JointStatus before = js.status[j];
    js.status[j] = broken[b] > 0 ? JointStatus::Broken : touched[b] > 0 ? JointStatus::Softening : JointStatus::Intact;
    js.newly_failed[j] = before != JointStatus::Broken && js.status[j] == JointStatus::Broken;
  }
}

// The common case, before anything cracks: four joints of one face size and rule, under one
// law, with all their points lean and elastic. The four joints are the four lanes of
// lane::V4, so each operation of joint_kernel<NPF, NODAL, 4> is one operation for the four:
// the same arithmetic in the same order (so the same bits; the oracle test checks it, for
// every face size and rule), without the per-joint square root and division latencies of the
// scalar kernel. Returns false, having written nothing, when the batch is not that case or
// when any point may leave its elastic branch (lean_update's tests, taken conservatively):
// the caller then runs the scalar kernel, which decides exactly.
template <int NPF, bool NODAL>
bool lean_batch(JointSet& js, Index j0, const Real* x, const double (&N)[4][4], const double (&w)[4], Real* out) {
  using lane::V4;
  const std::size_t p0 = 4 * static_cast<std::size_t>(j0);
  if (!js.offset.empty()) return false;  // extrinsic joints: the scalar kernel adds the offsets
  const JointLaw law = js.params[js.param[j0]].law;
  for (int b = 0; b < 4; ++b) {
    if (js.params[js.param[j0 + b]].law != law) return false;
    for (int g = 0; g < NPF; ++g)
      if (js.full[p0 + 4 * b + g]) return false;
  }
  // Lane b is joint j0 + b (each joint has its own parameters: the penalty follows its
  // elements' size).
  const CohesiveParams* P[4];
  for (int b = 0; b < 4; ++b) P[b] = &js.params[js.param[j0 + b]];
  auto par = [&](Real CohesiveParams::*m) { return V4::gather(&(P[0]->*m), &(P[1]->*m), &(P[2]->*m), &(P[3]->*m)); };
  const Index* ja = &js.a[p0];
  const Index* jb = &js.b[p0];
  auto pos = [x](const Index* nodes, int k, int d) {
    return V4::gather(
        x + 3 * static_cast<std::size_t>(nodes[k]) + d, x + 3 * static_cast<std::size_t>(nodes[4 + k]) + d,
        x + 3 * static_cast<std::size_t>(nodes[8 + k]) + d, x + 3 * static_cast<std::size_t>(nodes[12 + k]) + d);
  };
  // A lean point's fields, lane b from point 4 (j0 + b) + g.
  constexpr std::size_t stride = 4 * sizeof(LeanPoint) / sizeof(Real);
  static_assert(sizeof(LeanPoint) == 3 * sizeof(Real));
  auto lean = [&](int g, Real LeanPoint::*m) {
    const Real* q = &(js.lean[p0 + g].*m);
    return V4::gather(q, q + stride, q + 2 * stride, q + 3 * stride);
  };
  const V4 zero = V4::set1(0.0), half = V4::set1(0.5);
  V4 dx[NPF][3], xm[NPF][3];
  for (int k = 0; k < NPF; ++k)
    for (int d = 0; d < 3; ++d) {
      const V4 A = pos(ja, k, d), B = pos(jb, k, d);
      dx[k][d] = B - A;
      xm[k][d] = half * (A + B);
    }
  // The scalar kernel's normal: (x1 - x0) x (x2 - x0) on a triangle, the diagonals'
  // (x2 - x0) x (x3 - x1) on a quadrilateral.
  V4 e1[3], e2[3];
  for (int d = 0; d < 3; ++d)
    e1[d] = xm[NPF == 3 ? 1 : 2][d] - xm[0][d], e2[d] = NPF == 3 ? xm[2][d] - xm[0][d] : xm[3][d] - xm[1][d];
  V4 n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
  const V4 nl = lane::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  if (!lane::all(lane::gt(nl, zero))) return false;  // a collapsed face: the scalar kernel's case
  for (int d = 0; d < 3; ++d) n[d] = n[d] / nl;
  const V4 kn = par(&CohesiveParams::kn), ks = par(&CohesiveParams::ks), ft = par(&CohesiveParams::ft),
           c = par(&CohesiveParams::c), tan_phi = par(&CohesiveParams::tan_phi);
  const V4 area0 = V4::load(&js.area0[j0]);
  V4 ok = lane::gt(nl, zero);  // all set
  V4 dn[NPF], ds[NPF], sv[NPF][3], sn[NPF], ss[NPF], dn_max[NPF];
  for (int g = 0; g < NPF; ++g) {
    // The jump at point g: at a node, the node pair's; at a Gauss point, summed over the
    // nodes from zero as the scalar kernel sums it.
    V4 jump[3];
    for (int d = 0; d < 3; ++d) {
      if constexpr (NODAL) {
        jump[d] = dx[g][d];
      } else {
        jump[d] = zero;
        for (int k = 0; k < NPF; ++k) jump[d] = jump[d] + V4::set1(N[g][k]) * dx[k][d];
      }
    }
    dn[g] = jump[0] * n[0] + jump[1] * n[1] + jump[2] * n[2];
    for (int d = 0; d < 3; ++d) sv[g][d] = jump[d] - dn[g] * n[d];
    ds[g] = lane::sqrt(sv[g][0] * sv[g][0] + sv[g][1] * sv[g][1] + sv[g][2] * sv[g][2]);
    // lean_update, lane by lane.
    sn[g] = kn * dn[g];
    ss[g] = ks * ds[g];
    const V4 lp_dn_max = lean(g, &LeanPoint::dn_max);
    if (law == JointLaw::Coupled) {
      const V4 un = lane::max(zero, dn[g]);
      const V4 fs = c + lane::max(zero, lane::neg(kn) * dn[g]) * tan_phi;
      const V4 an = kn * un * fs, as = ks * ds[g] * ft, lim = ft * fs;
      ok = ok & lane::lt(an * an + as * as, V4::set1(0.98) * lim * lim);
      dn_max[g] = lane::max(lp_dn_max, dn[g]);
    } else {
      dn_max[g] = lane::select(lane::gt(dn[g], zero), lane::max(lp_dn_max, dn[g]), lp_dn_max);
      ok = ok & lane::lt(dn_max[g] * kn, ft * V4::set1(1 - 1e-12));
      if (law != JointLaw::ModeI) {
        const V4 fs = lane::max(c - lane::min(sn[g], ft) * tan_phi, V4::set1(1e-12) * lane::max(c, V4::set1(1.0)));
        ok = ok & lane::lt(ds[g] * ks, fs * V4::set1(1 - 1e-12));
      }
    }
  }
  if (!lane::all(ok)) return false;
  // Forces of side A; written only now that every lane is known to be elastic. At a node the
  // point's force is its node's (0 - y, as the scalar kernel writes it); Gauss points spread
  // theirs over the nodes, point after point, from zero.
  V4 fa[NPF][3];
  if constexpr (!NODAL)
    for (int k = 0; k < NPF; ++k)
      for (int d = 0; d < 3; ++d) fa[k][d] = zero;
  for (int g = 0; g < NPF; ++g) {
    V4 t[3];
    const V4 slip = lane::gt(ds[g], zero), r = ss[g] / lane::select(slip, ds[g], V4::set1(1.0));
    for (int d = 0; d < 3; ++d)
      t[d] = lane::select(slip, lane::neg(sn[g]) * n[d] - r * sv[g][d], lane::neg(sn[g]) * n[d]);
    const V4 wa = V4::set1(w[g]) * area0;
    for (int d = 0; d < 3; ++d) {
      if constexpr (NODAL) {
        (zero - wa * t[d]).scatter(out + 3 * g + d, 12);
      } else {
        for (int k = 0; k < NPF; ++k) fa[k][d] = fa[k][d] - V4::set1(N[g][k]) * wa * t[d];
      }
    }
    LeanPoint& l = js.lean[p0 + g];
    dn[g].scatter(&l.dn, stride), ds[g].scatter(&l.ds, stride);
    dn_max[g].scatter(&l.dn_max, stride);
  }
  if constexpr (!NODAL)
    for (int k = 0; k < NPF; ++k)
      for (int d = 0; d < 3; ++d) fa[k][d].scatter(out + 3 * k + d, 12);
  // A triangle's 4th slot (3 numbers) is not written, as the scalar kernel leaves it.
  for (int b = 0; b < 4; ++b) js.status[j0 + b] = JointStatus::Intact;
  return true;
}

// Joints j0 .. j0 + B - 1 with the same face size and rule, all active: one batch.
template <int B>
bool uniform_batch(const JointSet& js, Index j0) {
  for (int b = 0; b < B; ++b)
    if (js.inactive(j0 + b) || js.npf[j0 + b] != js.npf[j0] || js.rule(j0 + b) != js.rule(j0)) return false;
  return true;
}

// Calls k.template operator()<NPF, NODAL>(N, w) with the face size and rule of joint j0 and
// their quadrature tables: the one place where the run-time face maps onto the kernels'
// template arguments.
template <class K>
decltype(auto) with_face(const JointSet& js, Index j0, const QuadratureTables& qt, K&& k) {
  const int ri = static_cast<int>(js.rule(j0));
  const bool nodal = js.rule(j0) == Quadrature::Nodal;
  const int fi = js.npf[j0] == 3 ? 0 : 1;
  const auto& N = qt.N[fi][ri];
  const auto& w = qt.w[fi][ri];
  if (fi == 0) return nodal ? k.template operator()<3, true>(N, w) : k.template operator()<3, false>(N, w);
  return nodal ? k.template operator()<4, true>(N, w) : k.template operator()<4, false>(N, w);
}

template <int B>
void run_kernel(JointSet& js, Index j0, const Real* x, const QuadratureTables& qt, Real* out) {
  with_face(js, j0, qt, [&]<int NPF, bool NODAL>(const auto& N, const auto& w) {
    joint_kernel<NPF, NODAL, B>(js, j0, x, N, w, out);
  });
}
bool run_lean_batch(JointSet& js, Index j0, const Real* x, const QuadratureTables& qt, Real* out) {
  return with_face(js, j0, qt, [&]<int NPF, bool NODAL>(const auto& N, const auto& w) {
    return lean_batch<NPF, NODAL>(js, j0, x, N, w, out);
  });
}
}  // namespace

void add_joint_forces(JointSet& js, const Real* x, Real* f, std::vector<Real>& slots) {
  const Index nj = js.size();
  if (nj == 0) return;
  // An inactive joint's slots are left out of the gather (they would add zeros), so the
  // gather follows the active set. Checking it is a pass over three byte arrays.
  bool stale = js.gather_joints != nj;
  for (Index j = 0; !stale && j < nj; ++j) stale = js.gather_active[j] != static_cast<char>(!js.inactive(j));
  if (stale) build_gather(js);
  slots.resize(12 * static_cast<std::size_t>(nj));
  js.newly_failed.resize(nj);
  const QuadratureTables& qt = quadrature_tables();
  constexpr Index batch = 4;
  const Index nb = (nj + batch - 1) / batch;
#pragma omp parallel for schedule(static) if (nj > 1024)
  for (Index q = 0; q < nb; ++q) {
    const Index j0 = batch * q, j1 = std::min(j0 + batch, nj);
    bool any = false;
    for (Index j = j0; j < j1; ++j) js.newly_failed[j] = 0, any = any || js.gather_active[j];
    if (!any) continue;  // nothing of this batch is gathered
    if (j1 - j0 == batch && uniform_batch<batch>(js, j0)) {
      Real* out = &slots[12 * static_cast<std::size_t>(j0)];
      if (!run_lean_batch(js, j0, x, qt, out)) run_kernel<batch>(js, j0, x, qt, out);
      continue;
    }
    for (Index j = j0; j < j1; ++j) {
      Real* out = &slots[12 * static_cast<std::size_t>(j)];
      if (js.inactive(j))
        for (int k = 0; k < 12; ++k) out[k] = 0;
      else
        run_kernel<1>(js, j, x, qt, out);
    }
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

Real remove_joint_forces(const JointSet& js, const std::vector<Index>& joints, const std::vector<Real>& slots,
                         const Real* v, Real h, const std::vector<char>& owned, Real* f) {
  Real work = 0;
  for (Index j : joints) {
    const Real* s = &slots[12 * static_cast<std::size_t>(j)];  // side A's forces; side B's are their opposite
    Real p = 0;
    for (int k = 0; k < js.npf[j]; ++k) {
      const std::size_t a = 3 * static_cast<std::size_t>(js.a[4 * static_cast<std::size_t>(j) + k]);
      const std::size_t b = 3 * static_cast<std::size_t>(js.b[4 * static_cast<std::size_t>(j) + k]);
      for (int d = 0; d < 3; ++d) {
        f[a + d] -= s[3 * k + d], f[b + d] += s[3 * k + d];
        p += s[3 * k + d] * (v[a + d] - v[b + d]);
      }
    }
    if (owned.empty() || owned[j]) work += 0.5 * h * p;
  }
  return work;
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

JointTotals joint_totals(const JointSet& js, const std::vector<char>& owned) {
  JointTotals t;
  double N[4][4], w[4];
  for (Index j = 0; j < js.size(); ++j) {
    if (!owned.empty() && !owned[j]) continue;
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
  // Joints are released by contact; a distributed run books each one's energy on the
  // process that owns it (contact::ContactSystem), so the shares add up.
  t.fracture_II += js.released_energy;
  return t;
}

}  // namespace dspdem::joint
