// The early-end rule of a run ([time] stop_series): stops only after the peak, on the drop.
#include <gtest/gtest.h>

#include "time/stop_rule.hpp"

using namespace dspdem;

TEST(StopRule, StopsOnlyAfterThePeakHasFallenBelowTheFraction) {
  PeakDropStop r(0.3, 0.0);
  // A compressive (negative) load rising to 10 kN and falling: the sign must not matter.
  const double load[] = {0, -2e3, -6e3, -10e3, -8e3, -4e3, -3.5e3};
  for (double f : load) EXPECT_FALSE(r.update(f)) << f;
  EXPECT_DOUBLE_EQ(r.peak(), 10e3);
  EXPECT_TRUE(r.update(-2.9e3));  // below 0.3 x 10 kN
}

TEST(StopRule, TheFirstContactsRingingDoesNotEndTheRun) {
  // Plates touching a disc ring: 500 N, then 0, before the real loading. Without a
  // min_peak the zero would end the run; with 5 kN it must not.
  PeakDropStop naive(0.3, 0.0), guarded(0.3, 5e3);
  EXPECT_FALSE(naive.update(500));
  EXPECT_TRUE(naive.update(0));
  EXPECT_FALSE(guarded.update(500));
  EXPECT_FALSE(guarded.update(0));
  EXPECT_FALSE(guarded.update(20e3));
  EXPECT_TRUE(guarded.update(1e3));
}
