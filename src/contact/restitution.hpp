// Restitution of the contact law's normal part (contact_law.hpp): a linear spring and a
// linear dashpot that may push but never pull. Because the force is cut off once the
// dashpot would pull, the two bodies part before the spring is unloaded and the
// restitution is higher than the textbook exp(-zeta pi / sqrt(1 - zeta^2)) of a dashpot
// that pulls (zeta 0.2155 gives 0.550, not 0.500). The closed form for the cut-off law is
// Schwager and Poeschel, "Coefficient of restitution and linear-dashpot model revisited",
// Granular Matter 9 (2007) 465-469; both branches (zeta below and above 1/sqrt 2) are one
// expression with atan2. Pure functions, tested in tests/unit/test_contact_law.cpp.
#pragma once
#include <cmath>

#include "core/types.hpp"

namespace dspdem::contact {

/// Restitution of a head-on contact of damping ratio zeta in [0, 1) (fraction of the
/// critical c = 2 sqrt(k m) of the two masses on the spring): 1 at 0, falling to e^-2 at 1.
inline Real restitution_of_damping(Real zeta) {
  if (zeta <= 0) return 1.0;
  if (zeta >= 1) return std::exp(-2.0);
  const Real s = std::sqrt(1 - zeta * zeta);
  return std::exp(-zeta / s * (M_PI - std::atan2(2 * zeta * s, 1 - 2 * zeta * zeta)));
}

/// The damping ratio that gives restitution e in [e^-2, 1]: the inverse of
/// restitution_of_damping (monotone), by bisection to 1e-12.
inline Real damping_for_restitution(Real e) {
  if (e >= 1) return 0.0;
  Real lo = 0, hi = 1;
  while (hi - lo > 1e-12) {
    const Real mid = 0.5 * (lo + hi);
    (restitution_of_damping(mid) > e ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

/// Smallest restitution the law can give (zeta = 1).
inline Real min_restitution() { return std::exp(-2.0); }

}  // namespace dspdem::contact
