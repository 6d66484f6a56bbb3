// The extrinsic insertion criterion (joint/onset.hpp) as pure functions: the face traction
// against the analytic one of a uniaxial stress, and the onset ratio against the laws
// themselves, which must leave their elastic branch exactly where the ratio crosses 1.
#include <gtest/gtest.h>

#include <cmath>

#include "joint/joint_law.hpp"
#include "joint/onset.hpp"

using namespace dspdem;
using namespace dspdem::joint;

TEST(Onset, FaceTractionOfAUniaxialStress) {
  // sigma along x on a face at angle theta: t_n = sigma cos^2, t_s = |sigma sin cos|.
  const Real sigma = 2.5e6;
  const Real s[6] = {sigma, 0, 0, 0, 0, 0};
  for (Real th : {0.0, 0.3, M_PI / 4, 1.2, M_PI / 2, 2.0}) {
    const Vec3 n(std::cos(th), std::sin(th), 0);
    const FaceTraction t = face_traction(s, s, n);
    EXPECT_NEAR(t.tn, sigma * std::cos(th) * std::cos(th), 1e-9 * sigma);
    EXPECT_NEAR(t.ts, std::abs(sigma * std::sin(th) * std::cos(th)), 1e-9 * sigma);
  }
  // The mean of two elements' stresses; shear components in the xy yz xz slots.
  const Real a[6] = {1e6, 0, 0, 0, 0, 0}, b[6] = {3e6, 0, 0, 4e6, 0, 0};
  const FaceTraction t = face_traction(a, b, Vec3(1, 0, 0));
  EXPECT_NEAR(t.tn, 2e6, 1e-3);
  EXPECT_NEAR(t.ts, 2e6, 1e-3);  // the mean xy stress
}

namespace {
CohesiveParams params(JointLaw law) {
  CohesiveParams p;
  p.kn = 3e14, p.ks = 2e14, p.ft = 3e6, p.GfI = 100, p.GfII = 1000, p.c = 9e6;
  p.tan_phi = std::tan(35 * M_PI / 180), p.law = law;
  return p;
}

// Whether the law, driven from a fresh state straight to the elastic opening and slip of
// traction (tn, ts), leaves its elastic branch there.
bool leaves_elastic(const CohesiveParams& p, Real tn, Real ts) {
  CohesiveState s;
  const Real dn = tn / p.kn, ds = ts / p.ks;
  for (int i = 1; i <= 4; ++i) joint_law_update(p, dn * i / 4, ds * i / 4, s);
  const bool elastic = s.status == JointStatus::Intact && std::abs(s.sn - p.kn * dn) <= 1e-12 * p.ft &&
                       std::abs(s.ss - p.ks * ds) <= 1e-12 * p.ft;
  return !elastic;
}
}  // namespace

TEST(Onset, RatioOneIsWhereEachLawLeavesItsElasticBranch) {
  // Directions in the (t_n, t_s) plane from pure tension through shear to compression and
  // shear; along each, the traction with ratio 1 (found by bisection) scaled by 1 -+ 1e-6:
  // the law stays elastic just inside and leaves just outside.
  for (JointLaw law : {JointLaw::ModeI, JointLaw::Paper, JointLaw::Coupled, JointLaw::PaperResidual}) {
    const CohesiveParams p = params(law);
    for (Real ang : {0.0, 0.4, 0.9, 1.4, M_PI / 2, 2.0, 2.5}) {
      const Real cn = std::cos(ang), cs = std::sin(ang);
      if (law == JointLaw::ModeI && ang > 0) continue;  // mode I opens in tension only
      Real lo = 0, hi = 1e9;
      for (int it = 0; it < 200; ++it) {
        const Real mid = 0.5 * (lo + hi);
        (onset_ratio(p, {mid * cn, mid * cs}) < 1 ? lo : hi) = mid;
      }
      const Real r = 0.5 * (lo + hi);
      EXPECT_NEAR(onset_ratio(p, {r * cn, r * cs}), 1.0, 1e-12);
      EXPECT_FALSE(leaves_elastic(p, (1 - 1e-6) * r * cn, (1 - 1e-6) * r * cs))
          << "law " << static_cast<int>(law) << " angle " << ang;
      EXPECT_TRUE(leaves_elastic(p, (1 + 1e-6) * r * cn, (1 + 1e-6) * r * cs))
          << "law " << static_cast<int>(law) << " angle " << ang;
    }
  }
}

TEST(Onset, CompressionRaisesTheShearStrength) {
  // Pure shear against shear with compression: the second needs more shear to open, by
  // tan(phi) times the compression (both laws with friction); mode I ignores shear.
  for (JointLaw law : {JointLaw::Paper, JointLaw::Coupled, JointLaw::PaperResidual}) {
    const CohesiveParams p = params(law);
    EXPECT_NEAR(onset_ratio(p, {0, p.c}), 1.0, 1e-12);
    EXPECT_NEAR(onset_ratio(p, {-2e6, p.c + 2e6 * p.tan_phi}), 1.0, 1e-12);
  }
  EXPECT_LT(onset_ratio(params(JointLaw::ModeI), {0, 1e9}), 1.0);
}

