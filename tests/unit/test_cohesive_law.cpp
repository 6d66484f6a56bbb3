// The cohesive law alone (README M2), with the Brazilian-disc parameters of the
// paper: f_t 2.3 MPa, G_fI 10 N/m, c 20 MPa, phi 45 deg, G_fII 1500 N/m; penalty
// k = 10 E / h with E = 25.8 GPa, h = 7.6 mm (the default disc mesh).
#include <gtest/gtest.h>

#include "joint/cohesive_law.hpp"
#include "joint/joint_law.hpp"
#include "support/joint_walk.hpp"

using namespace dspdem;
using namespace dspdem::joint;

namespace {
CohesiveParams disc_params() {
  CohesiveParams p;
  p.kn = p.ks = 10 * 25.8e9 / 7.6e-3;
  p.ft = 2.3e6, p.GfI = 10, p.c = 20e6, p.tan_phi = 1.0, p.GfII = 1500;
  return p;
}

Real envelope_I(const CohesiveParams& p, Real d) {
  const Real w_ft = p.ft / p.kn, w_GI = 2 * p.GfI / p.ft;
  if (d <= w_ft) return p.kn * d;
  return std::max<Real>(0, p.ft * (1 - (d - w_ft) / w_GI));
}
}  // namespace

TEST(CohesiveLaw, ModeIOpeningFollowsTheLawAndDissipatesGf) {
  const CohesiveParams p = disc_params();
  const Real w_ft = p.ft / p.kn, w_GI = 2 * p.GfI / p.ft, df = w_ft + w_GI;
  CohesiveState s;
  const int n = 20000;
  Real worst = 0;
  for (int i = 1; i <= n; ++i) {
    const Real d = 1.2 * df * i / n;
    cohesive_update(p, d, 0.0, s);
    if (s.status != JointStatus::Broken) worst = std::max(worst, std::abs(s.sn - envelope_I(p, d)) / p.ft);
  }
  EXPECT_LT(worst, 1e-9);  // the curve is the law (up to round-off)
  EXPECT_EQ(s.status, JointStatus::Broken);
  EXPECT_EQ(s.sn, 0.0);
  // Dissipation = area under the whole curve: G_fI + f_t^2 / (2 k_n). The trapezoid rule
  // is exact on the linear pieces except in the step holding the peak: 1e-4.
  EXPECT_NEAR(s.dissipated_I(p) / (p.GfI + p.ft * p.ft / (2 * p.kn)), 1.0, 1e-4);
  // Against G_fI alone: within 1 % at the default penalty (the elastic ramp adds 0.78 %).
  EXPECT_NEAR(s.dissipated_I(p) / p.GfI, 1.0, 0.01);
}

TEST(CohesiveLaw, UnloadingAndReloadingFollowTheSecant) {
  const CohesiveParams p = disc_params();
  const Real w_ft = p.ft / p.kn, w_GI = 2 * p.GfI / p.ft;
  const Real m = w_ft + 0.4 * w_GI;  // 40 % into softening
  CohesiveState s;
  for (int i = 1; i <= 1000; ++i) cohesive_update(p, m * i / 1000, 0, s);
  const Real secant = envelope_I(p, m) / m;
  const Real diss_at_m = s.dissipated_I(p);
  for (int i = 999; i >= 0; --i) {  // unload to zero
    cohesive_update(p, m * i / 1000, 0, s);
    ASSERT_NEAR(s.sn, secant * m * i / 1000, 1e-9 * p.ft);
  }
  EXPECT_NEAR(s.dissipated_I(p), diss_at_m, 1e-9 * p.GfI);  // unloading dissipates nothing
  for (int i = 1; i <= 1000; ++i) {                         // reload along the same secant
    cohesive_update(p, m * i / 1000, 0, s);
    ASSERT_NEAR(s.sn, secant * m * i / 1000, 1e-9 * p.ft);
  }
  cohesive_update(p, m * 1.01, 0, s);  // then back on the envelope
  EXPECT_NEAR(s.sn, envelope_I(p, m * 1.01), 1e-9 * p.ft);
  EXPECT_EQ(s.status, JointStatus::Softening);
}

TEST(CohesiveLaw, CompressionNeverDamages) {
  const CohesiveParams p = disc_params();
  CohesiveState s;
  for (int i = 1; i <= 100; ++i) cohesive_update(p, -1e-3 * i / 100, 0, s);  // ~1000 x w_ft in compression
  EXPECT_EQ(s.status, JointStatus::Intact);
  EXPECT_DOUBLE_EQ(s.sn, p.kn * -1e-3);
  EXPECT_NEAR(s.dissipated_I(p), 0.0, 1e-9 * std::abs(s.work_n));
}

