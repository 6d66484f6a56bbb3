// The paper's law with the shear softening its text describes (`joint_law = "paper_residual"`),
// per integration point, in the joint's local frame: opening dn (> 0 in tension) and slip
// magnitude ds.
//
// Why: eq. 4 as printed softens the whole shear strength f_s = c - s_n tan(phi) to zero over
// w_GII = 2 G_fII / f_s, and only past the end gives the residual friction -s_n tan(phi)
// (cohesive_law.hpp follows it, as METHOD.md restates it). The text beside eq. 4 says instead
// that the shear stress "decreases gradually to the residual value of pure friction,
// f_mu = -s_n tan(phi)" (Fig. 2(b)), and that G_fII is the shaded area of that figure: the
// area above the friction line. Under a contact's compression the two readings part. At
// s_n = -500 MPa (the sphere's c 55 MPa, phi 30 deg) eq. 4 as printed takes a face from 344
// MPa to nothing over 1.2 um of slip; the text keeps its 289 MPa of friction and softens only
// the 55 MPa of cohesion, over 7.3 um.
//
//   normal : the paper's (eq. 3, cohesive_law.hpp), unchanged.
//   shear  : elastic-plastic along the slip magnitude, s_s = k_s (ds - p), |s_s| <= cap,
//            cap = f_mu + coh (1 - D), f_mu = <-s_n> tan(phi), coh = f_s(s_n) - f_mu
//            (c in compression, eq. 5's c - s_n tan(phi) in tension: the part that softens);
//            D grows with the plastic slip p of sliding on the cap, dD = |dp| / w_GII,
//            w_GII = 2 G_fII / coh, so the cohesion's triangle above the friction line holds
//            exactly G_fII whatever s_n does meanwhile; at D = 1 the face slides on friction
//            alone. A cap that falls below the traction (compression released) drops it at
//            the same slip, dissipated but no damage (no slip has happened).
//   break  : eq. 6 with b = D; then the residual friction of a broken point (cohesive_law.hpp),
//            which starts from the traction the face had, capped at f_mu: no drop to zero.
//            That friction is a vector in the face's plane; the shear before the break
//            still follows the slip's magnitude, as above.
//
// At constant s_n and growing slip this is eq. 4's curve with its softening line ending on
// the friction, as Fig. 2(b) draws it (the softening measured in plastic slip: its end lies
// (f_s - f_mu) / k_s short of the printed w_fs + w_GII, a fraction c^2 / (2 k_s G_fII) of
// w_GII in compression, 2 % for the sphere's joints). The mode-II dissipation (dissipated_II) then holds
// G_fII and the friction's work while the face slides. Unlike the residual friction of a
// broken point, the law acts on the slip's magnitude: a slip that turns without growing is
// not resisted.
// Where it differs from the printed law: once a face passes its shear strength (it unloads
// elastically from the cap, not along the secant to the origin, and keeps its friction in
// compression), and where a compressed face breaks (it keeps its friction, not zero).
#pragma once
#include "joint/cohesive_law.hpp"

