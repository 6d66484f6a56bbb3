// The flat contact history (contact/pair_history): a rebuild of the candidate list keeps the
// tangential springs of the pairs that stay candidates, under their new index, and only
// theirs; lookups find a feature pair's elongation or zero; the spring energy of touches
// that end (or whose pair is dropped) is counted once, and only theirs; a spring is carried
// to a new cluster share at constant energy.
#include <gtest/gtest.h>

#include <cmath>

#include "contact/pair_history.hpp"
#include "core/error.hpp"

using namespace dspdem;
using namespace dspdem::contact;

namespace {
PairHistory two_pairs() {
  // Pair 0 touched through two feature pairs, pair 1 through none, pair 2 through one.
  PairHistory h;
  h.offset = {0, 2, 2, 3};
  h.entry = {{4, 1, 2, Vec3(1, 0, 0), 0.5}, {3, 0, 5, Vec3(0, 2, 0), 2.0}, {0, 3, 3, Vec3(0, 0, 3), 4.5}};
  return h;
}
// The stored elongation of a feature pair, or zero when it did not touch last step.
Vec3 xi_of(const PairHistory& h, Index p, int kind, int fa, int fb) {
  const HistoryEntry* e = h.entry_of(p, kind, fa, fb);
  return e ? e->xi : Vec3::Zero();
}
}  // namespace

TEST(PairHistory, FindsAFeaturePairsElongationOrZero) {
  const PairHistory h = two_pairs();
  EXPECT_EQ(h.pairs(), 3);
  EXPECT_EQ(xi_of(h, 0, 3, 0, 5), Vec3(0, 2, 0));
  EXPECT_EQ(xi_of(h, 0, 4, 1, 2), Vec3(1, 0, 0));
  EXPECT_EQ(xi_of(h, 0, 4, 2, 1), Vec3::Zero());  // the same features the other way round: another contact
  EXPECT_EQ(xi_of(h, 1, 4, 1, 2), Vec3::Zero());
  EXPECT_EQ(xi_of(h, 2, 0, 3, 3), Vec3(0, 0, 3));
}

TEST(PairHistory, ASpringIsCarriedToItsNewClusterShareAtConstantEnergy) {
  // Stored at share 0.5, looked up at share 0.25 and at 1: scaled by sqrt(0.5 / share), so
  // share x |xi|^2 (the spring's energy over fade x kt / 2) stays 0.5 x 4 = 2 (round-off);
  // at its own share it is the stored value bit for bit; a missing touch is zero at any share.
  PairHistory h = two_pairs();
  h.entry[1].share = 0.5;
  EXPECT_EQ(h.carry(0, 3, 0, 5, 0.5), Vec3(0, 2, 0));
  for (const Real share : {0.25, 1.0}) {
    const Vec3 xi = h.carry(0, 3, 0, 5, share);
    EXPECT_NEAR(share * xi.squaredNorm(), 2.0, 1e-14) << share;
    EXPECT_EQ(xi(0), 0.0);
    EXPECT_EQ(xi(2), 0.0);
  }
  EXPECT_EQ(h.carry(0, 4, 1, 2, 0.3), Vec3(1, 0, 0) * std::sqrt(1 / 0.3));  // stored at the default share 1
  EXPECT_EQ(h.carry(1, 4, 1, 2, 0.3), Vec3::Zero());
}

