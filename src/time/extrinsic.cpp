#include "time/extrinsic.hpp"

#include <algorithm>

namespace dspdem {

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
    // The face's current normal from A to B, as the joint kernel takes it (a closed face's
    // two sides coincide).
    Vec3 xm[4];
    for (int k = 0; k < js.npf[j]; ++k) xm[k] = node_pos_ptr(x, js.a[j4 + k]);
    Vec3 n = js.npf[j] == 3 ? Vec3((xm[1] - xm[0]).cross(xm[2] - xm[0])) : Vec3((xm[2] - xm[0]).cross(xm[3] - xm[1]));
    const Real nl = n.norm();
    if (!(nl > 0)) continue;
    n /= nl;
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
  Index count = 0;
  for (Index j = 0; j < nj; ++j) {
    if (!open_[j]) continue;
    ++count;
    js.closed[j] = 0;
    const std::size_t j4 = 4 * static_cast<std::size_t>(j);
    const joint::CohesiveParams& p = js.params[js.param[j]];
    const Real tn = traction_[j4];
    const Vec3 ts(traction_[j4 + 1], traction_[j4 + 2], traction_[j4 + 3]);
    // Every point of the face starts where its law's elastic branch gives the face's traction.
    joint::CohesiveState s;
    s.dn = tn / p.kn;
    s.ds = ts.norm() / p.ks;
    s.dn_max = std::max<Real>(0.0, s.dn);
    s.ds_max = s.ds;
    s.sn = p.kn * s.dn, s.ss = p.ks * s.ds;
    for (int g = 0; g < js.npf[j]; ++g) {
      Real* o = &js.offset[4 * (j4 + g)];
      o[0] = s.dn;
      for (int d = 0; d < 3; ++d) o[1 + d] = ts(d) / p.ks;
      js.state[j4 + g] = s;
      js.full[j4 + g] = 1;
    }
  }
  if (count > 0) it.retie();
  opened_ += count;
  return count;
}

}  // namespace dspdem
