// Which spring of the last step a pair's touch goes on with (contact/spring_handover): its
// own feature pair's; else, for a touch that pushes and carries weight, the nearest spring no
// touch claimed, within the reach, at the ended touch's stored energy; else none. And which
// springs end (mark_ended), so that each is released once. Checked against entries placed by
// hand, each case against the rule it tests.
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
  // Beyond the reach, nothing: 28 and 32 mm from the two points, reach 20 mm.
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
  // The entry was stored at weight 0.5 (share 1 x fade 0.5), the touch now has weight 0.1
  // and share 0.4. Own: carried by the share alone, share x |xi|^2 kept (1 x 1 = 0.4 x 2.5;
  // the fade's gradient is in the force). Successor: the ended touch's stored energy whole,
  // weight x |xi|^2 kept (0.5 x 1 = 0.1 x 5). The two rules give different lengths here.
  HistoryEntry e = entry(Feature::VF, 1, 2, Vec3::Zero(), Vec3(1, 0, 0));
  e.weight = 0.5;
  Touch t = touch(Feature::EE, 0, 0, Vec3::Zero(), 1e-4);
  t.weight = 0.1, t.share = 0.4;
  const Vec3 own = starting_spring(SpringFrom{&e, false}, t);
  EXPECT_NEAR(own.squaredNorm(), 2.5, 1e-14);
  const Vec3 taken = starting_spring(SpringFrom{&e, true}, t);
  EXPECT_NEAR(taken.squaredNorm(), 5.0, 1e-14);
  for (const Vec3& xi : {own, taken}) {  // the same direction
    EXPECT_GT(xi(0), 0.0);
    EXPECT_EQ(xi(1), 0.0);
    EXPECT_EQ(xi(2), 0.0);
  }
  EXPECT_EQ(starting_spring(SpringFrom{}, t), Vec3::Zero());
}

TEST(SpringHandover, ASpringEndsUnlessATouchThatPushesGoesOnWithIt) {
  // Two pairs: pair 0 with the two entries of last_step, pair 1 with one. In pair 0, (1, 2)
  // goes on itself and pushes; a new touch took (3, 5) over but gave no force (the function's
  // contract: in ContactSystem springs_of hands a spring over only to a touch that pushes, by
  // the same test as the evaluation's), so (3, 5) ends. Pair 1's only touch matched its own
  // entry but has opened: it ends. Only pair p's entries are written (7: not written).
  PairHistory h = last_step();
  h.offset = {0, 2, 3};
  h.entry.push_back(entry(Feature::VV, 0, 0, Vec3::Zero(), Vec3(0, 1, 0)));
  std::vector<char> ended(3, 7);
  mark_ended(h, 0, {SpringFrom{&h.entry[0], false}, SpringFrom{&h.entry[1], true}}, {1, 0}, ended);
  EXPECT_EQ(ended, (std::vector<char>{0, 1, 7}));
  mark_ended(h, 0, {SpringFrom{&h.entry[0], false}, SpringFrom{&h.entry[1], true}}, {1, 1}, ended);
  EXPECT_EQ(ended, (std::vector<char>{0, 0, 7}));  // the successor pushes: nothing ends
  mark_ended(h, 1, {SpringFrom{&h.entry[2], false}}, {0}, ended);
  EXPECT_EQ(ended, (std::vector<char>{0, 0, 1}));
  ended[2] = 7;
  mark_ended(h, 1, {SpringFrom{}}, {1}, ended);  // a new contact: the old spring ends
  EXPECT_EQ(ended, (std::vector<char>{0, 0, 1}));
  mark_ended(h, 0, {}, {}, ended);  // no touches: both end
  EXPECT_EQ(ended, (std::vector<char>{1, 1, 1}));
  ended.assign(3, 7);
  mark_ended(h, 2, {SpringFrom{}}, {1}, ended);  // a pair new since the rebuild has none
  EXPECT_EQ(ended, (std::vector<char>{7, 7, 7}));
}

TEST(SpringHandover, ARebuildThenAStepReleaseEachSpringOnce) {
  // springs_of, mark_ended and remap_history together, as ContactSystem uses them. A rebuild
  // drops pair (10, 3), holding 4.5 (remap_history counts it); in the step after it, pair
  // (1, 2)'s touch (1, 2) goes on and a new touch 1 mm from (3, 5)'s point takes that one
  // over: nothing more is released. Had the contact gone in that step instead, both would
  // have ended: 0.5 + 2.
  PairHistory h = last_step();
  h.offset = {0, 2, 2, 3};
  h.entry.push_back(entry(Feature::VF, 0, 0, Vec3::Zero(), Vec3(0, 0, 3)));
  h.entry[0].spring_energy = 0.5, h.entry[1].spring_energy = 2, h.entry[2].spring_energy = 4.5;
  Real released = 0;
  const PairHistory after = remap_history(h, {{1, 2}, {1, 7}, {10, 3}}, {{1, 2}, {1, 7}}, &released);
  EXPECT_EQ(released, 4.5);
  auto step = [&](const PairHistory& hist, const std::vector<std::vector<Touch>>& touches) {
    std::vector<char> ended(hist.entry.size(), 0);
    for (Index p = 0; p < hist.pairs(); ++p) {
      std::vector<SpringFrom> from;
      springs_of(hist, p, touches[p], kR, kR, 0, 2 * kR, from);
      mark_ended(hist, p, from, std::vector<char>(touches[p].size(), 1), ended);
    }
    for (std::size_t k = 0; k < hist.entry.size(); ++k)
      if (ended[k]) released += hist.entry[k].spring_energy;
  };
  step(after, {{touch(Feature::VF, 1, 2, Vec3::Zero(), 1e-4), touch(Feature::EE, 0, 1, Vec3(0.005, 0, 0), 1e-4)}, {}});
  EXPECT_EQ(released, 4.5);
  step(after, {{}, {}});
  EXPECT_EQ(released, 7.0);
}
