#include "time/model.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include "core/error.hpp"
#include "joint/joint_dt.hpp"

namespace dspdem {

StableStep stable_step(const Model& m) {
  std::vector<Real> per_element;
  element_stable_step(m.fem, m.materials, &per_element);
  return stable_step(m, per_element);
}

StableStep stable_step(const Model& m, const std::vector<Real>& per_element, const joint::Ties* ties) {
  StableStep out;
  if (m.joints.size() > 0) {
    out = joint::stable_step_with_joints(m.fem, m.joints, per_element, ties);
  } else {
    out.dt = INFINITY;  // the smallest element step, the first element of that step named
    for (Index g = 0; g < m.fem.n_elements; ++g)
      if (per_element[g] < out.dt) out.dt = per_element[g], out.element = g;
  }
  if (!m.contact.enabled()) return out;
  // A node in contact adds the contact spring to its element stiffness: frequencies add
  // in squares (as for joints), w^2 <= w_s^2 + w_c^2.
  Index ce = -1;
  const Real dtc = m.contact.stable_dt(&ce);
  if (!(dtc < INFINITY)) return out;
  const Real dt = 1.0 / std::sqrt(1.0 / (out.dt * out.dt) + 1.0 / (dtc * dtc));
  if (dtc < out.dt) out.limiter = "contact", out.element = ce;
  out.dt = dt;
  return out;
}

}  // namespace dspdem
