// report/onsets: the first swept value at which a property holds, per realisation, and the
// middle of those.
#include <gtest/gtest.h>

#include <cmath>

#include "report/onsets.hpp"

using namespace dspdem::report;

TEST(Onsets, FirstValuePerRealisationInAnyOrderAndInfinityWhenNever) {
  // Realisation 2 holds at 7.5 and 10 (given out of order); 0 holds at 5, loses it at 7.5
  // and has it again at 10: its first is still 5; 1 never holds.
  const std::vector<SweepPoint> pts = {{2, 10.0, true}, {0, 7.5, false}, {1, 5.0, false},
                                       {2, 5.0, false}, {0, 10.0, true}, {2, 7.5, true},
                                       {1, 7.5, false}, {0, 5.0, true},  {1, 10.0, false}};
  const std::vector<Onset> o = first_onsets(pts);
  ASSERT_EQ(o.size(), 3u);
  EXPECT_EQ(o[0].realisation, 0);
  EXPECT_EQ(o[0].first, 5.0);
  EXPECT_EQ(o[1].realisation, 1);
  EXPECT_TRUE(std::isinf(o[1].first));
  EXPECT_EQ(o[2].realisation, 2);
  EXPECT_EQ(o[2].first, 7.5);
  EXPECT_TRUE(first_onsets({}).empty());
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
