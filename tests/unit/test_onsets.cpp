// report/onsets: the first swept value at which a property holds, per realisation, and the
// middle of those.
#include <gtest/gtest.h>

#include <cmath>

#include "report/onsets.hpp"

using namespace dspdem::report;

TEST(Onsets, FirstValuePerRealisationInAnyOrderAndInfinityWhenNever) {
  // Realisation 2 holds at 7.5 and 10 (given out of order); 0 holds at 5, loses it at 7.5
  // and has it again at 10: its first is still 5; 1 never holds; 3 holds at 5 then at 10 (the
  // lowest given first).
  const std::vector<SweepPoint> pts = {{2, 10.0, true},  {0, 7.5, false}, {1, 5.0, false}, {2, 5.0, false},
                                       {0, 10.0, true},  {2, 7.5, true},  {1, 7.5, false}, {0, 5.0, true},
                                       {1, 10.0, false}, {3, 5.0, true},  {3, 10.0, true}};
  const std::vector<Onset> o = first_onsets(pts);
  ASSERT_EQ(o.size(), 4u);
  EXPECT_EQ(o[0].realisation, 0);
  EXPECT_EQ(o[0].first, 5.0);
  EXPECT_EQ(o[1].realisation, 1);
  EXPECT_TRUE(std::isinf(o[1].first));
  EXPECT_EQ(o[2].realisation, 2);
  EXPECT_EQ(o[2].first, 7.5);
  EXPECT_EQ(o[3].first, 5.0);
  for (const Onset& x : o) {
    EXPECT_EQ(x.highest_known, 10.0);
    EXPECT_FALSE(x.failed_below);
  }
  EXPECT_TRUE(first_onsets({}).empty());
}

TEST(Onsets, AFailedRunBelowTheFirstMakesItAnUpperBound) {
  // 0: failed at 5, holds from 7.5: first 7.5, but it may have held at 5. 1: holds at 5,
  // failed at 10 (above): first 5 is exact. 2: never holds, failed at 10: its highest run is
  // 7.5 and the failed one lies below "never". 3: every run failed.
  const std::vector<SweepPoint> pts = {{0, 5.0, false, false}, {0, 7.5, true},          {0, 10.0, true},
                                       {1, 5.0, true},         {1, 10.0, false, false}, {2, 5.0, false},
                                       {2, 7.5, false},        {2, 10.0, false, false}, {3, 5.0, false, false}};
  const std::vector<Onset> o = first_onsets(pts);
  ASSERT_EQ(o.size(), 4u);
  EXPECT_EQ(o[0].first, 7.5);
  EXPECT_TRUE(o[0].failed_below);
  EXPECT_EQ(o[0].highest_known, 10.0);
  EXPECT_EQ(o[1].first, 5.0);
  EXPECT_FALSE(o[1].failed_below);
  EXPECT_EQ(o[1].highest_known, 5.0);
  EXPECT_TRUE(std::isinf(o[2].first));
  EXPECT_TRUE(o[2].failed_below);
  EXPECT_EQ(o[2].highest_known, 7.5);
  EXPECT_TRUE(std::isinf(o[3].first));
  EXPECT_TRUE(o[3].failed_below);
  EXPECT_TRUE(std::isnan(o[3].highest_known));
}

TEST(Onsets, MiddleOfOddAndEvenCountsWithNeverAsTheLargest) {
  const Middle odd = middle({10.0, 5.0, 7.5});
  EXPECT_EQ(odd.low, 7.5);
  EXPECT_EQ(odd.high, 7.5);
  const Middle even = middle({12.5, 8.75, 10.0, 7.5});
  EXPECT_EQ(even.low, 8.75);
  EXPECT_EQ(even.high, 10.0);
  // Session 60's ten meshes, first speed with a few large pieces (o9 never by 15 m/s).
  const double inf = INFINITY;
  const Middle ten = middle({8.75, 8.75, 7.5, 12.5, 12.5, 10.0, 12.5, 10.0, 8.75, inf});
  EXPECT_EQ(ten.low, 10.0);
  EXPECT_EQ(ten.high, 10.0);
  const Middle never = middle({inf, 5.0, inf});
  EXPECT_TRUE(std::isinf(never.low));
  EXPECT_TRUE(std::isnan(middle({}).low));
}
