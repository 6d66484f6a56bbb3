#include "joint/joint_dt.hpp"

#include <cmath>
#include <limits>

namespace dspdem::joint {

StableStep stable_step_with_joints(const FemModel& m, const JointSet& js, const std::vector<Real>& per_element) {
  std::vector<Real> w2e(m.n_nodes, 0.0), kj(m.n_nodes, 0.0);
  std::vector<Index> elem_of(m.n_nodes, -1), joint_elem(m.n_nodes, -1);
  for (const auto& b : m.blocks)
    for (Index e = 0; e < b.size(); ++e) {
      const Index g = b.elem[e];
      const Real w = 2.0 / per_element[g];
      for (int i = 0; i < b.npe(); ++i) {
        const Index n = b.conn[static_cast<std::size_t>(e) * b.npe() + i];
        if (w * w > w2e[n]) w2e[n] = w * w, elem_of[n] = g;
      }
    }
  for (Index j = 0; j < js.size(); ++j) {
    // A closed joint (extrinsic insertion) has no spring yet, but may open at any step: the
    // step allows for it from the start, so that it never has to change.
    const CohesiveParams& p = js.params[js.param[j]];
    const Real k = max_stiffness(p) * js.area0[j] / js.npf[j];
    for (int s = 0; s < js.npf[j]; ++s) {
      kj[js.a[4 * static_cast<std::size_t>(j) + s]] += k,
          joint_elem[js.a[4 * static_cast<std::size_t>(j) + s]] = js.ea[j];
      kj[js.b[4 * static_cast<std::size_t>(j) + s]] += k,
          joint_elem[js.b[4 * static_cast<std::size_t>(j) + s]] = js.eb[j];
    }
  }
  StableStep s;
  s.dt = std::numeric_limits<Real>::infinity();
  for (Index n = 0; n < m.n_nodes; ++n) {
    const Real wj = 2.0 * kj[n] / m.mass[n];
    const Real dt = 2.0 / std::sqrt(w2e[n] + wj);
    if (dt < s.dt) {
      s.dt = dt;
      const bool joint = wj > w2e[n];
      s.limiter = joint ? "joint" : "element";
      s.element = joint ? joint_elem[n] : elem_of[n];
    }
  }
  return s;
}

}  // namespace dspdem::joint