TEST(Onset, TheFloorScreensOnlyTractionsBelowTheOnset) {
  // Tractions in every direction with magnitudes up to the floor: none may reach the onset;
  // the floor is not far below it either (some direction at 1.5 x the floor opens).
  for (JointLaw law : {JointLaw::ModeI, JointLaw::Paper, JointLaw::Coupled, JointLaw::PaperResidual}) {
    const CohesiveParams p = params(law);
    const Real fl = onset_floor(p);
    bool opens_above = false;
    for (int i = 0; i <= 360; ++i) {
      const Real a = i * M_PI / 360;  // t_s >= 0: angles 0 to pi
      for (Real m : {0.999, 0.9, 0.5}) EXPECT_LT(onset_ratio(p, {m * fl * std::cos(a), m * fl * std::sin(a)}), 1.0);
      opens_above = opens_above || onset_ratio(p, {1.5 * fl * std::cos(a), 1.5 * fl * std::sin(a)}) >= 1;
    }
    EXPECT_TRUE(opens_above) << static_cast<int>(law);
  }
  // The stress bound: |sigma n| for unit n never exceeds it.
  const Real s[6] = {1e6, -2e6, 0.5e6, 0.7e6, -0.3e6, 1.1e6};
  for (int i = 0; i < 50; ++i) {
    const Vec3 n = Vec3(std::sin(i * 0.7), std::cos(i * 1.3), std::sin(i * 0.31 + 1)).normalized();
    const Vec3 t = face_traction_vector(s, s, n);
    EXPECT_LE(t.norm(), stress_bound(s) * (1 + 1e-12));
  }
}

TEST(Onset, TheLargerRuleTakesTheElementNearerItsOnsetAndTheMeanRuleTheirMean) {
  // Two elements across a face of normal x, in tension along x: 4 MPa on side A, 1 MPa on
  // side B (a stress peak on A's side). Mode I, f_t = 3 MPa: the mean (2.5 MPa) stays below
  // the onset, A's own stress is past it.
  const CohesiveParams p = params(JointLaw::ModeI);
  const Real a[6] = {4e6, 0, 0, 0, 0, 0}, b[6] = {1e6, 0, 0, 0, 0, 0};
  const Vec3 n(1, 0, 0);
  const FaceOnset mean = face_onset(p, a, b, n, FaceStress::Mean);
  EXPECT_NEAR(mean.ratio, 2.5 / 3.0, 1e-12);
  EXPECT_NEAR(mean.t(0), 2.5e6, 1e-6);
  const FaceOnset larger = face_onset(p, a, b, n, FaceStress::Larger);
  EXPECT_NEAR(larger.ratio, 4.0 / 3.0, 1e-12);
  EXPECT_NEAR(larger.t(0), 4e6, 1e-6);
  // The same with the sides swapped: where the ratios differ, the rule does not depend on
  // which side is A (on a tie it keeps side A's traction).
  const FaceOnset swapped = face_onset(p, b, a, n, FaceStress::Larger);
  EXPECT_EQ(swapped.ratio, larger.ratio);
  EXPECT_EQ(swapped.t, larger.t);
  // Under one uniform stress both rules give the traction of face_traction, bit for bit.
  const FaceTraction u = face_traction(a, a, n);
  for (FaceStress r : {FaceStress::Mean, FaceStress::Larger}) {
    const FaceOnset o = face_onset(p, a, a, n, r);
    EXPECT_EQ(o.t.dot(n), u.tn);
    EXPECT_EQ(o.ratio, onset_ratio(p, u));
  }
  // The choice is by ratio, not by the size of the traction: under the coupled law
  // (f_t 3 MPa, c 9 MPa) side A's tension of 2.8 MPa is nearer the onset (ratio 0.933) than
  // side B's larger shear of 8 MPa (ratio 0.889).
  const CohesiveParams q = params(JointLaw::Coupled);
  const Real sa[6] = {2.8e6, 0, 0, 0, 0, 0}, sb[6] = {0, 0, 0, 8e6, 0, 0};
  for (bool swap : {false, true}) {
    const FaceOnset o =
        swap ? face_onset(q, sb, sa, n, FaceStress::Larger) : face_onset(q, sa, sb, n, FaceStress::Larger);
    EXPECT_NEAR(o.ratio, 2.8 / 3.0, 1e-12);
    EXPECT_NEAR(o.t(0), 2.8e6, 1e-6);
    EXPECT_EQ(o.t(1), 0.0);
  }
}
