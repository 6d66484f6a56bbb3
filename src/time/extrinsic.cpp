#include "time/extrinsic.hpp"

#include <algorithm>
#include <array>

#include "joint/min_cut.hpp"

namespace dspdem {

namespace {
// The current unit normal of closed face j from A to B, as the joint kernel takes it (a closed
// face's two sides coincide); zero for a degenerate face.
Vec3 face_normal(const joint::JointSet& js, const Real* x, Index j) {
  const std::size_t j4 = 4 * static_cast<std::size_t>(j);
  Vec3 xm[4];
  for (int k = 0; k < js.npf[j]; ++k) xm[k] = node_pos_ptr(x, js.a[j4 + k]);
  const Vec3 n =
      js.npf[j] == 3 ? Vec3((xm[1] - xm[0]).cross(xm[2] - xm[0])) : Vec3((xm[2] - xm[0]).cross(xm[3] - xm[1]));
  const Real nl = n.norm();
  return nl > 0 ? Vec3(n / nl) : Vec3::Zero();
}

// The frame of closed face j's plane (joint::FaceFrame) of unit normal n, as the joint kernel
// will take it (a closed face's two sides coincide).
joint::FaceFrame face_frame(const joint::JointSet& js, const Real* x, Index j, const Vec3& n) {
  const std::size_t j4 = 4 * static_cast<std::size_t>(j);
  Vec3 xm[4];
  for (int k = 0; k < js.npf[j]; ++k) xm[k] = node_pos_ptr(x, js.a[j4 + k]);
  return joint::FaceFrame(joint::FaceFrame::line(js.npf[j], xm), n);
}

// Opens closed joint j: every point of the face starts where its law's elastic branch gives
// the traction t (normal part tn, shear vector ts) the face carries. The offset's slip is
// kept on the face's frame, so that it turns with the face as the face's own slip does.
void open_face(joint::JointSet& js, const Real* x, Index j, Real tn, const Vec3& ts) {
  js.closed[j] = 0;
  const std::size_t j4 = 4 * static_cast<std::size_t>(j);
  const joint::CohesiveParams& p = js.params[js.param[j]];
  // The slip offset's components; none on a collapsed face (no plane, no frame: the kernel
  // runs no law there), which a cut front can open.
  const Vec3 n = face_normal(js, x, j);
  Real u0 = 0, v0 = 0;
  if (!n.isZero()) {
    const joint::FaceFrame f = face_frame(js, x, j, n);
    u0 = ts.dot(f.e1) / p.ks, v0 = ts.dot(f.e2) / p.ks;
  }
  joint::CohesiveState s;
  s.dn = tn / p.kn;
  s.ds = ts.norm() / p.ks;
  s.dn_max = std::max<Real>(0.0, s.dn);
  s.sn = p.kn * s.dn, s.ss = p.ks * s.ds;
  for (int g = 0; g < js.npf[j]; ++g) {
    Real* o = &js.offset[4 * (j4 + g)];
    o[0] = s.dn;
    o[1] = u0, o[2] = v0, o[3] = 0.0;
    js.state[j4 + g] = s;
    js.full[j4 + g] = 1;
  }
}
}  // namespace

Index ExtrinsicInsertion::check(Model& m, Integrator& it) {
  joint::JointSet& js = m.joints;
  if (js.closed.empty()) return 0;
  it.keep_stresses_every(interval_);  // the steps checked keep their force evaluation's stresses
  if (it.steps() % interval_ != 0) return 0;
  it.stresses(stress_);
  const Real* x = it.x().data();
  const Index nj = js.size();
  open_.assign(static_cast<std::size_t>(nj), 0);
  traction_.resize(4 * static_cast<std::size_t>(nj));
  // The screen: a face whose elements' stresses are too small for any traction on it to
  // reach its law's onset is not tested (most faces, most of the time).
  if (static_cast<Index>(floor_.size()) != nj) {
    floor_.resize(static_cast<std::size_t>(nj));
    for (Index j = 0; j < nj; ++j) floor_[j] = joint::onset_floor(js.params[js.param[j]]);
  }
  const Index ne = static_cast<Index>(stress_.size() / 6);
  bound_.resize(static_cast<std::size_t>(ne));
#pragma omp parallel for schedule(static) if (ne > 4096)
  for (Index e = 0; e < ne; ++e) bound_[e] = joint::stress_bound(&stress_[6 * static_cast<std::size_t>(e)]);
#pragma omp parallel for schedule(static) if (nj > 1024)
  for (Index j = 0; j < nj; ++j) {
    // (A margin of 1e-9 keeps rounding in the bound from screening a face at its onset.)
    const Real ba = bound_[js.ea[j]], bb = bound_[js.eb[j]];
    const Real bound = stress_rule_ == joint::FaceStress::Mean ? 0.5 * (ba + bb) : std::max(ba, bb);
    if (!js.closed[j] || bound * (1 + 1e-9) < floor_[j]) continue;
    const std::size_t j4 = 4 * static_cast<std::size_t>(j);
    const Vec3 n = face_normal(js, x, j);
    if (n.isZero()) continue;
    const Real* sa = &stress_[6 * static_cast<std::size_t>(js.ea[j])];
    const Real* sb = &stress_[6 * static_cast<std::size_t>(js.eb[j])];
    const joint::FaceOnset fo = joint::face_onset(js.params[js.param[j]], sa, sb, n, stress_rule_);
    if (fo.ratio < 1) continue;
    const Real tn = fo.t.dot(n);
    const Vec3 ts = fo.t - tn * n;
    open_[j] = 1;
    traction_[j4] = tn;
    for (int d = 0; d < 3; ++d) traction_[j4 + 1 + d] = ts(d);
  }
  std::vector<Index> opened;
  for (Index j = 0; j < nj; ++j) {
    if (!open_[j]) continue;
    opened.push_back(j);
    const std::size_t j4 = 4 * static_cast<std::size_t>(j);
    open_face(js, x, j, traction_[j4], Vec3(traction_[j4 + 1], traction_[j4 + 2], traction_[j4 + 3]));
  }
  Index count = static_cast<Index>(opened.size());
  if (front_ == InsertionFront::Cut && count > 0) {
    const Index forced = cut_fronts(js, x, opened);
    forced_ += forced, count += forced;
  }
  if (count > 0) it.retie();
  opened_ += count;
  return count;
}

Index ExtrinsicInsertion::cut_fronts(joint::JointSet& js, const Real* x, const std::vector<Index>& opened) {
  const Index nj = js.size();
  if (node_ptr_.empty() || joints_indexed_ != nj) {  // the joints at each node (fixed topology)
    joints_indexed_ = nj;
    Index nn = 0;
    for (Index v : js.a) nn = std::max(nn, v + 1);
    for (Index v : js.b) nn = std::max(nn, v + 1);
    node_ptr_.assign(static_cast<std::size_t>(nn) + 1, 0);
    for (Index j = 0; j < nj; ++j)
      for (int k = 0; k < js.npf[j]; ++k)
        ++node_ptr_[js.a[4 * static_cast<std::size_t>(j) + k] + 1],
            ++node_ptr_[js.b[4 * static_cast<std::size_t>(j) + k] + 1];
    for (Index i = 0; i < nn; ++i) node_ptr_[i + 1] += node_ptr_[i];
    node_joint_.resize(static_cast<std::size_t>(node_ptr_.back()));
    std::vector<Index> fill(node_ptr_.begin(), node_ptr_.end() - 1);
    for (Index j = 0; j < nj; ++j)
      for (int k = 0; k < js.npf[j]; ++k)
        node_joint_[fill[js.a[4 * static_cast<std::size_t>(j) + k]]++] = j,
                                                                node_joint_[fill[js.b[4 * static_cast<std::size_t>(j) +
                                                                                      k]]++] = j;
    local_.assign(static_cast<std::size_t>(nn), -1);
  }
  // The copy across joint j from copy c (the same original node on the other side).
  auto across = [&](Index j, Index c) {
    const std::size_t j4 = 4 * static_cast<std::size_t>(j);
    for (int k = 0; k < js.npf[j]; ++k) {
      if (js.a[j4 + k] == c) return js.b[j4 + k];
      if (js.b[j4 + k] == c) return js.a[j4 + k];
    }
    return Index{-1};
  };
  Index forced = 0;
  std::vector<Index> star;               // the copies tied to s, in the order reached
  std::vector<Index> edge_joint;         // per edge of the star, its closed joint
  std::vector<std::array<int, 2>> edge;  // its two copies, as vertices of the star
  std::vector<Real> cap;
  std::vector<Vec3> traction, normal;  // per edge: the face's mean traction and its normal
  for (Index j : opened)
    for (int k = 0; k < js.npf[j]; ++k) {
      const Index s = js.a[4 * static_cast<std::size_t>(j) + k], t = js.b[4 * static_cast<std::size_t>(j) + k];
      // The copies tied to s through closed faces (breadth first), and those faces.
      star.assign(1, s), edge_joint.clear(), edge.clear();
      local_[s] = 0;
      for (std::size_t q = 0; q < star.size(); ++q)
        for (Index p = node_ptr_[star[q]]; p < node_ptr_[star[q] + 1]; ++p) {
          const Index jj = node_joint_[p];
          if (!js.closed[jj]) continue;
          const Index o = across(jj, star[q]);
          if (local_[o] < 0) local_[o] = static_cast<Index>(star.size()), star.push_back(o);
          if (star[q] < o)
            edge_joint.push_back(jj), edge.push_back({static_cast<int>(local_[star[q]]), static_cast<int>(local_[o])});
        }
      const bool tied = local_[t] >= 0;
      const int tv = tied ? static_cast<int>(local_[t]) : -1;
      for (Index c : star) local_[c] = -1;
      if (!tied) continue;
      // Each face costs how far its traction (the two elements' mean) stands from its onset,
      // so that the cut runs through the faces nearest to opening by themselves.
      cap.resize(edge.size()), traction.resize(edge.size()), normal.resize(edge.size());
      for (std::size_t e = 0; e < edge.size(); ++e) {
        const Index jj = edge_joint[e];
        normal[e] = face_normal(js, x, jj);
        const joint::FaceOnset fo =
            joint::face_onset(js.params[js.param[jj]], &stress_[6 * static_cast<std::size_t>(js.ea[jj])],
                              &stress_[6 * static_cast<std::size_t>(js.eb[jj])], normal[e], joint::FaceStress::Mean);
        cap[e] = std::max<Real>(1e-3, 1 - fo.ratio);
        traction[e] = fo.t;
      }
      for (int e : joint::min_cut(static_cast<int>(star.size()), edge, cap, 0, tv)) {
        const Real tn = traction[e].dot(normal[e]);
        open_face(js, x, edge_joint[e], tn, traction[e] - tn * normal[e]);
        ++forced;
      }
    }
  return forced;
}

}  // namespace dspdem
