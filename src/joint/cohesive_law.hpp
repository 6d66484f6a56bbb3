// Cohesive joint law of the paper (eqs. 1-6; README M2), per integration point,
// in the joint's local frame: opening dn (> 0 in tension) and slip magnitude ds (and, for a
// broken point's friction, the slip's components on the face's frame: Slip).
//
//   mode I : w_ft = f_t / k_n, w_GI = 2 G_fI / f_t
//            dn <= w_ft           : s_n = k_n dn  (compression too: a penalty, no damage)
//            w_ft <= dn < w_ft+w_GI: s_n = f_t (1 - (dn - w_ft) / w_GI)
//   mode II: f_s = c - s_n tan(phi) for s_n < f_t, else c - f_t tan(phi)
//            w_fs = f_s / k_s, w_GII = 2 G_fII / f_s, same shape in ds
//   failure (mixed mode, eq. 6): (<dn_max - w_ft>/w_GI)^2 + b^2 >= 1, b the largest
//            <ds - w_fs>/w_GII reached (see irreversibility below)
//
// Decisions where the paper is silent (tested in tests/unit/test_cohesive_law.cpp):
//  - irreversibility: the largest opening reached is a history variable; below it the
//    joint unloads and reloads along the secant to the origin; it never heals. In shear the
//    envelope moves with s_n (Mohr-Coulomb), so the history is the damage b = <ds - w_fs> /
//    w_GII at its largest, each time with the w_fs, w_GII of that moment's s_n (as the
//    coupled law keeps its damage): the largest slip against the current strength would
//    count a slip that was elastic under compression as damage once the compression is
//    released. The secant stiffness is kept as a history variable that can only decrease:
//    otherwise more compression at a damaged slip would raise s_s and a closed path could
//    create energy (seen in a notched-bar run);
//  - compression is a penalty and never damages the joint;
//  - once broken, a joint carries no tension; in compression it keeps the normal penalty and
//    a Coulomb residual friction |s_s| <= -s_n tan(phi), elastic-plastic on the slip vector
//    in the face's plane (its components on a frame that turns with the face, Slip): the
//    friction is a vector, a tangential spring capped radially, as the contacts' are. (Until
//    session 104 it followed the slip's magnitude alone: a slip turning without growing was
//    not resisted, and one passing back through zero kept the friction's sign, so that it
//    pushed along the motion for cap / k_s; REFERENCE.md.)
//  - energy: the work of the tractions is integrated (trapezoid) per mode; dissipation is
//    work minus the recoverable elastic energy (1/2 s dn on the secant), so at complete
//    separation mode-I dissipation is G_fI + f_t^2 / (2 k_n); residual friction books, step
//    by step, the trapezoid work less its stored energy's change, never negative
//    (residual_friction).
#pragma once
#include <algorithm>
#include <cmath>

#include "core/error.hpp"
#include "core/types.hpp"

