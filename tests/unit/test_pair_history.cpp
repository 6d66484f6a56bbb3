// The flat contact history (contact/pair_history): a rebuild of the candidate list keeps the
// tangential springs of the pairs that stay candidates, under their new index, and only
// theirs, and counts the spring energy of the pairs it drops, only theirs; a spring is
// carried to a new cluster share at constant energy. Which entry a touch goes on with:
// test_spring_handover.
#include <gtest/gtest.h>

#include <cmath>

#include "contact/pair_history.hpp"

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
// Pair p's entries, in order, by their elongation (each entry of two_pairs has its own).
std::vector<Vec3> xis_of(const PairHistory& h, Index p) {
  std::vector<Vec3> out;
  for (Index k = h.offset[p]; k < h.offset[p + 1]; ++k) out.push_back(h.entry[k].xi);
  return out;
}
}  // namespace

TEST(PairHistory, ASpringIsCarriedToItsNewClusterShareAtConstantEnergy) {
  // Stored at share 0.5, carried to share 0.25 and to 1: scaled by sqrt(0.5 / share), so
  // share x |xi|^2 (the spring's energy over fade x kt / 2) stays 0.5 x 4 = 2 (round-off);
  // at its own share it is the stored value bit for bit.
  PairHistory h = two_pairs();
  h.entry[1].share = 0.5;
  EXPECT_EQ(PairHistory::carry(h.entry[1], 0.5), Vec3(0, 2, 0));
  for (const Real share : {0.25, 1.0}) {
    const Vec3 xi = PairHistory::carry(h.entry[1], share);
    EXPECT_NEAR(share * xi.squaredNorm(), 2.0, 1e-14) << share;
    EXPECT_EQ(xi(0), 0.0);
    EXPECT_EQ(xi(2), 0.0);
  }
  EXPECT_EQ(PairHistory::carry(h.entry[0], 0.3), Vec3(1, 0, 0) * std::sqrt(1 / 0.3));  // stored at the default share 1
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
  EXPECT_EQ(xis_of(h, 1), (std::vector<Vec3>{Vec3(1, 0, 0), Vec3(0, 2, 0)}));  // (1, 2) moved from index 0 to 1
  EXPECT_EQ(h.entry[1].share, 0.5);
  EXPECT_EQ(xis_of(h, 3), (std::vector<Vec3>{Vec3(0, 0, 3)}));  // the wall pair from 2 to 3
  EXPECT_TRUE(xis_of(h, 4).empty());                            // the same element against another wall: new
  EXPECT_TRUE(xis_of(h, 0).empty() && xis_of(h, 2).empty());    // new pairs start empty
  const std::vector<Real> v = remap_values({0.5, 0.25, 0.125}, old_keys, new_keys, -1.0);
  EXPECT_EQ(v, (std::vector<Real>{-1.0, 0.5, -1.0, 0.125, -1.0}));
}

TEST(PairHistory, ARebuildReleasesTheSpringsOfTheDroppedPairsOnly) {
  // Pairs (1, 2) and (10, 3) stay candidates, (1, 7) is dropped with nothing; then (10, 3),
  // holding 4.5, is dropped too: only its energy is counted, once.
  Real released = 0;
  const PairHistory kept = remap_history(two_pairs(), {{1, 2}, {1, 7}, {10, 3}}, {{1, 2}, {1, 7}, {10, 3}}, &released);
  EXPECT_EQ(released, 0.0);
  const PairHistory remapped = remap_history(kept, {{1, 2}, {1, 7}, {10, 3}}, {{1, 2}, {1, 7}}, &released);
  EXPECT_EQ(released, 4.5);
  EXPECT_EQ(remapped.pairs(), 2);
  EXPECT_EQ(remapped.entry.size(), 2u);
  remap_history(remapped, {{1, 2}, {1, 7}}, {{1, 2}, {1, 7}}, &released);
  EXPECT_EQ(released, 4.5);
}
