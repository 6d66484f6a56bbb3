// The flat contact history (contact/pair_history): a rebuild of the candidate list keeps the
// tangential springs of the pairs that stay candidates, under their new index, and only
// theirs; lookups find a feature pair's elongation or zero.
#include <gtest/gtest.h>

#include "contact/pair_history.hpp"

using namespace dspdem;
using namespace dspdem::contact;

namespace {
PairHistory two_pairs() {
  // Pair 0 touched through two feature pairs, pair 1 through none, pair 2 through one.
  PairHistory h;
  h.offset = {0, 2, 2, 3};
  h.entry = {{4, 1, 2, Vec3(1, 0, 0)}, {3, 0, 5, Vec3(0, 2, 0)}, {0, 3, 3, Vec3(0, 0, 3)}};
  return h;
}
}  // namespace

TEST(PairHistory, FindsAFeaturePairsElongationOrZero) {
  const PairHistory h = two_pairs();
  EXPECT_EQ(h.pairs(), 3);
  EXPECT_EQ(h.find(0, 3, 0, 5), Vec3(0, 2, 0));
  EXPECT_EQ(h.find(0, 4, 1, 2), Vec3(1, 0, 0));
  EXPECT_EQ(h.find(0, 4, 2, 1), Vec3::Zero());  // the same features the other way round: another contact
  EXPECT_EQ(h.find(1, 4, 1, 2), Vec3::Zero());
  EXPECT_EQ(h.find(2, 0, 3, 3), Vec3(0, 0, 3));
}

TEST(PairHistory, ARebuildCarriesTheSurvivingPairsToTheirNewIndex) {
  const std::vector<PairKey> old_keys = {{1, 2}, {1, 7}, {10, 3}};  // (10, 3): element 3 against wall 0 of 10 elements
  const std::vector<PairKey> new_keys = {{0, 4}, {1, 2}, {2, 9}, {10, 3}, {11, 3}};
  const PairHistory h = remap_history(two_pairs(), old_keys, new_keys);
  ASSERT_EQ(h.pairs(), 5);
  EXPECT_EQ(h.offset, (std::vector<Index>{0, 0, 2, 2, 3, 3}));
  EXPECT_EQ(h.find(1, 3, 0, 5), Vec3(0, 2, 0));  // (1, 2) moved from index 0 to 1
  EXPECT_EQ(h.find(3, 0, 3, 3), Vec3(0, 0, 3));  // the wall pair from 2 to 3
  EXPECT_EQ(h.find(4, 0, 3, 3), Vec3::Zero());   // the same element against another wall: new
  const std::vector<Real> v = remap_values({0.5, 0.25, 0.125}, old_keys, new_keys, -1.0);
  EXPECT_EQ(v, (std::vector<Real>{-1.0, 0.5, -1.0, 0.125, -1.0}));
}
