// The contact force law of one feature pair (contact_law.hpp) alone: normal spring and
// damping, the tangential spring's history, the Coulomb cap, and its energy book-keeping.
#include <gtest/gtest.h>

#include "contact/contact_law.hpp"
#include "contact/restitution.hpp"

using namespace dspdem;
using namespace dspdem::contact;

namespace {
const Vec3 ez(0, 0, 1);
}

TEST(ContactLaw, NormalSpringAndDampingThatNeverPulls) {
  LawParams p{1e6, 0, 0, 100, 0};
  Vec3 xi = Vec3::Zero();
  // Approaching at 1 m/s (A moves towards B: vrel . n < 0): spring plus damping.
  LawResult r = contact_law(p, 1e-4, ez, Vec3(0, 0, -1), 1e-6, xi);
  EXPECT_NEAR(r.force(2), 1e6 * 1e-4 + 100 * 1.0, 1e-9);
  EXPECT_NEAR(r.elastic, 0.5 * 1e6 * 1e-8, 1e-15);
  EXPECT_NEAR(r.damping_power, 100.0 * 1.0, 1e-9);  // c v^2
  // Separating fast: the damping may not turn the force into a pull.
  r = contact_law(p, 1e-4, ez, Vec3(0, 0, 10), 1e-6, xi);
  EXPECT_EQ(r.force(2), 0.0);
  EXPECT_GE(r.damping_power, 0.0);  // what the clipped damper removes is still dissipation
}

TEST(ContactLaw, StickThenSlideAtTheCoulombCapDissipatingCapTimesSlip) {
  const Real kn = 1e6, kt = 5e5, mu = 0.5, overlap = 1e-4, dt = 1e-6;
  LawParams p{kn, kt, mu, 0, 0};
  Vec3 xi = Vec3::Zero();
  const Real cap = mu * kn * overlap;  // 50 N
  const Vec3 v(0.2, 0, 0);             // tangential sliding speed of A over B
  Real slipped = 0, dissipated = 0, work = 0;
  Vec3 f_prev = Vec3::Zero();
  bool slid = false;
  for (int s = 0; s < 4000; ++s) {
    const LawResult r = contact_law(p, overlap, ez, v, dt, xi);
    const Real ft = std::hypot(r.force(0), r.force(1));
    EXPECT_LE(ft, cap * (1 + 1e-12));
    // Work of the tangential force on the relative motion, trapezoidal.
    work += -0.5 * (f_prev(0) + r.force(0)) * v(0) * dt;
    f_prev = r.force;
    dissipated += r.slip_work;
    if (ft >= cap * (1 - 1e-12)) {
      if (slid) slipped += v(0) * dt;
      slid = true;
    } else {
      EXPECT_NEAR(r.force(0), -kt * xi(0), 1e-9);  // sticking: the spring alone
      EXPECT_NEAR(r.slip_work, 0.0, 1e-12);
    }
  }
  ASSERT_TRUE(slid);
  // Sliding: the spring stays at cap / kt, and every further step dissipates cap x slip.
  EXPECT_NEAR(xi.norm(), cap / kt, 1e-12);
  EXPECT_NEAR(dissipated / (cap * slipped), 1.0, 1e-3);
  // Energy: work done = stored tangential energy + dissipated.
  const Real stored_t = 0.5 * kt * xi.squaredNorm();
  EXPECT_NEAR(work, stored_t + dissipated, 1e-6 * work);
}

