// The lean form of an elastic integration point. Almost every joint point of a run stays
// elastic to the end, and while it does its whole CohesiveState (144 bytes) follows from
// three numbers: tractions k_n dn and k_s ds, work equal to the stored energy, nothing
// dissipated, no damage. Streaming the full state of every point twice a step was the
// joint kernel's largest cost (issue 19: the kernel is bound by memory traffic), so a point
// is kept in this 24-byte form until its law first leaves the elastic branch; from then on
// it is kept in full for good (JointSet::full_point).
//
// lean_update decides exactly as the laws do (cohesive_update, coupled_update): where it
// keeps a point lean, the full law would give the same tractions and history to the bit.
// Only the work integrals differ, by rounding: the closed form 1/2 s d here against the
// laws' trapezoid sum, equal for a linear spring in exact arithmetic.
#pragma once
#include <algorithm>

#include "joint/joint_law.hpp"

namespace dspdem::joint {

struct LeanPoint {
  Real dn = 0, ds = 0;  ///< last opening and slip [m]
  Real dn_max = 0;      ///< largest opening reached, as the laws keep it [m]
};

/// Advances a lean point to opening dn and slip ds (>= 0) if its law keeps it elastic and
/// undamaged: then lp is updated, sn and ss are its tractions and the result is true.
/// Otherwise lp is left as it was (the state before this update) and the result is false:
/// the caller must switch the point to its full form and run the law.
inline bool lean_update(const CohesiveParams& p, Real dn, Real ds, LeanPoint& lp, Real& sn, Real& ss) {
  sn = p.kn * dn;
  ss = p.ks * ds;
  Real dn_max;
  if (p.law == JointLaw::Coupled) {
    // coupled_update's gate: well inside the onset ellipse no damage can grow.
    const Real un = std::max<Real>(0.0, dn);
    const Real fs = coupled_shear_strength(p, dn);
    const Real an = p.kn * un * fs, as = p.ks * ds * p.ft, lim = p.ft * fs;
    if (an * an + as * as > 0.98 * lim * lim) return false;
    dn_max = std::max(lp.dn_max, dn);
  } else {
    // cohesive_update: elastic while the largest opening is below w_ft and the slip below
    // w_fs at the current normal traction (mode I: no shear limit).
    // Each limit is first tested by a product with a margin of 1e-12, far beyond rounding:
    // below it the division's test (the law's) cannot fail, and the division is skipped.
    dn_max = dn > 0 ? std::max(lp.dn_max, dn) : lp.dn_max;
    if (!(dn_max * p.kn < p.ft * (1 - 1e-12)) && dn_max > p.ft / p.kn) return false;
    if (p.law != JointLaw::ModeI) {
      const Real fs = shear_strength(p, sn);
      if (!(ds * p.ks < fs * (1 - 1e-12)) && ds > fs / p.ks) return false;
    }
  }
  lp.dn = dn, lp.ds = ds, lp.dn_max = dn_max;
  return true;
}

/// The full state a lean point stands for.
inline CohesiveState full_state(const CohesiveParams& p, const LeanPoint& lp) {
  CohesiveState s;
  s.dn = lp.dn, s.ds = lp.ds;
  s.dn_max = lp.dn_max;
  s.sn = p.kn * lp.dn, s.ss = p.ks * lp.ds;
  s.work_n = 0.5 * s.sn * s.dn, s.work_s = 0.5 * s.ss * s.ds;
  return s;
}

}  // namespace dspdem::joint
