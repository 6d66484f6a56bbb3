// Which spring of the last step a pair's touch goes on with (contact/spring_handover): its
// own feature pair's; else, for a touch that pushes and carries weight, the nearest spring no
// touch claimed, within the reach, at the ended touch's stored energy; else none. Checked
// against entries placed by hand, each case against the rule it tests.
#include <gtest/gtest.h>

#include <cmath>

#include "contact/spring_handover.hpp"

using namespace dspdem;
using namespace dspdem::contact;

namespace {
constexpr Real kR = 0.01;  // both roundings: the contact point is the touch's pa = pb

Touch touch(Feature kind, int fa, int fb, const Vec3& at, Real overlap, Real weight = 1) {
  Touch t;
  t.kind = kind, t.fa = fa, t.fb = fb;
  t.pa = t.pb = at;
  t.n = Vec3(0, 1, 0);
  t.d = 2 * kR - overlap;
  t.weight = t.share = weight;
  return t;
}
HistoryEntry entry(Feature kind, int fa, int fb, const Vec3& at, const Vec3& xi, Real weight = 1) {
  HistoryEntry e;
  e.kind = static_cast<int>(kind), e.fa = fa, e.fb = fb;
  e.c = at, e.xi = xi, e.weight = e.share = weight;
  return e;
}
// Pair 0 touched at two points 4 mm apart last step; pair 1 did not touch.
PairHistory last_step() {
  PairHistory h;
  h.offset = {0, 2, 2};
  h.entry = {entry(Feature::VF, 1, 2, Vec3(0, 0, 0), Vec3(1, 0, 0)),
             entry(Feature::EE, 3, 5, Vec3(0.004, 0, 0), Vec3(0, 0, 2))};
  return h;
}
std::vector<SpringFrom> springs(const PairHistory& h, Index p, const std::vector<Touch>& touches, Real offset = 0,
                                Real reach = 2 * kR) {
  std::vector<SpringFrom> out;
  springs_of(h, p, touches, kR, kR, offset, reach, out);
  return out;
}
}  // namespace

TEST(SpringHandover, ATouchGoesOnWithItsOwnFeaturePairsSpring) {
  const PairHistory h = last_step();
  const auto out =
      springs(h, 0, {touch(Feature::EE, 3, 5, Vec3(0.01, 0, 0), 1e-4), touch(Feature::VF, 1, 2, Vec3::Zero(), 1e-4)});
  ASSERT_EQ(out.size(), 2u);
  EXPECT_EQ(out[0].entry, &h.entry[1]);
  EXPECT_FALSE(out[0].successor);  // its own, however far it moved
  EXPECT_EQ(out[1].entry, &h.entry[0]);
  EXPECT_FALSE(out[1].successor);
  // The same features the other way round are another contact; a pair with no entries, or
  // one past the history's pairs (new since the rebuild), starts every touch afresh.
  EXPECT_EQ(springs(h, 0, {touch(Feature::FV, 2, 1, Vec3(0.1, 0, 0), 1e-4)})[0].entry, nullptr);
  EXPECT_EQ(springs(h, 1, {touch(Feature::VF, 1, 2, Vec3::Zero(), 1e-4)})[0].entry, nullptr);
  EXPECT_EQ(springs(h, 2, {touch(Feature::VF, 1, 2, Vec3::Zero(), 1e-4)})[0].entry, nullptr);
}

