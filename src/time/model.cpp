#include "time/model.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include "core/error.hpp"
#include "joint/joint_dt.hpp"

namespace dspdem {

StableStep stable_step(const Model& m) {
  std::vector<Real> per_element;
  const StableStep s = element_stable_step(m.fem, m.materials, &per_element);
  StableStep out = m.joints.size() == 0 ? s : joint::stable_step_with_joints(m.fem, m.joints, per_element);
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
