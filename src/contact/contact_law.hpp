// Contact force law of one feature pair (paper eqs. 12-13), a pure function: linear normal
// spring on the overlap with optional viscous damping (never pulling), and an incremental
// tangential spring (with optional viscous damping while sticking) whose history is rotated
// into the current tangent plane and capped by Coulomb friction. Energies are returned so
// the ledger can be exact. Tangential damping matters: undamped tangential springs ring
// at their own high frequency and make the contact stick in part of every period, so a
// sliding block meets less than mu N on average (a 2x2x2 hex block on a slope slid 25 %
// too fast).
#pragma once
#include <algorithm>
#include <cmath>

#include "core/types.hpp"

namespace dspdem::contact {

struct LawParams {
  Real kn = 0;  ///< normal stiffness [N/m]
  Real kt = 0;  ///< tangential stiffness [N/m]
  Real mu = 0;  ///< Coulomb friction coefficient
  Real cn = 0;  ///< normal damping coefficient [N s/m]
  Real ct = 0;  ///< tangential damping coefficient while sticking [N s/m]
};

struct LawResult {
  Vec3 force = Vec3::Zero();                                ///< on A (B gets the opposite)
  Real elastic = 0;                                         ///< stored energy after the update [J]
  Real slip_work = 0;                                       ///< energy dissipated by sliding in this update [J]
  Real damping_power = 0;                                   ///< rate of viscous dissipation [W]
  Vec3 damping_n = Vec3::Zero(), damping_t = Vec3::Zero();  ///< viscous parts of the force (on A)
};

/// overlap > 0; n unit from B to A; vrel = velocity of A minus velocity of B at the
/// contact point; xi = tangential spring elongation (history), updated in place.
inline LawResult contact_law(const LawParams& p, Real overlap, const Vec3& n, const Vec3& vrel, Real dt, Vec3& xi) {
  LawResult r;
  const Real vn = vrel.dot(n);
  const Real fe = p.kn * overlap;
  const Real fn = std::max<Real>(0.0, fe - p.cn * vn);
  r.damping_power = (fn - fe) * -vn;  // the viscous part times the approach speed
  r.damping_n = (fn - fe) * n;
  // Rotate the history into the current tangent plane keeping its length.
  const Real len = xi.norm();
  xi -= xi.dot(n) * n;
  const Real len2 = xi.norm();
  if (len2 > 0) xi *= len / len2;
  const Vec3 vt = vrel - vn * n, xi_old = xi, du = vt * dt;
  xi += du;
  const Real cap = p.mu * fe;
  Vec3 ft = -p.kt * xi - p.ct * vt;
  const Real ftn = ft.norm();
  if (ftn > cap) {
    // Slide: the force stays at the Coulomb cap, carried by the spring alone.
    ft *= cap / ftn;
    xi = p.kt > 0 ? Vec3(-ft / p.kt) : Vec3::Zero();
  } else {
    r.damping_power += p.ct * vt.squaredNorm();
    r.damping_t = -p.ct * vt;
  }
  // Dissipated = work put in by the relative motion (trapezoidal, force from the spring
  // before and after) minus the change of stored energy: zero while sticking, cap x slip
  // while sliding, and exact when the cap drops with the normal force.
  if (p.kt > 0) r.slip_work = 0.5 * p.kt * (xi_old.squaredNorm() + (xi_old + xi).dot(du) - xi.squaredNorm());
  r.force = fn * n + ft;
  r.elastic = 0.5 * p.kn * overlap * overlap + (p.kt > 0 ? 0.5 * p.kt * xi.squaredNorm() : 0.0);
  return r;
}

}  // namespace dspdem::contact
