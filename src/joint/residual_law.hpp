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
//            D grows with the plastic slip p, dD = |dp| / w_GII, w_GII = 2 G_fII / coh, so
//            the cohesion's triangle above the friction line holds exactly G_fII whatever
//            s_n does meanwhile; at D = 1 the face slides on friction alone.
//   break  : eq. 6 with b = D; then the residual friction of a broken point (cohesive_law.hpp),
//            which starts from the traction the face had, capped at f_mu: no drop to zero.
//
// At constant s_n and growing slip this is eq. 4's curve with its softening line ending on
// the friction, as Fig. 2(b) draws it (the softening measured in plastic slip: its end lies
// (f_s - f_mu) / k_s short of the printed w_fs + w_GII, a fraction f_s^2 / (2 k_s G_fII) of
// w_GII, 2 % at the sphere's strength). The mode-II dissipation (dissipated_II) then holds
// G_fII and the friction's work while the face slides. Like the residual friction, the law
// acts on the slip's magnitude: a slip that turns without growing is not resisted.
#pragma once
#include "joint/cohesive_law.hpp"

namespace dspdem::joint {

/// Advances one integration point of paper_residual to opening dn and slip magnitude ds >= 0.
inline void residual_update(const CohesiveParams& p, Real dn, Real ds, CohesiveState& s) {
  Real sn = paper_normal_traction(p, dn, s);
  Real ss;
  bool slid = false;
  if (s.status == JointStatus::Broken) {
    ss = residual_friction(p, sn, ds, s);
  } else {
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
      // released) drops at the old slip, its energy dissipated; then the slip's increment
      // goes elastic and slides on the cap, the cohesion softening along the plastic slip
      // dp (softening modulus h): k_s (|trial| - dp) = cap - h dp. Past D = 1 the rest
      // slides on friction alone, as it does at once where k_s <= h. The dissipation is
      // booked exactly, path by path (diss_II_at_break, until the break).
      Real e = s.ss;
      if (std::abs(e) > cap) {
        s.diss_II_at_break += (e * e - cap * cap) / (2.0 * p.ks);
        e = e > 0 ? cap : -cap;
      }
      const Real trial = e + p.ks * (ds - s.ds), t = std::abs(trial);
      if (t <= cap) {
        ss = trial;
      } else {
        Real dp = p.ks > h ? (t - cap) / (p.ks - h) : INFINITY;
        if (D + dp / w_GII < 1.0) {
          s.diss_II_at_break += (cap - 0.5 * h * dp) * dp;  // the mean of the cap along dp
        } else {
          dp = (t - mu) / p.ks;
          const Real dp1 = (1.0 - std::min<Real>(D, 1.0)) * w_GII;  // softening to the friction
          s.diss_II_at_break += dp1 <= dp ? 0.5 * (cap + mu) * dp1 + mu * (dp - dp1) : 0.5 * (t + mu) * dp;
        }
        s.damage = D + dp / w_GII;
        ss = trial > 0 ? t - p.ks * dp : p.ks * dp - t;
      }
      s.ds_plastic = ds - ss / p.ks;
    }
  }
  if (s.status != JointStatus::Broken) {
    const Real w_ft = p.ft / p.kn, w_GI = 2.0 * p.GfI / p.ft;
    const Real a = std::max<Real>(0.0, s.dn_max - w_ft) / w_GI, b = s.damage;
    if (a * a + b * b >= 1.0) {
      // Broken (eq. 6): no tension, no cohesion; the friction keeps what it can carry, and
      // the rest of the shear traction is released at this slip (dissipated).
      s.status = JointStatus::Broken;
      sn = dn < 0 ? p.kn * dn : 0.0;
      const Real cap = p.tan_phi * std::max<Real>(0.0, -sn);
      const Real kept = std::clamp(ss, -cap, cap);
      s.diss_II_at_break += (ss * ss - kept * kept) / (2.0 * p.ks);
      ss = kept;
      s.ds_plastic = ds - ss / p.ks;
    } else if (s.dn_max > w_ft || s.damage > 0 || slid) {
      s.status = JointStatus::Softening;
    }
  }
  // The work of the tractions, as the other laws book it (the ledger's dissipation of this
  // law is booked exactly above: CohesiveState::dissipated_II).
  s.work_n += 0.5 * (s.sn + sn) * (dn - s.dn);
  s.work_s += 0.5 * (s.ss + ss) * (ds - s.ds);
  s.dn = dn, s.ds = ds, s.sn = sn, s.ss = ss;
}

/// Fails a point of paper_residual that has not reached eq. 6 itself, because its joint
/// failed elsewhere: no tension and no cohesion from now on; its shear keeps what the
/// residual friction can carry at its normal traction (none if it is open), the rest is
/// released (dissipated).
inline void residual_force_break(const CohesiveParams& p, CohesiveState& s) {
  if (s.status == JointStatus::Broken) return;
  s.status = JointStatus::Broken;
  const Real cap = s.dn < 0 ? p.tan_phi * std::max<Real>(0.0, -s.sn) : 0.0;
  const Real kept = std::clamp(s.ss, -cap, cap);
  s.diss_II_at_break += (s.ss * s.ss - kept * kept) / (2.0 * p.ks);
  s.ss = kept;
  s.ds_plastic = s.ds - s.ss / p.ks;
}

}  // namespace dspdem::joint
