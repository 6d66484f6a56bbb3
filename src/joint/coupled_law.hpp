// Coupled mixed-mode cohesive law (`joint_law = "coupled"`), per integration point, in the
// joint's local frame: opening dn (> 0 in tension) and slip magnitude ds (a broken point's
// friction takes the slip's components: Slip, cohesive_law.hpp).
//
// Why: the paper's law (cohesive_law.hpp) softens the normal and the shear traction
// independently and couples them only in its break test (eq. 6). A face inclined to a
// tensile crack then keeps its full shear strength while it opens, and a crack that must
// zigzag through such faces (any mesh not aligned with it) pays many times G_fI: the
// Brazilian disc on an unstructured mesh came out +160 % strong (issue 8). Here one damage
// variable softens both tractions together, as FDEM codes do (Munjiza's combined
// single/smeared crack model, Y-Geo/Irazu) and as cohesive-zone codes for mixed mode do
// (Camanho & Davila 2002):
//
//   free energy  psi = 1/2 k_n <-dn>^2 + (1 - d) (1/2 k_n <dn>^2 + 1/2 k_s ds^2)
//   tractions    s_n = k_n dn (dn < 0: compression never damages), (1 - d) k_n dn (dn > 0)
//                s_s = (1 - d) k_s ds
//
// with d only ever increasing, so no loading path can create energy (the dissipation rate
// is psi's drop at fixed displacement, >= 0). Unloading goes along the secant to the origin.
//
// Evolution of d along the current direction of (<dn>, ds), lambda = |(<dn>, ds)|,
// cos = <dn> / lambda, sin = ds / lambda:
//   shear strength   f_s = c + <-s_n> tan(phi)  (compression raises it; opening does not
//                    lower it below c: the interaction with tension is the onset criterion;
//                    so a face that opens never gains strength, unlike eq. 5 with a softened
//                    s_n)
//   onset            (k_n <dn> / f_t)^2 + (k_s ds / f_s)^2 = 1, i.e. lambda_0 =
//                    1 / sqrt((k_n cos / f_t)^2 + (k_s sin / f_s)^2)
//   final            (`mixed_mode = "energy"`, the default) on the energies released past
//                    the onset, G_I / G_fI + G_II / G_fII = 1, with G_I : G_II =
//                    k_n cos^2 : k_s sin^2 on the path (Camanho & Davila 2002's power law
//                    with exponent 1): the total is the mean of G_fI and G_fII weighted by
//                    the shares, harmonically, so it always lies between them;
//                    (`"displacement"`, the form before session 79) the eq. 6 ellipse on the
//                    displacements past onset:
//                    ((lambda - lambda_0) cos / w_GI)^2 + ((lambda - lambda_0) sin / w_GII)^2 = 1,
//                    w_GI = 2 G_fI / f_t, w_GII = 2 G_fII / f_s
//   damage           D = (lambda - lambda_0) / (lambda_f - lambda_0), d = D lambda_f / lambda,
//                    so the traction falls linearly from the onset to zero at lambda_f on a
//                    proportional path.
// Why the energy form: the displacement ellipse was written for the paper's law, whose modes
// each soften from their own strength. Here a face opening at an angle starts to soften at
// a shear traction of only about f_t tan(angle), so its w_GII = 2 G_fII / f_s stands for
// far less energy than G_fII. Where w_GII < w_GI (c >> f_t: the sphere, c = 18 f_t) a face
// 30 deg off its crack then releases 0.31 G_fI, below both modes' energies; the energy form
// gives 1.2 G_fI there, between them. With the inter-element parameters c = 2 f_t,
// G_fII = G_fI (the disc's core, the Galvez beam) the displacement form gives 0.80-1.0 G_fI
// and the energy form G_fI at any angle. Where w_GII > w_GI (the paper's disc numbers) the
// two agree within 1 % up to 60 deg.
// In pure mode I this is the paper's mode-I triangle exactly (dissipation G_fI + f_t^2/2k_n);
// in pure mode II the paper's mode-II triangle at that f_s (G_fII + f_s^2/2k_s); mixed paths
// dissipate 1/2 lambda_0 lambda_f (k_n cos^2 + k_s sin^2), in between. At d = 1 the point is
// broken and keeps the paper's residual Coulomb friction in compression. Between onset and
// break the shear traction is the degraded cohesion only (friction starts at the break:
// a simplification; under compression the cohesive secant then briefly carries less than the
// friction cap, which the break restores without a jump, since friction starts from zero).
// Slip is a vector handled by the caller: s_s acts along it, and the law is isotropic in
// the tangent plane, so before the break a slip that turns without growing neither damages
// nor dissipates (a broken point's friction, a vector, resists it).
#pragma once
#include "joint/cohesive_law.hpp"

