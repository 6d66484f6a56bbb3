// The chi-square test of homogeneity and its permutation test against tabulated and exact values.
#include <gtest/gtest.h>

#include <cmath>

#include "report/homogeneity.hpp"

using dspdem::report::chi_square_sf;
using dspdem::report::homogeneity;

// The chi-square distribution's upper 5 % and 1 % points (tabulated to three decimals in e.g.
// the NIST/SEMATECH e-Handbook of Statistical Methods, table 1.3.6.7.4; here to 16 digits, as
// a quantile function gives them): the survival function there is 0.05 and 0.01. Tolerance 1e-10: the closed form is
// exact up to rounding, and 16-digit points move the value by under 1e-14.
TEST(Homogeneity, ChiSquareTailMatchesTabulatedPoints) {
  struct Row {
    double x;
    int dof;
    double p;
  };
  for (const Row& r :
       {Row{3.841458820694124, 1, 0.05}, Row{5.991464547107979, 2, 0.05}, Row{7.814727903251178, 3, 0.05},
        Row{9.487729036781154, 4, 0.05}, Row{11.070497693516351, 5, 0.05}, Row{16.918977604620448, 9, 0.05},
        Row{6.634896601021214, 1, 0.01}, Row{9.210340371976182, 2, 0.01}, Row{21.665994333461924, 9, 0.01}})
    EXPECT_NEAR(chi_square_sf(r.x, r.dof), r.p, 1e-10) << r.x << " on " << r.dof;
}

// Exact forms: two degrees of freedom give e^(-x/2), one gives erfc(sqrt(x/2)); nothing above x
// = 0 is 1; far into the tail with many degrees of freedom the sum neither overflows nor
// underflows (the median of chi-square on k degrees of freedom lies near k (1 - 2 / (9 k))^3,
// Wilson and Hilferty 1931, just under k).
TEST(Homogeneity, ChiSquareTailExactForms) {
  for (double x : {0.1, 1.0, 7.3, 40.0}) {
    EXPECT_NEAR(chi_square_sf(x, 2), std::exp(-0.5 * x), 1e-14 * std::max(1.0, std::exp(-0.5 * x)));
    EXPECT_NEAR(chi_square_sf(x, 1), std::erfc(std::sqrt(0.5 * x)), 1e-14);
  }
  EXPECT_EQ(chi_square_sf(0.0, 4), 1.0);
  const double big = chi_square_sf(2000.0, 2000);
  EXPECT_GT(big, 0.45);
  EXPECT_LT(big, 0.5);
  EXPECT_LT(chi_square_sf(3000.0, 2001), 1e-12);
}

// 3 of 10 against 7 of 10: Pearson's statistic by hand is 4 (2^2 / 5) = 3.2 on one degree of
// freedom, the between share 3.2 / 20 = 0.16. The permutation test is Fisher's exact test
// (two-sided, by the statistic): P(k <= 3 or k >= 7) under the hypergeometric of 10 drawn from
// 10 + 10 = 2 (1 + 100 + 2025 + 14400) / 184756 = 0.17889. With 20000 shuffles its standard
// error is 0.0027; tolerance four of them.
TEST(Homogeneity, TwoGroupsAgainstHandAndFisher) {
  auto group = [](int k, int n) {
    std::vector<bool> g(n, false);
    for (int i = 0; i < k; ++i) g[i] = true;
    return g;
  };
  const auto h = homogeneity({group(3, 10), group(7, 10)});
  EXPECT_EQ(h.groups, 2);
  EXPECT_EQ(h.runs, 20);
  EXPECT_EQ(h.shown, 10);
  EXPECT_NEAR(h.chi2, 3.2, 1e-12);
  EXPECT_EQ(h.dof, 1);
  EXPECT_NEAR(h.between_share, 0.16, 1e-12);
  EXPECT_NEAR(h.p_chi2, std::erfc(std::sqrt(1.6)), 1e-14);
  EXPECT_DOUBLE_EQ(h.min_expected, 5.0);
  EXPECT_TRUE(h.chi2_valid);
  EXPECT_EQ(h.shuffles, 20000);
  EXPECT_NEAR(h.p_permutation, 2.0 * (1 + 100 + 2025 + 14400) / 184756.0, 4 * 0.0027);
  // The same seed, the same p; the test is a pure function.
  EXPECT_EQ(homogeneity({group(3, 10), group(7, 10)}).p_permutation, h.p_permutation);

  // Split apart completely: all the variance between the groups; only 2 of C(20, 10) labellings
  // are as extreme, so nearly no shuffle reaches it, and p is never 0.
  const auto apart = homogeneity({group(0, 10), group(10, 10)});
  EXPECT_NEAR(apart.between_share, 1.0, 1e-12);
  EXPECT_NEAR(apart.chi2, 20.0, 1e-12);
  EXPECT_GE(apart.p_permutation, 1.0 / 20001);
  EXPECT_LT(apart.p_permutation, 1e-3);
}

// Unequal groups: the statistic equals Pearson's sum over the cells, written out here
// independently of the between-share form the code uses; an empty group is left out; a table
// where every run shows the event tells nothing.
TEST(Homogeneity, UnequalGroupsMatchPearsonsSum) {
  const std::vector<std::vector<bool>> g = {
      {true, true, false}, {}, {false, false, false, false, true}, {true, true, true, true, false, true, true}};
  const auto h = homogeneity(g);
  EXPECT_EQ(h.groups, 3);
  EXPECT_EQ(h.dof, 2);
  double N = 0, K = 0;
  for (const auto& v : g)
    for (bool b : v) N += 1, K += b;
  double pearson = 0, least = N;
  for (const auto& v : g) {
    if (v.empty()) continue;
    double k = 0;
    for (bool b : v) k += b;
    const double n = v.size(), e1 = n * K / N, e0 = n - e1;
    pearson += (k - e1) * (k - e1) / e1 + (n - k - e0) * (n - k - e0) / e0;
    least = std::min({least, e0, e1});
  }
  EXPECT_NEAR(h.chi2, pearson, 1e-12);
  EXPECT_NEAR(h.between_share, pearson / N, 1e-12);
  EXPECT_NEAR(h.p_chi2, std::exp(-0.5 * pearson), 1e-14);
  EXPECT_DOUBLE_EQ(h.min_expected, least);
  EXPECT_FALSE(h.chi2_valid);  // every expected count under 5
  EXPECT_GT(h.p_permutation, 0.0);
  EXPECT_LE(h.p_permutation, 1.0);

  const auto all = homogeneity({{true, true}, {true}});
  EXPECT_EQ(all.chi2, 0.0);
  EXPECT_EQ(all.p_chi2, 1.0);
  EXPECT_EQ(all.p_permutation, 1.0);
  EXPECT_EQ(all.between_share, 0.0);
  EXPECT_EQ(homogeneity({{true, false}}).groups, 1);  // one group: no test
}