TEST(CohesiveLaw, ShearUnderCompressionDissipatesGfIIThenSlidesWithFriction) {
  CohesiveParams p = disc_params();
  const Real sigma = -5e6;  // 5 MPa compression
  const Real dn = sigma / p.kn;
  const Real fs = p.c - sigma * p.tan_phi;  // 25 MPa
  const Real w_fs = fs / p.ks, w_GII = 2 * p.GfII / fs, df = w_fs + w_GII;
  CohesiveState s;
  const int n = 40000;
  Real worst = 0, diss_at_break = -1;
  for (int i = 1; i <= n; ++i) {
    const Real d = 1.5 * df * i / n;
    cohesive_update(p, dn, d, s);
    if (s.status != JointStatus::Broken) {
      const Real env = d <= w_fs ? p.ks * d : fs * (1 - (d - w_fs) / w_GII);
      worst = std::max(worst, std::abs(s.ss - env) / fs);
    } else if (diss_at_break < 0) {
      diss_at_break = s.dissipated_II(p);
    }
  }
  EXPECT_LT(worst, 1e-9);
  EXPECT_EQ(s.status, JointStatus::Broken);
  EXPECT_NEAR(diss_at_break / (p.GfII + fs * fs / (2 * p.ks)), 1.0, 1e-3);
  // Residual friction: |s_s| = -s_n tan(phi) = 5 MPa, and compression is still carried.
  EXPECT_NEAR(s.ss, -sigma * p.tan_phi, 1e-6 * fs);
  EXPECT_NEAR(s.sn, sigma, 1e-6 * std::abs(sigma));
}

TEST(CohesiveLaw, MixedModeBreaksWhereEquation6Predicts) {
  const CohesiveParams p = disc_params();
  // Proportional path dn = ds = d: the joint must break where
  // ((d - w_ft)/w_GI)^2 + ((d - w_fs)/w_GII)^2 = 1, with w_fs from the shear strength at the
  // normal traction of that moment. Tolerance 2e-3: the step size of the path.
  CohesiveState s;
  const Real w_ft = p.ft / p.kn, w_GI = 2 * p.GfI / p.ft;
  const int n = 200000;
  Real d_break = -1;
  for (int i = 1; i <= n && d_break < 0; ++i) {
    const Real d = 2 * (w_ft + w_GI) * i / n;
    cohesive_update(p, d, d, s);
    if (s.status == JointStatus::Broken) d_break = d;
  }
  ASSERT_GT(d_break, 0);
  // Pure mode I would break at w_ft + w_GI; the shear term makes it break earlier, but
  // only slightly, because w_GII (G_fII = 1500 N/m) is much longer than w_GI.
  EXPECT_LT(d_break, w_ft + w_GI);
  // Check eq. 6 at the break with the strength the law used just before it.
  const Real a = (d_break - w_ft) / w_GI;
  const Real fs = shear_strength(p, envelope_I(p, d_break));
  const Real b = (d_break - fs / p.ks) / (2 * p.GfII / fs);
  EXPECT_NEAR(a * a + b * b, 1.0, 2e-3);
}

TEST(CohesiveLaw, NoPathCreatesEnergy) {
  // Random walks in (opening, slip), in small steps as in a run, with the normal traction
  // swinging between tension and strong compression: the dissipated energy of each mode
  // must never decrease (beyond the trapezoid rule's error at kinks, bounded here by
  // 1e-6 of the fracture energies).
  const CohesiveParams p = disc_params();
  const Real w_ft = p.ft / p.kn, w_fs = p.c / p.ks;
  testsupport::JointWalk walk{12345, 0.2 * w_ft, 0.2 * w_fs, -60 * w_ft, 3 * w_ft, 200 * w_fs};
  const testsupport::WalkVerdict v =
      testsupport::walk_energy(p, walk, 50, 20000, 1e-6 * (p.GfI + p.GfII), cohesive_update);
  EXPECT_LT(v.path, 0) << "energy created on path " << v.path << " at step " << v.step;
}

