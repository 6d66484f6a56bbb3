// A run's output times: the schedule moves past the step's time and never spins.
#include <gtest/gtest.h>

#include "run/output_schedule.hpp"

using namespace dspdem;

TEST(OutputSchedule, AddsTheIntervalAsASumAsBefore) {
  // The usual case: one interval past, by the same sum the loop always made, so that runs
  // keep their output steps to the bit.
  // At t = 0.75 the sum of eight tenths is 0.7999999999999999, eight times a tenth 0.8: a
  // schedule that multiplied would move some runs' outputs by a step.
  double sum = 0.1;
  while (sum <= 0.75) sum += 0.1;
  ASSERT_NE(sum, 8 * 0.1);
  EXPECT_EQ(next_output_time(0.1, 0.75, 0.1, 0.0), sum);
  EXPECT_EQ(next_output_time(0.5, 0.35, 0.1, 0.0), 0.5);  // not due yet: unchanged
  // Exactly at an output time (within the tolerance) moves to the next one.
  EXPECT_EQ(next_output_time(0.25, 0.25 - 1e-15, 0.25, 1e-12), 0.5);
}

TEST(OutputSchedule, AnIntervalBelowTheDoublesSpacingStillMovesOn) {
  // 1e-30 s at t = 1e-6 s: adding it leaves the sum where it is (the run spun here; the old
  // loop never returns, and the test's timeout fails it).
  const double t = 1e-6, tol = 1e-18;
  const double n = next_output_time(1e-30, t, 1e-30, tol);
  EXPECT_GT(n, t + tol);
  EXPECT_LT(n, t + 2 * tol);  // the first time past, not a step later
}

TEST(OutputSchedule, AStepOfATrillionIntervalsJumpsInOneGo) {
  // A 1 s step over 1e-12 s intervals: adding them one by one would take tens of minutes
  // (the test's timeout fails it then, as it fails the spin above).
  const double n = next_output_time(1e-12, 1.0, 1e-12, 0.0);
  EXPECT_GT(n, 1.0);
  EXPECT_LE(n, 1.0 + 2e-12);
}
