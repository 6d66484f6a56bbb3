// The Wilson score interval against published values.
#include <gtest/gtest.h>

#include "report/proportion.hpp"

using dspdem::report::wilson_interval;

// Newcombe (Stat. Med. 17:857-872, 1998): the four examples he works through every method
// with, 95 %, his method 3 (score, no continuity correction), printed to four decimals. Tolerance 5e-5: half the
// last printed digit.
TEST(Proportion, WilsonMatchesNewcombesTable) {
  struct Row {
    int k, n;
    double lo, hi;
  };
  for (const Row& r : {Row{81, 263, 0.2553, 0.3662}, Row{15, 148, 0.0624, 0.1605}, Row{0, 20, 0.0, 0.1611},
                       Row{1, 29, 0.0061, 0.1718}}) {
    const auto i = wilson_interval(r.k, r.n);
    EXPECT_NEAR(i.lo, r.lo, 5e-5) << r.k << " of " << r.n;
    EXPECT_NEAR(i.hi, r.hi, 5e-5) << r.k << " of " << r.n;
  }
}

// Properties that hold for any k of n: inside [0, 1], around k / n, symmetric under
// k -> n - k, narrower with more draws at the same proportion, wider at a higher confidence.
TEST(Proportion, WilsonIsABracketThatNarrowsWithDraws) {
  for (int n : {1, 5, 10, 20, 100})
    for (int k = 0; k <= n; ++k) {
      const auto i = wilson_interval(k, n), m = wilson_interval(n - k, n);
      const double p = static_cast<double>(k) / n;
      EXPECT_GE(i.lo, 0.0);
      EXPECT_LE(i.hi, 1.0);
      EXPECT_LE(i.lo, p);
      EXPECT_GE(i.hi, p);
      EXPECT_NEAR(i.lo, 1.0 - m.hi, 1e-12);
      EXPECT_NEAR(i.hi, 1.0 - m.lo, 1e-12);
      const auto w = wilson_interval(k, n, 2.575829);  // 99 %
      EXPECT_LT(w.lo, i.lo + 1e-15);
      EXPECT_GT(w.hi, i.hi - 1e-15);
    }
  const auto ten = wilson_interval(3, 10), hundred = wilson_interval(30, 100);
  EXPECT_LT(hundred.hi - hundred.lo, ten.hi - ten.lo);
  const auto none = wilson_interval(0, 0);
  EXPECT_EQ(none.lo, 0.0);
  EXPECT_EQ(none.hi, 1.0);
}