TEST(SpringHandover, ANewTouchTakesOverTheNearestSpringNoTouchClaimed) {
  // (1, 2) goes on itself; a new edge-edge touch 1 mm from (3, 5)'s point takes (3, 5)'s
  // spring, not the nearer (1, 2)'s, which its own touch claimed.
  const PairHistory h = last_step();
  auto out =
      springs(h, 0, {touch(Feature::EE, 1, 2, Vec3(0.001, 0, 0), 1e-4), touch(Feature::VF, 1, 2, Vec3::Zero(), 1e-4)});
  EXPECT_EQ(out[0].entry, &h.entry[1]);
  EXPECT_TRUE(out[0].successor);
  EXPECT_EQ(out[1].entry, &h.entry[0]);
  // Two new touches, both nearest (1, 2)'s point: the first in order takes it, the second the
  // one left; a third finds none.
  out = springs(h, 0,
                {touch(Feature::VE, 0, 0, Vec3(0.001, 0, 0), 1e-4), touch(Feature::VE, 0, 1, Vec3(0.0005, 0, 0), 1e-4),
                 touch(Feature::VE, 0, 2, Vec3(0.0002, 0, 0), 1e-4)});
  EXPECT_EQ(out[0].entry, &h.entry[0]);
  EXPECT_EQ(out[1].entry, &h.entry[1]);
  EXPECT_EQ(out[2].entry, nullptr);
  // Beyond the reach, nothing: 30 mm from both points, reach 20 mm.
  EXPECT_EQ(springs(h, 0, {touch(Feature::VE, 0, 0, Vec3(0.03, 0.01, 0), 1e-4)})[0].entry, nullptr);
}

TEST(SpringHandover, OnlyATouchThatPushesAndCarriesWeightTakesASpringOver) {
  const PairHistory h = last_step();
  const Vec3 at(0.001, 0, 0);
  EXPECT_EQ(springs(h, 0, {touch(Feature::VE, 0, 0, at, -1e-4)})[0].entry, nullptr);  // apart
  EXPECT_EQ(springs(h, 0, {touch(Feature::VE, 0, 0, at, 1e-4)}, 2e-4)[0].entry,
            nullptr);  // within the overlap the pair was born with
  EXPECT_NE(springs(h, 0, {touch(Feature::VE, 0, 0, at, 3e-4)}, 2e-4)[0].entry, nullptr);  // past it
  EXPECT_EQ(springs(h, 0, {touch(Feature::VE, 0, 0, at, 1e-4, 0.0)})[0].entry, nullptr);   // faded out
  // A faded touch of weight 0 held no energy: its spring is not taken over.
  PairHistory faded = last_step();
  faded.entry[0].weight = faded.entry[1].weight = 0;
  EXPECT_EQ(springs(faded, 0, {touch(Feature::VE, 0, 0, at, 1e-4)})[0].entry, nullptr);
  // But a touch of its own feature pair goes on with its own spring, pushing or not: whether
  // that spring then ends is the evaluation's (ContactSystem::evaluate_pair).
  EXPECT_EQ(springs(faded, 0, {touch(Feature::VF, 1, 2, Vec3::Zero(), -1e-4)})[0].entry, &faded.entry[0]);
}

TEST(SpringHandover, ASpringGoesOnAtItsStoredEnergy) {
  // Own: carried to the touch's cluster share at constant share x |xi|^2. Successor: at the
  // ended touch's weight x |xi|^2 (0.5 x 1), whatever the new touch's weight and share.
  HistoryEntry e = entry(Feature::VF, 1, 2, Vec3::Zero(), Vec3(1, 0, 0), 0.5);
  const Touch t = touch(Feature::EE, 0, 0, Vec3::Zero(), 1e-4, 0.25);
  const Vec3 own = starting_spring(SpringFrom{&e, false}, t);
  EXPECT_NEAR(t.share * own.squaredNorm(), e.share * e.xi.squaredNorm(), 1e-15);
  const Vec3 taken = starting_spring(SpringFrom{&e, true}, t);
  EXPECT_NEAR(t.weight * taken.squaredNorm(), 0.5, 1e-15);
  EXPECT_GT(taken(0), 0.0);  // the same direction
  EXPECT_EQ(taken(1), 0.0);
  EXPECT_EQ(taken(2), 0.0);
  EXPECT_EQ(starting_spring(SpringFrom{}, t), Vec3::Zero());
}