namespace dspdem::joint {

/// Which law a joint follows: the paper's (eqs. 3-6: normal and shear soften independently,
/// coupled only by the break test), the coupled mixed-mode law of coupled_law.hpp (one
/// damage variable softens both together), or mode I only (the paper's normal law; the
/// shear stays elastic until the joint breaks in opening, as the paper's impact beam with
/// its "shear strength set high enough").
/// The fourth, paper_residual (residual_law.hpp), is the paper's law with the shear softening
/// as its text and Fig. 2(b) describe it: the cohesion softens, the friction stays.
enum class JointLaw : char { Paper = 0, Coupled = 1, ModeI = 2, PaperResidual = 3 };

struct CohesiveParams {
  Real kn = 0, ks = 0;     ///< penalty stiffness [Pa/m]
  Real ft = 0;             ///< tensile strength [Pa]
  Real GfI = 0, GfII = 0;  ///< fracture energies [J/m^2]
  Real c = 0;              ///< cohesion [Pa]
  Real tan_phi = 0;        ///< tan of the friction angle
  JointLaw law = JointLaw::Paper;
  /// Coupled law only: where a mixed-mode path breaks. true (the default): on the energies
  /// released per mode, G_I / G_fI + G_II / G_fII = 1; false: the eq. 6 ellipse on the
  /// displacements past the onset, the form before session 79 (coupled_law.hpp says why).
  bool energy_mixed_mode = true;
};

enum class JointStatus : int { Intact = 0, Softening = 1, Broken = 2 };

/// The slip at a point: its magnitude ds as the joint kernel measures it (what the laws of an
/// unbroken point follow), and its components (u, v) on an orthonormal frame of the face's
/// plane that turns with the face (what a broken point's friction follows, as a vector).
/// A law called with a magnitude alone takes the slip along u.
struct Slip {
  Real ds = 0, u = 0, v = 0;
  Slip() = default;
  Slip(Real ds_) : ds(ds_), u(ds_) {}  // NOLINT(google-explicit-constructor): a slip along u
  Slip(Real ds_, Real u_, Real v_) : ds(ds_), u(u_), v(v_) {}
};

/// History and last state of one integration point.
struct CohesiveState {
  Real dn_max = 0;      ///< largest opening reached [m]
  Real ds_plastic = 0;  ///< paper_residual, before its break: the shear's plastic slip [m]
  Real ks_secant = -1;  ///< damaged shear stiffness, only ever decreasing (< 0: undamaged) [Pa/m]
  /// Only ever increasing. Coupled law: secant damage d in [0, 1]. The paper's law: the shear
  /// damage b of eq. 6, the largest <ds - w_fs> / w_GII reached (past 1 at the break).
  Real damage = 0;
  /// Mode-II dissipation when the point failed [J/m^2]; paper_residual books it as it goes.
  Real diss_II_at_break = 0;
  Real friction = 0;            ///< residual-friction dissipation since then (residual_friction) [J/m^2]
  Real dn = 0, ds = 0;          ///< last opening and slip [m]
  Real sn = 0, ss = 0;          ///< last tractions [Pa] (a broken point's ss: its friction's magnitude)
  Real su = 0, sv = 0;          ///< last slip's components on the face's frame (Slip) [m]
  Real fu = 0, fv = 0;          ///< a broken point's friction on the face's frame, against the slip [Pa]
  Real work_n = 0, work_s = 0;  ///< work of the tractions per unit area [J/m^2]
  /// The shear traction a forced break (force_break) dropped after the step's forces had
  /// been applied with it: the next update books the work it does over that step [Pa].
  Real ss_forced = 0;
  JointStatus status = JointStatus::Intact;