TEST(ContactLaw, HistoryTurnsWithTheContactPlaneKeepingItsLength) {
  // A sticking spring stretched along x on a plane with normal z; the plane then tilts by
  // 30 degrees about y (the pair rotated): the history must lie in the new plane with the
  // same length, so a rigid rotation neither stores nor releases tangential energy.
  LawParams p{1e6, 5e5, 10.0, 0, 0};  // mu high: sticks
  Vec3 xi = Vec3::Zero();
  contact_law(p, 1e-4, ez, Vec3(0.1, 0, 0), 1e-5, xi);
  const Real len = xi.norm();
  ASSERT_GT(len, 0.0);
  const Real a = M_PI / 6;
  const Vec3 n(std::sin(a), 0, std::cos(a));
  const LawResult r = contact_law(p, 1e-4, n, Vec3::Zero(), 1e-5, xi);
  EXPECT_NEAR(xi.dot(n), 0.0, 1e-15);
  EXPECT_NEAR(xi.norm(), len, 1e-15);
  EXPECT_NEAR(r.elastic, 0.5 * 1e6 * 1e-8 + 0.5 * 5e5 * len * len, 1e-12);
  EXPECT_NEAR((r.force - r.force.dot(n) * n).norm(), 5e5 * len, 1e-9);
}

TEST(ContactLaw, CapFollowsTheNormalForceWhenItDrops) {
  // Stuck at 80 % of the cap, then the overlap halves: the tangential force must drop to
  // the new cap, and the energy released from the spring beyond it is booked as slip work
  // (not lost): stored before = stored after + dissipated (no relative motion).
  LawParams p{1e6, 5e5, 0.5, 0, 0};
  Vec3 xi(0.8 * 0.5 * 1e6 * 1e-4 / 5e5, 0, 0);
  const Real before = 0.5 * 5e5 * xi.squaredNorm();
  const LawResult r = contact_law(p, 0.5e-4, ez, Vec3::Zero(), 1e-6, xi);
  const Real cap = 0.5 * 1e6 * 0.5e-4;
  EXPECT_NEAR(std::abs(r.force(0)), cap, 1e-9);
  const Real after = 0.5 * 5e5 * xi.squaredNorm();
  EXPECT_NEAR(before, after + r.slip_work, 1e-15);
  EXPECT_GT(r.slip_work, 0.0);
}

// The restitution the case key contact_restitution asks for is the one the law gives: a
// mass dropped head-on onto the spring-dashpot, integrated finely with the law itself
// (Velocity Verlet, 4000 steps per contact period), leaves with e times its speed. The
// bound 1e-3 is the integration's (halving dt changes e by less than 2e-4).
TEST(ContactLaw, DampingChosenForARestitutionGivesThatRestitution) {
  const Real m = 2.0, kn = 1e6;
  for (Real e : {0.2, 0.5, 0.8, 0.95, 1.0}) {
    const Real zeta = damping_for_restitution(e);
    EXPECT_NEAR(restitution_of_damping(zeta), e, 1e-10);
    const LawParams p{kn, 0, 0, 2 * zeta * std::sqrt(kn * m), 0};
    const Real dt = 2 * M_PI * std::sqrt(m / kn) / 4000;
    Real overlap = 0, v = -1.0;  // v: velocity of A along n (negative: approaching)
    Vec3 xi = Vec3::Zero();
    Real f = 0;
    for (int s = 0; s < 100000 && overlap >= 0; ++s) {
      v += 0.5 * dt * f / m;
      overlap -= dt * v;
      f = overlap > 0 ? contact_law(p, overlap, ez, Vec3(0, 0, v), dt, xi).force(2) : 0.0;
      v += 0.5 * dt * f / m;
    }
    EXPECT_LT(overlap, 0.0) << "e " << e << ": the mass never left";
    EXPECT_NEAR(v, e, 1e-3) << "e " << e << ", zeta " << zeta;
  }
  // The cut-off matters: the textbook zeta for e = 0.5 (0.2155, a dashpot that may pull)
  // gives 0.550 here, and the smallest restitution at critical damping is e^-2.
  EXPECT_NEAR(restitution_of_damping(0.2154537619662468), 0.5503, 5e-4);
  EXPECT_NEAR(restitution_of_damping(0.999999), min_restitution(), 1e-2);
  EXPECT_GT(damping_for_restitution(0.5), 0.2155);
}