TEST(PairHistory, ARebuildCarriesTheSurvivingPairsToTheirNewIndex) {
  const std::vector<PairKey> old_keys = {{1, 2}, {1, 7}, {10, 3}};  // (10, 3): element 3 against wall 0 of 10 elements
  const std::vector<PairKey> new_keys = {{0, 4}, {1, 2}, {2, 9}, {10, 3}, {11, 3}};
  Real released = 0.25;  // added to, not set
  PairHistory before = two_pairs();
  before.entry[1].share = 0.5;  // the share the spring was stored at goes with it
  const PairHistory h = remap_history(before, old_keys, new_keys, &released);
  EXPECT_EQ(released, 0.25);  // the dropped pair (1, 7) held no touch
  ASSERT_EQ(h.pairs(), 5);
  EXPECT_EQ(h.offset, (std::vector<Index>{0, 0, 2, 2, 3, 3}));
  EXPECT_EQ(xi_of(h, 1, 3, 0, 5), Vec3(0, 2, 0));  // (1, 2) moved from index 0 to 1
  EXPECT_EQ(h.carry(1, 3, 0, 5, 0.5), Vec3(0, 2, 0));
  EXPECT_EQ(xi_of(h, 3, 0, 3, 3), Vec3(0, 0, 3));  // the wall pair from 2 to 3
  EXPECT_EQ(xi_of(h, 4, 0, 3, 3), Vec3::Zero());   // the same element against another wall: new
  const std::vector<Real> v = remap_values({0.5, 0.25, 0.125}, old_keys, new_keys, -1.0);
  EXPECT_EQ(v, (std::vector<Real>{-1.0, 0.5, -1.0, 0.125, -1.0}));
}

TEST(PairHistory, ASpringThatEndsLoadedIsReleasedOnce) {
  // After a step, pair 0 goes on through feature pair (3, 0, 5) and hands (4, 1, 2) over to
  // (2, 1, 2) (an edge-edge pair instead of a vertex-face one); pair 2's touch ends. The
  // energy released is that of (4, 1, 2) and of pair 2's touch: 0.5 + 4.5. A touch that
  // goes on keeps its energy in the ledger's stored energy, whatever its elongation now.
  const PairHistory before = two_pairs();
  PairHistory after;
  after.offset = {0, 2, 2, 2};
  after.entry = {{3, 0, 5, Vec3(0, 1, 0), 0.5}, {2, 1, 2, Vec3::Zero(), 0}};
  EXPECT_EQ(released_spring_energy(before, after), 5.0);
  EXPECT_EQ(released_spring_energy(before, before), 0.0);
  EXPECT_EQ(released_spring_energy(PairHistory{}, after), 0.0);  // the first step: nothing before
  // A rebuild drops pair 2 (its touch ended with the pair): remap_history counts it, and the
  // step after the rebuild, over the remapped history, counts only what ends then (pair 0's
  // handed-over touch): 4.5 + 0.5 in all, pair 2's spring once.
  Real released = 0;
  const PairHistory remapped = remap_history(before, {{1, 2}, {1, 7}, {10, 3}}, {{1, 2}, {1, 7}}, &released);
  EXPECT_EQ(released, 4.5);
  PairHistory next;
  next.offset = {0, 2, 2};
  next.entry = after.entry;
  released += released_spring_energy(remapped, next);
  EXPECT_EQ(released, 5.0);
  PairHistory short_list;
  short_list.offset = {0, 0};
  EXPECT_THROW(released_spring_energy(before, short_list), Error);  // not the same pairs
}

TEST(PairHistory, ASpringTakenOverByASuccessorIsNotReleased) {
  // As in the last test, but the edge-edge touch (2, 1, 2) took over the spring of (4, 1, 2)
  // (ContactSystem::springs_of): that spring goes on, so only pair 2's ends (4.5).
  const PairHistory before = two_pairs();
  PairHistory after;
  after.offset = {0, 2, 2, 2};
  after.entry = {{3, 0, 5, Vec3(0, 1, 0), 0.5}, {2, 1, 2, Vec3(1, 0, 0), 0.5}};
  after.entry[1].from_kind = 4, after.entry[1].from_fa = 1, after.entry[1].from_fb = 2;
  EXPECT_EQ(released_spring_energy(before, after), 4.5);
  after.entry[1].from_fb = 3;  // taken over from a feature pair the pair did not have: (4, 1, 2) ends
  EXPECT_EQ(released_spring_energy(before, after), 5.0);
}