TEST(CohesiveLaw, ResidualFrictionResistsReversal) {
  // After a shear failure under 5 MPa compression: slide forward, then back. The friction
  // changes sign and holds |s_s| = -s_n tan(phi) both ways; sliding back dissipates too.
  const CohesiveParams p = disc_params();
  const Real sigma = -5e6, dn = sigma / p.kn, cap = -sigma * p.tan_phi;
  const Real fs = p.c - sigma * p.tan_phi, df = fs / p.ks + 2 * p.GfII / fs;
  CohesiveState s;
  for (int i = 1; i <= 20000; ++i) cohesive_update(p, dn, 1.2 * df * i / 20000, s);
  ASSERT_EQ(s.status, JointStatus::Broken);
  EXPECT_NEAR(s.ss, cap, 1e-6 * cap);
  const Real forward = s.dissipated_II(p);
  const Real back = 0.1 * df;
  for (int i = 1; i <= 2000; ++i) cohesive_update(p, dn, 1.2 * df - back * i / 2000, s);
  // The friction (on the face's frame, the slip along u) has turned round; ss is its size.
  EXPECT_NEAR(s.fu, -cap, 1e-6 * cap);
  EXPECT_NEAR(s.ss, cap, 1e-6 * cap);
  // Sliding back by `back` (less the elastic reversal 2 cap / k_s) dissipates cap x that.
  EXPECT_NEAR((s.dissipated_II(p) - forward) / (cap * (back - 2 * cap / p.ks)), 1.0, 1e-3);
}

namespace {
// A point broken in shear under compression sigma, sliding along +u to 1.2 times the slip
// at which the paper's law fails it: the start of the friction tests below.
CohesiveState broken_sliding_along_u(const CohesiveParams& p, Real sigma, Real& u_end) {
  const Real dn = sigma / p.kn, fs = p.c - sigma * p.tan_phi, df = fs / p.ks + 2 * p.GfII / fs;
  CohesiveState s;
  u_end = 1.2 * df;
  for (int i = 1; i <= 20000; ++i) cohesive_update(p, dn, Slip(u_end * i / 20000, u_end * i / 20000, 0), s);
  return s;
}
}  // namespace

TEST(CohesiveLaw, ResidualFrictionResistsASlipGoingBackAndForthAcrossWhereItStarted) {
  // The slip goes back along u to +a, then ten times between +a and -a, a = 3 cap / k_s: its
  // magnitude falls to 0 and grows again each time. The vector friction resists all the way:
  // the first pass, on from the way back, dissipates cap 2a; each later one cap (2a - 2 cap
  // / k_s), the path less the elastic reversal. A friction on the slip's magnitude (dspdem
  // before session 104) kept its sign through zero, pushed along the motion for cap / k_s and
  // dissipated about half that. Tolerance 1e-3: a step is 1/3000 of a pass, and the
  // trapezoid's books are off by at most a step's share at a turn.
  const CohesiveParams p = disc_params();
  const Real sigma = -5e6, dn = sigma / p.kn, cap = -sigma * p.tan_phi, l = cap / p.ks, a = 3 * l;
  Real u0;
  CohesiveState s = broken_sliding_along_u(p, sigma, u0);
  ASSERT_EQ(s.status, JointStatus::Broken);
  auto go = [&](Real from, Real to, int n) {
    for (int i = 1; i <= n; ++i) {
      const Real u = from + (to - from) * i / n;
      cohesive_update(p, dn, Slip(std::abs(u), u, 0), s);
    }
  };
  go(u0, a, 2000);
  const Real before = s.dissipated_II(p);
  for (int k = 0; k < 10; ++k) go(k % 2 == 0 ? a : -a, k % 2 == 0 ? -a : a, 3000);
  EXPECT_NEAR(s.fu, cap, 1e-9 * cap);  // the last pass slid towards +u
  EXPECT_NEAR((s.dissipated_II(p) - before) / (cap * (2 * a + 9 * (2 * a - 2 * l))), 1.0, 1e-3);
}

TEST(CohesiveLaw, ResidualFrictionTurnsWithASlipTurnedAcross) {
  // After sliding along u, the slip goes along v by L with u held. On the cap the friction
  // f = cap (cos a, sin a) turns as the trial's radial return turns it: cap da = k_s cos a
  // dv, so sin a = tanh(k_s v / cap), and all the work is dissipated (|f| stays cap):
  // cap^2 / k_s ln cosh(k_s L / cap). A friction on the slip's magnitude would barely resist
  // (the magnitude grows by L^2 / 2 u_0 at first). Tolerance 2e-3: a step is 1/1000 of
  // cap / k_s, and the radial return is first-order in the step.
  const CohesiveParams p = disc_params();
  const Real sigma = -5e6, dn = sigma / p.kn, cap = -sigma * p.tan_phi, l = cap / p.ks;
  Real u0;
  CohesiveState s = broken_sliding_along_u(p, sigma, u0);
  const Real before = s.dissipated_II(p), L = 5 * l;
  const int n = 5000;
  Real worst = 0;
  for (int i = 1; i <= n; ++i) {
    const Real v = L * i / n;
    cohesive_update(p, dn, Slip(std::hypot(u0, v), u0, v), s);
    worst = std::max(worst, std::abs(s.fv - cap * std::tanh(v / l)) / cap);
  }
  EXPECT_LT(worst, 2e-3);
  EXPECT_NEAR(s.ss, cap, 1e-9 * cap);
  EXPECT_NEAR((s.dissipated_II(p) - before) / (cap * l * std::log(std::cosh(L / l))), 1.0, 2e-3);
}

