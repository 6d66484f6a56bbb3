#include "joint/joint_dt.hpp"

#include <cmath>
#include <limits>

namespace dspdem::joint {

StableStep stable_step_with_joints(const FemModel& m, const JointSet& js, const std::vector<Real>& per_element,
                                   const Ties* ties) {
  // Per point (a node, or a tied group at its first copy): the largest element frequency of
  // its copies, the joint springs at them, and their mass.
  const bool tied = ties != nullptr && ties->groups() > 0;
  auto point = [&](Index n) { return tied && ties->group[n] >= 0 ? ties->node[ties->ptr[ties->group[n]]] : n; };
  std::vector<Real> w2e(m.n_nodes, 0.0), kj(m.n_nodes, 0.0), mass(m.n_nodes, 0.0);
  std::vector<Index> elem_of(m.n_nodes, -1), joint_elem(m.n_nodes, -1);
  for (Index n = 0; n < m.n_nodes; ++n) mass[point(n)] += m.mass[n];
  for (const auto& b : m.blocks)
    for (Index e = 0; e < b.size(); ++e) {
      const Index g = b.elem[e];
      const Real w = 2.0 / per_element[g];
      for (int i = 0; i < b.npe(); ++i) {
        const Index n = point(b.conn[static_cast<std::size_t>(e) * b.npe() + i]);
        if (w * w > w2e[n]) w2e[n] = w * w, elem_of[n] = g;
      }
    }
  const bool skip_closed = ties != nullptr && !js.closed.empty();
  for (Index j = 0; j < js.size(); ++j) {
    // Without ties, a closed joint (extrinsic insertion) counts as if open: the step with
    // every joint open, which bounds every state's and which a fixed [time] dt must respect.
    if (skip_closed && js.closed[j]) continue;
    const CohesiveParams& p = js.params[js.param[j]];
    const Real k = max_stiffness(p) * js.area0[j] / js.npf[j];
    for (int s = 0; s < js.npf[j]; ++s) {
      const Index a = point(js.a[4 * static_cast<std::size_t>(j) + s]);
      const Index b = point(js.b[4 * static_cast<std::size_t>(j) + s]);
      if (tied && a == b) continue;  // an open face whose copies are still tied round it: no stretch
      kj[a] += k, joint_elem[a] = js.ea[j];
      kj[b] += k, joint_elem[b] = js.eb[j];
    }
  }
  StableStep s;
  s.dt = std::numeric_limits<Real>::infinity();
  for (Index n = 0; n < m.n_nodes; ++n) {
    if (point(n) != n) continue;  // a group's other copies: counted at its first
    const Real wj = 2.0 * kj[n] / mass[n];
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