namespace dspdem::joint {

/// Where the coupled law's damage starts and ends along a direction (cos, sin) of
/// (<dn>, ds) at shear strength fs: onset lambda_0 and final lambda_f [m].
struct CoupledEnvelope {
  Real lambda0 = 0, lambdaf = 0;
};

inline CoupledEnvelope coupled_envelope(const CohesiveParams& p, Real cos_t, Real sin_t, Real fs) {
  const Real qn = p.kn * cos_t / p.ft, qs = p.ks * sin_t / fs;
  CoupledEnvelope e;
  e.lambda0 = 1.0 / std::sqrt(qn * qn + qs * qs);
  if (p.energy_mixed_mode) {
    // Past the onset the point releases 1/2 lambda_0 K (lambda_f - lambda_0), shared between
    // the modes as k_n cos^2 : k_s sin^2 (each traction is (1 - d) k times its own jump).
    const Real kI = p.kn * cos_t * cos_t, kII = p.ks * sin_t * sin_t, K = kI + kII;
    const Real Gc = K / (kI / p.GfI + kII / p.GfII);
    e.lambdaf = e.lambda0 + 2.0 * Gc / (e.lambda0 * K);
  } else {
    const Real gn = cos_t * p.ft / (2.0 * p.GfI), gs = sin_t * fs / (2.0 * p.GfII);
    e.lambdaf = e.lambda0 + 1.0 / std::sqrt(gn * gn + gs * gs);
  }
  return e;
}

/// Shear strength of the coupled law: c, raised by compression only.
inline Real coupled_shear_strength(const CohesiveParams& p, Real dn) {
  return p.c + std::max<Real>(0.0, -p.kn * dn) * p.tan_phi;
}

/// Advances one integration point to opening dn and slip sl (magnitude ds >= 0) under the
/// coupled law; same state and energy bookkeeping as cohesive_update.
inline void coupled_update(const CohesiveParams& p, Real dn, const Slip& sl, CohesiveState& s) {
  if (s.status == JointStatus::Broken) return broken_update(p, dn, sl, s);
  const Real ds = sl.ds;
  Real sn, ss;
  const Real un = std::max<Real>(0.0, dn);
  const Real fs = coupled_shear_strength(p, dn);
  // lambda > lambda0 below says (k_n un / f_t)^2 + (k_s ds / f_s)^2 > 1: the elastic
  // tractions outside the onset ellipse. Well inside it (below 0.98, far beyond rounding)
  // the damage cannot grow, and the square roots and six divisions of the envelope, the
  // cost of an intact point, are skipped; the result is the same to the bit.
  const Real an = p.kn * un * fs, as = p.ks * ds * p.ft, lim = p.ft * fs;
  const Real lambda = an * an + as * as > 0.98 * lim * lim ? std::hypot(un, ds) : 0.0;
  if (lambda > 0) {
    const CoupledEnvelope e = coupled_envelope(p, un / lambda, ds / lambda, fs);
    if (lambda > e.lambda0) {
      const Real d = lambda >= e.lambdaf ? 1.0 : e.lambdaf * (lambda - e.lambda0) / (lambda * (e.lambdaf - e.lambda0));
      s.damage = std::max(s.damage, d);
    }
  }
  s.dn_max = std::max(s.dn_max, dn);
  if (s.damage >= 1.0) {
    s.status = JointStatus::Broken;  // the friction starts from nothing (fu = fv = 0)
    sn = dn < 0 ? p.kn * dn : 0.0;
    ss = 0.0;
    s.diss_II_at_break = s.work_s + 0.5 * s.ss * (ds - s.ds);  // all shear work so far; s_s drops to 0
  } else {
    const Real k = 1.0 - s.damage;
    sn = dn < 0 ? p.kn * dn : k * p.kn * dn;
    ss = k * p.ks * ds;
    if (s.damage > 0) s.status = JointStatus::Softening;
  }
  s.advance(dn, sl, sn, ss);
}

}  // namespace dspdem::joint
