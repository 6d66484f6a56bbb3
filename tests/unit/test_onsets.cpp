// report/onsets: the first swept value at which a property holds, per realisation, and the
// middle of those.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <string>

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

TEST(Onsets, MedianIntervalTakesTheTabledRanksWithTheCoverageTheyGuarantee) {
  // The 95 % ranks for the median as Campbell & Gardner (BMJ 296:1454, 1988) table them, with
  // the coverage 1 - 2 P(B <= r - 1), B ~ Bin(n, 1/2), from exact binomial sums: n = 10 takes
  // the 2nd and 9th values (1 - 2 * 11/1024), n = 20 the 6th and 15th (1 - 2 * 21700/2^20),
  // n = 40 the 14th and 27th.
  struct Row {
    int n, lo, hi;
    double coverage;
  };
  for (const Row& row : {Row{10, 2, 9, 1.0 - 22.0 / 1024.0}, Row{20, 6, 15, 1.0 - 2.0 * 21700.0 / 1048576.0},
                         Row{40, 14, 27, 0.9615226917157997}}) {
    std::vector<double> v;
    for (int k = row.n; k >= 1; --k) v.push_back(0.1 * k);  // given in reverse: sorted inside
    const MedianInterval m = median_interval(v);
    EXPECT_EQ(m.rank, row.lo) << row.n;
    EXPECT_DOUBLE_EQ(m.lo, 0.1 * row.lo) << row.n;
    EXPECT_DOUBLE_EQ(m.hi, 0.1 * row.hi) << row.n;
    EXPECT_NEAR(m.coverage, row.coverage, 1e-12) << row.n;
  }
  // Five values cannot give 95 %: even the extremes cover the median with 1 - 2/32 only.
  const MedianInterval five = median_interval({1, 2, 3, 4, 5});
  EXPECT_EQ(five.rank, 0);
  EXPECT_TRUE(std::isnan(five.lo));
  // Six can, with the extremes (1 - 2/64); a lower level takes inner ranks.
  const MedianInterval six = median_interval({6, 5, 4, 3, 2, 1});
  EXPECT_EQ(six.rank, 1);
  EXPECT_DOUBLE_EQ(six.coverage, 1.0 - 2.0 / 64.0);
  EXPECT_EQ(median_interval({1, 2, 3, 4, 5, 6}, 0.5).rank, 2);  // P(B <= 1) = 7/64 <= 0.25
  // A censored upper half: the meshes that never came apart are +infinity, and so is the
  // interval's upper end once it reaches them.
  const double inf = INFINITY;
  std::vector<double> t = {0.6, 0.7, 0.8, 0.9, 1.0, 1.1, inf, inf, inf, inf};
  const MedianInterval cens = median_interval(t);
  EXPECT_DOUBLE_EQ(cens.lo, 0.7);
  EXPECT_TRUE(std::isinf(cens.hi));
  EXPECT_TRUE(std::isnan(median_interval({}).lo));
  // All censored from the lower rank on: one end, said once.
  const auto ms = [](double x) { return std::isinf(x) ? std::string("later") : fmt::format("{:.1f}", x); };
  EXPECT_EQ(median_interval_text(median_interval({0.6, inf, inf, inf, inf, inf, inf, inf, inf, inf}), ms, "few"),
            "later (97.9 %)");
  EXPECT_EQ(median_interval_text(cens, ms, "few"), "0.7 to later (97.9 %)");
  EXPECT_EQ(median_interval_text(five, ms, "few"), "few");
  // Ties (swept speeds): the ranks and their guarantee are the same; the values repeat.
  const MedianInterval ties = median_interval({5, 5, 7.5, 7.5, 7.5, 7.5, 10, 10, 10, 12.5});
  EXPECT_EQ(ties.rank, 2);
  EXPECT_EQ(ties.lo, 5);
  EXPECT_EQ(ties.hi, 10);
  // Many values: P(B = 0) = 2^-n underflows from n = 1075 on; the ranks must not collapse to
  // the middle there. The normal approximation's rank n/2 - 0.98 sqrt(n) (continuity
  // corrected) is within one of the exact one at n = 2000.
  std::vector<double> many;
  for (int k = 0; k < 2000; ++k) many.push_back(k);
  const MedianInterval big = median_interval(many);
  EXPECT_NEAR(big.rank, 1000 - 0.98 * std::sqrt(2000.0), 1.0);
  EXPECT_GE(big.coverage, 0.95);
  EXPECT_LT(big.coverage, 0.955);
  EXPECT_THROW(median_interval({1.0, std::nan(""), 2.0}), std::exception);
}