  /// Recoverable energy per unit area at the current state [J/m^2]. The shear of a broken
  /// point, and of any point of paper_residual, is elastic-plastic: 1/2 s_s^2 / k_s; the
  /// other laws' shear unloads along the secant: 1/2 s_s ds.
  Real elastic_energy(const CohesiveParams& p) const {
    const Real en = 0.5 * sn * dn;
    return en + (plastic_shear(p) ? 0.5 * ss * ss / std::max(p.ks, Real(1e-300)) : 0.5 * ss * ds);
  }
  Real dissipated_I(const CohesiveParams&) const { return work_n - 0.5 * sn * dn; }
  Real dissipated_II(const CohesiveParams& p) const {
    if (status == JointStatus::Broken) return diss_II_at_break + friction;
    if (p.law == JointLaw::PaperResidual) return diss_II_at_break;  // booked as it goes
    return work_s - 0.5 * ss * ds;
  }
  bool plastic_shear(const CohesiveParams& p) const {
    return status == JointStatus::Broken || p.law == JointLaw::PaperResidual;
  }
  /// Ends an update of an unbroken point at opening dn, slip sl with tractions sn, ss: the
  /// work of the tractions over the step (trapezoid rule) and the new last state. Every law
  /// ends so.
  void advance(Real dn_new, const Slip& sl, Real sn_new, Real ss_new) {
    work_s += 0.5 * (ss + ss_new) * (sl.ds - ds);
    advance_shear_booked(dn_new, sl, sn_new, ss_new);
  }
  /// The same for a point that was broken at the step's start: residual_friction has booked
  /// its shear work, on the slip vector (the magnitude's trapezoid would not be the friction's
  /// work once the slip turns).
  void advance_shear_booked(Real dn_new, const Slip& sl, Real sn_new, Real ss_new) {
    work_n += 0.5 * (sn + sn_new) * (dn_new - dn);
    dn = dn_new, ds = sl.ds, sn = sn_new, ss = ss_new;
    su = sl.u, sv = sl.v;
  }
  /// A point that breaks starts its friction from the shear traction ss it carries, which
  /// acts along its last slip (su, sv). With no slip to give it a direction (a slip back at
  /// exactly zero) the friction starts from nothing and the traction's stored energy is
  /// released (dissipated).
  void start_friction(const CohesiveParams& p) {
    const Real m = std::sqrt(su * su + sv * sv);
    if (m > 0) {
      fu = ss * su / m, fv = ss * sv / m;
    } else {
      diss_II_at_break += ss * ss / (2.0 * p.ks);
      fu = fv = ss = 0.0;
    }
  }
};

/// Shear strength f_s for the current normal traction (eq. 5, tension positive).
inline Real shear_strength(const CohesiveParams& p, Real sn) {
  return std::max<Real>(p.c - std::min(sn, p.ft) * p.tan_phi, 1e-12 * std::max<Real>(p.c, 1.0));
}

/// Drops a shear traction e above the cap to +-cap at a fixed slip; returns the energy per
/// unit area that the drop releases (dissipated), (e^2 - cap^2) / 2 k_s, or 0.
inline Real drop_to_cap(Real& e, Real cap, Real ks) {
  if (std::abs(e) <= cap) return 0.0;
  const Real released = (e * e - cap * cap) / (2.0 * ks);
  e = e > 0 ? cap : -cap;
  return released;
}

/// Shear traction of a broken point: residual Coulomb friction, a tangential spring on the
/// slip vector in the face's plane (components on the face's frame, Slip), |f| <= -s_n
/// tan(phi): the cap changes at fixed slip (a fallen cap drops the traction to it, radially),
/// then the slip's increment goes elastic and the trial traction is brought back radially
/// onto the cap (sliding). So sliding back, or across, is resisted at once. Returns |f|.
/// Dissipation: the forces' work over the step by the trapezoid rule less the change of the
/// stored energy 1/2 |f|^2 / k_s, as the contacts' tangential springs book it
/// (contact_law.hpp), so the books follow the bodies' work. Booked at the law's own values
/// (the released (s^2 - cap^2) / 2 k_s of a drop, cap x plastic slip), they ran ahead of it
/// at every step that went from elastic to sliding: a step's work counts the traction's
/// mean, the law the cap. That was the upward drift of the ledger after a break. A step that
/// both drops the cap and turns the friction can make the trapezoid hand the bodies back
/// energy the spring never stored: the step then books none (a point's dissipation never
/// falls) and the balance shows the step's error instead.
inline Real residual_friction(const CohesiveParams& p, Real sn, const Slip& sl, CohesiveState& s) {
  const Real du = sl.u - s.su, dv = sl.v - s.sv;
  // A forced break zeroed the shear after the forces were assembled with it, along the last
  // slip: the bodies felt it over the step that ends now, so its half of the trapezoid is
  // dissipated here.
  if (s.ss_forced != 0) {
    const Real m = std::sqrt(s.su * s.su + s.sv * s.sv);
    const Real w = m > 0 ? 0.5 * s.ss_forced * (s.su * du + s.sv * dv) / m : 0.0;
    s.diss_II_at_break += w, s.work_s += w;
    s.ss_forced = 0;
  }
  const Real cap = p.tan_phi * std::max<Real>(0.0, -sn);
  // Lengths compared squared, a square root and a division taken only to scale a vector onto
  // a cap above zero (an open point's cap is zero: its friction is simply gone). sqrt(u^2 +
  // v^2), not std::hypot: no slip or traction comes near its overflow, and hypot is several
  // times slower. (Neither this nor the state's size was what slowed the broken-joint kernel
  // after session 104; the laws' dispatch out of line was: broken_update says how.)
  Real eu = s.fu, ev = s.fv;
  const Real e2 = eu * eu + ev * ev, cap2 = cap * cap;
  const bool dropped = e2 > cap2;
  if (dropped) {
    const Real r = cap > 0 ? cap / std::sqrt(e2) : 0.0;
    eu *= r, ev *= r;
  }
  Real tu = eu + p.ks * du, tv = ev + p.ks * dv;
  const Real t2 = tu * tu + tv * tv;
  const bool slid = t2 > cap2;
  if (slid) {
    const Real r = cap > 0 ? cap / std::sqrt(t2) : 0.0;
    tu *= r, tv *= r;
  }
  // The step's work on the slip vector (CohesiveState::advance leaves a broken point's shear
  // work to this). An elastic step dissipates nothing; it is not computed there, where it is
  // rounding.
  const Real work = 0.5 * ((s.fu + tu) * du + (s.fv + tv) * dv);
  s.work_s += work;
  if (dropped || slid) {
    const Real stored = (tu * tu + tv * tv - s.fu * s.fu - s.fv * s.fv) / (2.0 * p.ks);
    s.friction += std::max<Real>(0.0, work - stored);
  }
  s.fu = tu, s.fv = tv;
  return slid ? cap : std::sqrt(t2);
}

/// Advances a point that was broken at the step's start, under any law: the normal penalty in
/// compression only, and the residual friction. (Every law's broken branch; the joint kernel
/// calls it directly, inlined, for a broken point: called through the laws' dispatch, out of
/// line, the point's slip went through memory and the broken-joint kernel ran at 0.7-0.8 of
/// this rate, BM_JointForcesBroken, session 105.)
inline void broken_update(const CohesiveParams& p, Real dn, const Slip& sl, CohesiveState& s) {
  const Real sn = dn < 0 ? p.kn * dn : 0.0;
  const Real ss = residual_friction(p, sn, sl, s);
  s.advance_shear_booked(dn, sl, sn, ss);
}

/// The paper's normal traction (eq. 3) at opening dn of an unbroken point, with its history
/// (the largest opening). (A broken point's, compression only, is broken_update's.)
inline Real paper_normal_traction(const CohesiveParams& p, Real dn, CohesiveState& s) {
  DSPDEM_ASSERT(s.status != JointStatus::Broken);
  if (dn <= 0) return p.kn * dn;
  const Real w_ft = p.ft / p.kn, w_GI = 2.0 * p.GfI / p.ft;
  s.dn_max = std::max(s.dn_max, dn);
  const Real m = s.dn_max;
  if (m <= w_ft) return p.kn * dn;
  return std::max<Real>(0.0, p.ft * (1.0 - (m - w_ft) / w_GI)) / m * dn;  // secant below the envelope
}

/// Eq. 6 with the mode-I part of the largest opening reached and the shear damage b.
inline bool eq6_broken(const CohesiveParams& p, Real dn_max, Real b) {
  const Real w_ft = p.ft / p.kn, w_GI = 2.0 * p.GfI / p.ft;
  const Real a = std::max<Real>(0.0, dn_max - w_ft) / w_GI;
  return a * a + b * b >= 1.0;
}

/// Advances one integration point to opening dn and slip sl (magnitude ds >= 0); updates the
/// tractions sn, ss (ss acts against the slip), the history and the work integrals.
inline void cohesive_update(const CohesiveParams& p, Real dn, const Slip& sl, CohesiveState& s) {
  if (s.status == JointStatus::Broken) return broken_update(p, dn, sl, s);
  const Real w_ft = p.ft / p.kn, ds = sl.ds;
  Real sn = paper_normal_traction(p, dn, s);
  Real ss;
  const bool mode_i = p.law == JointLaw::ModeI;
  const Real fs = mode_i ? INFINITY : shear_strength(p, sn);
  const Real w_fs = fs / p.ks, w_GII = mode_i ? 1.0 : 2.0 * p.GfII / fs;
  // The shear damage b, at the strength of this moment (irreversibility, above).
  if (!mode_i && ds > w_fs) s.damage = std::max(s.damage, (ds - w_fs) / w_GII);
  if (s.damage > 0) {
    const Real D = std::min<Real>(s.damage, 1.0);
    const Real k = std::max<Real>(0.0, fs * (1.0 - D)) / (w_fs + D * w_GII);
    s.ks_secant = s.ks_secant < 0 ? std::min(k, p.ks) : std::min(s.ks_secant, k);
  }
  ss = (s.ks_secant < 0 ? p.ks : s.ks_secant) * ds;
  // Mixed-mode failure (eq. 6); mode I only: b = 0.
  if (eq6_broken(p, s.dn_max, mode_i ? 0.0 : s.damage)) {
    s.status = JointStatus::Broken;
    sn = dn < 0 ? p.kn * dn : 0.0;
    ss = 0.0;
    s.diss_II_at_break = s.work_s + 0.5 * s.ss * (ds - s.ds);  // all shear work so far; s_s drops to 0
  } else if (s.dn_max > w_ft || s.damage > 0) {
    s.status = JointStatus::Softening;
  }
  s.advance(dn, sl, sn, ss);
  // s_s dropped to 0 at a break: the friction starts from nothing (fu = fv = 0).
}

/// Fails a point that has not reached eq. 6 itself, because its joint failed elsewhere: it
/// keeps no tension and no cohesion from the next update on (its elastic energy is then
/// dissipated; the rest of its fracture energy is not).
inline void force_break(CohesiveState& s) {
  if (s.status == JointStatus::Broken) return;
  s.status = JointStatus::Broken;
  s.diss_II_at_break = s.work_s;  // the stored shear energy is released: no elastic part is left
  s.ss_forced = s.ss;             // this step's forces carried it: booked at the next update
  s.ss = 0.0;
  s.fu = s.fv = 0.0;  // the friction starts from nothing
}

/// Largest stiffness the joint presents (for the stable time step).
inline Real max_stiffness(const CohesiveParams& p) { return std::max(p.kn, p.ks); }

}  // namespace dspdem::joint