namespace dspdem::joint {

/// Advances one integration point of paper_residual to opening dn and slip sl (magnitude
/// ds >= 0).
inline void residual_update(const CohesiveParams& p, Real dn, const Slip& sl, CohesiveState& s) {
  if (s.status == JointStatus::Broken) return broken_update(p, dn, sl, s);
  const Real ds = sl.ds;
  Real sn = paper_normal_traction(p, dn, s);
  Real ss;
  bool slid = false, breaks = false;
  const Real fs = shear_strength(p, sn);
  const Real mu = p.tan_phi * std::max<Real>(0.0, -sn);
  const Real coh = std::max<Real>(fs - mu, 1e-12 * std::max<Real>(p.c, 1.0));
  const Real w_GII = 2.0 * p.GfII / coh, h = coh / w_GII;
  const Real D = s.damage;
  const Real cap = D > 0 ? fs - coh * std::min<Real>(D, 1.0) : fs;
  const Real el = ds - s.ds_plastic;
  // Elastic at the end of the step: the same test as the paper's law (ds <= w_fs while
  // undamaged), so a lean point (lean_point.hpp) is one this law keeps elastic too.
  if (std::abs(el) <= cap / p.ks) {
    ss = p.ks * el;
  } else {
    slid = true;  // past the strength (perhaps by rounding alone): softening from now on
    // As residual_friction: first the traction above a cap that fell (compression
    // released) drops at the old slip, its energy dissipated but no damage done (no slip
    // has happened: session 54's rule for the paper's law); then the slip's increment goes
    // elastic and slides on the cap. The dissipation is booked exactly, path by path
    // (diss_II_at_break, until the break).
    Real e = s.ss;
    s.diss_II_at_break += drop_to_cap(e, cap, p.ks);
    const Real trial = e + p.ks * (ds - s.ds), t = std::abs(trial), sign = trial > 0 ? 1.0 : -1.0;
    const Real dp_soft = p.ks > h ? (t - cap) / (p.ks - h) : INFINITY;
    if (t <= cap) {
      ss = trial;
    } else if (D + dp_soft / w_GII < 1.0) {
      // Slides by dp with the cohesion softening along it (modulus h in plastic slip):
      // k_s (t - dp) = cap - h dp; dissipated, the cap's mean along dp times dp.
      s.diss_II_at_break += (cap - 0.5 * h * dp_soft) * dp_soft;
      s.damage = D + dp_soft / w_GII;
      ss = sign * (t - p.ks * dp_soft);
    } else {
      // The cohesion is spent within the step: it softens to the friction over dp1, and the
      // rest of the slip slides on the friction alone. Where k_s <= h (a softening steeper
      // than the penalty) it goes at once, the traction above the friction released.
      const Real dp = (t - mu) / p.ks, dp1 = (1.0 - std::min<Real>(D, 1.0)) * w_GII;
      s.diss_II_at_break += p.ks > h ? 0.5 * (cap + mu) * dp1 + mu * (dp - dp1) : (t * t - mu * mu) / (2.0 * p.ks);
      s.damage = p.ks > h ? D + dp / w_GII : std::max<Real>(1.0, D + dp / w_GII);  // >= 1: broken
      ss = sign * (t - p.ks * dp);                                                 // the friction mu
    }
    s.ds_plastic = ds - ss / p.ks;
  }
  if (eq6_broken(p, s.dn_max, s.damage)) {
    // Broken: no tension, no cohesion; the friction keeps what it can carry, and the rest
    // of the shear traction is released at this slip (dissipated).
    s.status = JointStatus::Broken;
    breaks = true;
    sn = dn < 0 ? p.kn * dn : 0.0;
    s.diss_II_at_break += drop_to_cap(ss, p.tan_phi * std::max<Real>(0.0, -sn), p.ks);
  } else if (s.dn_max > p.ft / p.kn || s.damage > 0 || slid) {
    s.status = JointStatus::Softening;
  }
  // The work of the tractions, as the other laws book it; this law's dissipation is booked
  // exactly above (CohesiveState::dissipated_II).
  s.advance(dn, sl, sn, ss);
  if (breaks) s.start_friction(p);  // from what the shear kept, along this slip
}

/// Fails a point of paper_residual that has not reached eq. 6 itself, because its joint
/// failed elsewhere: no tension and no cohesion from now on; its shear keeps what the
/// residual friction can carry at its normal traction (none if it is open), the rest is
/// released (dissipated). (The paper's law drops the shear to zero: force_break.)
inline void residual_force_break(const CohesiveParams& p, CohesiveState& s) {
  if (s.status == JointStatus::Broken) return;
  s.status = JointStatus::Broken;
  const Real before = s.ss;
  s.diss_II_at_break += drop_to_cap(s.ss, s.dn < 0 ? p.tan_phi * std::max<Real>(0.0, -s.sn) : 0.0, p.ks);
  // This step's forces carried the shear before the drop: the next update books the work of
  // what was dropped (as force_break's), the friction's own trapezoid starting from the rest.
  s.ss_forced = before - s.ss;
  s.start_friction(p);  // from what the shear kept, along the last slip
}

}  // namespace dspdem::joint
