// A run's output times: the schedule moves past the step's time and never spins.
#include <gtest/gtest.h>

#include "run/output_schedule.hpp"

using namespace dspdem;

TEST(OutputSchedule, AddsTheIntervalAsASumAsBefore) {
  // The usual case: one interval past, by the same sum the loop always made, so that runs
  // keep their output steps to the bit.
  double sum = 0.1;
  while (sum <= 0.35) sum += 0.1;
  EXPECT_EQ(next_output_time(0.1, 0.35, 0.1, 0.0), sum);
  EXPECT_EQ(next_output_time(0.5, 0.35, 0.1, 0.0), 0.5);  // not due yet: unchanged
  // Exactly at an output time (within the tolerance) moves to the next one.
  EXPECT_EQ(next_output_time(0.25, 0.25 - 1e-15, 0.25, 1e-12), 0.5);
}

TEST(OutputSchedule, AnIntervalBelowTheDoublesSpacingStillMovesOn) {
  // 1e-30 s at t = 1e-6 s: adding it leaves the sum where it is (the run spun here).
  const double t = 1e-6, tol = 1e-18;
  const double n = next_output_time(1e-30, t, 1e-30, tol);
  EXPECT_GT(n, t + tol);
  EXPECT_LT(n, t + 2 * tol);  // the first time past, not a step later
}

TEST(OutputSchedule, AStepOfMillionsOfIntervalsJumpsInOneGo) {
  // A 1 s step over 1e-7 s intervals would otherwise add ten million times.
  const double n = next_output_time(1e-7, 1.0, 1e-7, 0.0);
  EXPECT_GT(n, 1.0);
  EXPECT_LE(n, 1.0 + 1e-7 * (1 + 1e-6));
}