TEST(CohesiveLaw, ModeIOnlyKeepsTheShearElasticAndBreaksInOpening) {
  // joint_law = "mode_I" (the paper's impact beam): a slip 100x the paper law's elastic
  // limit c / k_s leaves the point intact, its shear traction k_s ds and nothing
  // dissipated; an opening then breaks it with G_fI (+ the elastic ramp) dissipated, as
  // the paper's law does; broken, it slides with friction tan(phi) under compression.
  CohesiveParams p = disc_params();
  p.law = JointLaw::ModeI;
  p.c = 0, p.GfII = 0;  // not used (the reader refuses them)
  CohesiveState s;
  const Real ds_big = 100 * 20e6 / p.ks;
  for (int i = 1; i <= 1000; ++i) cohesive_update(p, 0.0, ds_big * i / 1000, s);
  EXPECT_EQ(s.status, JointStatus::Intact);
  EXPECT_NEAR(s.ss, p.ks * ds_big, 1e-9 * p.ks * ds_big);
  EXPECT_NEAR(s.dissipated_II(p), 0.0, 1e-9 * s.elastic_energy(p));
  // Unload the slip, then open to failure.
  for (int i = 999; i >= 0; --i) cohesive_update(p, 0.0, ds_big * i / 1000, s);
  const Real df = p.ft / p.kn + 2 * p.GfI / p.ft;
  for (int i = 1; i <= 20000; ++i) cohesive_update(p, 1.2 * df * i / 20000, 0.0, s);
  EXPECT_EQ(s.status, JointStatus::Broken);
  EXPECT_NEAR(s.dissipated_I(p) / (p.GfI + p.ft * p.ft / (2 * p.kn)), 1.0, 1e-4);
  // Closed and pressed at 1 MPa, then slid: the traction caps at tan(phi) x 1 MPa.
  const Real dn = -1e6 / p.kn;
  for (int i = 1; i <= 1000; ++i) cohesive_update(p, dn, 1e-5 * i / 1000, s);
  EXPECT_NEAR(s.ss, 1e6, 1e-6 * 1e6);
}

TEST(CohesiveLaw, AnElasticSlipUnderCompressionIsNoDamageOnceReleased) {
  // Pressed at 50 MPa (f_s = 70 MPa), the face slips to 0.9 of its elastic limit and back;
  // then the pressure is released (f_s = 20 MPa, an elastic limit 0.29 of that slip). The face
  // never passed its strength, so it is undamaged: intact, damage index 0, and slipping again
  // to half its limit it carries k_s ds. (The largest slip against the current strength
  // would count 0.85 % of G_fII's branch as damage here and cut the shear stiffness by 3x.)
  const CohesiveParams p = disc_params();
  const Real sigma = -50e6, dn = sigma / p.kn;
  const Real ds_top = 0.9 * shear_strength(p, sigma) / p.ks;
  CohesiveState s;
  for (int i = 1; i <= 100; ++i) cohesive_update(p, dn * i / 100, 0.0, s);
  for (int i = 1; i <= 100; ++i) cohesive_update(p, dn, ds_top * i / 100, s);
  ASSERT_EQ(s.status, JointStatus::Intact);
  for (int i = 99; i >= 0; --i) cohesive_update(p, dn, ds_top * i / 100, s);
  for (int i = 99; i >= 0; --i) cohesive_update(p, dn * i / 100, 0.0, s);
  const Real w_fs = shear_strength(p, 0.0) / p.ks;
  ASSERT_GT(ds_top, 3 * w_fs);  // the released face's limit is well below the slip it had
  for (int i = 1; i <= 100; ++i) cohesive_update(p, 0.0, 0.5 * w_fs * i / 100, s);
  EXPECT_EQ(s.status, JointStatus::Intact);
  EXPECT_EQ(damage_index(p, s), 0.0);
  EXPECT_NEAR(s.ss, p.ks * 0.5 * w_fs, 1e-12 * p.ks * w_fs);
  EXPECT_NEAR(s.dissipated_II(p), 0.0, 1e-9 * p.GfII);
}
