// report/breakage_probability: Vogel & Peukert's breakage probability fitted by maximum
// likelihood, its profile-likelihood interval, and the data that cannot be fitted.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "core/error.hpp"
#include "report/breakage_probability.hpp"

using namespace dspdem::report;

namespace {

// The truth the tests draw from: W_min = 20 J/kg (6.3 m/s) and a rate that puts P = 1/2 at
// 40 J/kg (8.9 m/s), about where the sphere's split lies.
constexpr double kWmin = 20.0, kW50 = 40.0;
const double kRate = std::log(2.0) / (kW50 - kWmin);

double truth(double w) { return w <= kWmin ? 0.0 : 1.0 - std::exp(-kRate * (w - kWmin)); }

// Speeds 3-14 m/s, 1 m/s apart, as energies per mass.
std::vector<double> levels() {
  std::vector<double> w;
  for (int v = 3; v <= 14; ++v) w.push_back(0.5 * v * v);
  return w;
}

// At each level n runs, of which round(P n) broke: the proportions of the truth to within
// 1 / (2 n).
std::vector<BreakageTrial> exact(int n) {
  std::vector<BreakageTrial> t;
  for (double w : levels()) {
    const int k = static_cast<int>(std::lround(truth(w) * n));
    for (int i = 0; i < n; ++i) t.push_back({w, i < k});
  }
  return t;
}

}  // namespace

// With the truth's proportions at 1000 runs a level the fit must give the truth back. The
// counts' rounding moves each proportion by at most 1 / 2000 = 5e-4; the curve's slope dP/dW
// is 0.035 per J/kg at W_min and 0.017 at W50, so at W50 that moves the energy by at most
// 0.03 J/kg. 0.05 J/kg on W_min and W50 and 0.5 % on the rate allow for it and little more
// (the fit is off by 0.011 J/kg and 3e-5 of the rate).
TEST(BreakageProbability, ExactProportionsGiveTheTruthBack) {
  const BreakageFit f = fit_breakage(exact(1000));
  ASSERT_EQ(f.outcome, BreakageFit::Outcome::fitted);
  EXPECT_NEAR(f.w_min, kWmin, 0.05);
  EXPECT_NEAR(f.rate, kRate, 5e-3 * kRate);
  EXPECT_NEAR(f.energy_at(0.5), kW50, 0.05);
  // The interval holds the truth and is narrow at 12000 runs: the standard error of W50 is
  // about sqrt(P (1 - P) / N_near) / (dP/dW), some 0.3 J/kg here.
  EXPECT_LT(f.w50_lo, kW50);
  EXPECT_GT(f.w50_hi, kW50);
  EXPECT_LT(f.w50_hi - f.w50_lo, 2.0);
  // The same proportions at 20 runs a level: a wider interval (the sphere's twenty meshes).
  const BreakageFit g = fit_breakage(exact(20));
  ASSERT_EQ(g.outcome, BreakageFit::Outcome::fitted);
  EXPECT_GT(g.w50_hi - g.w50_lo, 5 * (f.w50_hi - f.w50_lo));
}

// Twenty draws at each of the 12 levels, as the sphere's twenty meshes.
std::vector<BreakageTrial> drawn(std::mt19937_64& rng) {
  std::vector<BreakageTrial> t;
  for (double w : levels())
    for (int i = 0; i < 20; ++i) t.push_back({w, (rng() >> 11) * 0x1.0p-53 < truth(w)});
  return t;
}

// The most of `f` over a 2000-point grid of W_min in [0, w_max): a search of its own, to check
// the fit's against.
template <class F>
double grid_max(const F& f, double w_max) {
  double best = -INFINITY;
  for (int j = 0; j < 2000; ++j) best = std::max(best, f(w_max * j / 2000));
  return best;
}

// The fit is the maximum: no point of a fine grid over (W_min, rate) does better, moving
// either a little does worse, and the curve's probability and energy are each other's inverse.
TEST(BreakageProbability, TheFitIsTheLikelihoodsMaximum) {
  std::mt19937_64 rng(7);
  const std::vector<BreakageTrial> t = drawn(rng);
  const BreakageFit f = fit_breakage(t);
  ASSERT_EQ(f.outcome, BreakageFit::Outcome::fitted);
  for (int i = 0; i < 400; ++i)
    for (int j = 0; j < 400; ++j) {
      const double w_min = f.above * i / 400, rate = 1e-3 * std::pow(1e3, j / 399.0);  // 1e-3 to 1 kg/J
      EXPECT_LE(breakage_log_likelihood(t, w_min, rate), f.log_likelihood + 1e-9) << w_min << " " << rate;
    }
  for (double d : {-1e-2, 1e-2}) {
    EXPECT_LT(breakage_log_likelihood(t, f.w_min + d * f.above, f.rate), f.log_likelihood);
    EXPECT_LT(breakage_log_likelihood(t, f.w_min, f.rate * (1 + d)), f.log_likelihood);
  }
  for (double p : {0.1, 0.5, 0.9}) EXPECT_NEAR(f.probability(f.energy_at(p)), p, 1e-12);
  EXPECT_EQ(f.probability(f.w_min), 0.0);
  EXPECT_LE(f.w50_lo, f.energy_at(0.5));
  EXPECT_GE(f.w50_hi, f.energy_at(0.5));
}

// The interval's ends lie where the profile likelihood of W50 has fallen by half the
// chi-square quantile (deviance 3.841): checked with a profile of the test's own, over a grid
// of W_min with the rate that puts P = 1/2 at the end. A cut-off of 1.92 (half of it) or
// 5.99 (two degrees of freedom), or a deviance without its factor 2, puts the deviance at the
// ends at 1.92, 5.99 or 7.68 instead. The test's grid finds a profile a little below the
// true one, so a deviance a little above: 3.8421 and 3.8415 here, so 0.01 allows for it.
TEST(BreakageProbability, TheIntervalsEndsLieAtADevianceOf3_84) {
  std::mt19937_64 rng(11);
  const std::vector<BreakageTrial> t = drawn(rng);
  const BreakageFit f = fit_breakage(t);
  ASSERT_EQ(f.outcome, BreakageFit::Outcome::fitted);
  ASSERT_TRUE(std::isfinite(f.w50_hi));
  ASSERT_GT(f.w50_lo, 0.0);
  for (double w50 : {f.w50_lo, f.w50_hi}) {
    const double profile =
        grid_max([&](double w_min) { return breakage_log_likelihood(t, w_min, std::log(2.0) / (w50 - w_min)); },
                 std::min(w50, f.above));
    EXPECT_NEAR(2 * (f.log_likelihood - profile), 3.841, 0.01) << w50;
  }
}

// Over 200 experiments drawn from the truth the interval must hold the true W50 in about 190.
// The count is binomial (n 200, p 0.95, standard deviation 3.1): below 182 comes once in 170
// seeds for a true 95 % interval, above 198 once in 2500; one seed, fixed. The 95 % is
// nominal (Wilks's theorem, asymptotic), and this test says the interval is about right: it
// catches gross errors, not a cut-off for 90 % or 99 % (the ends' test above does that).
TEST(BreakageProbability, TheIntervalHoldsTheTruthNineteenTimesInTwenty) {
  std::mt19937_64 rng(20031);
  int held = 0, fitted = 0;
  for (int e = 0; e < 200; ++e) {
    const std::vector<BreakageTrial> t = drawn(rng);
    const BreakageFit f = fit_breakage(t);
    if (f.outcome != BreakageFit::Outcome::fitted) continue;
    ++fitted;
    held += f.w50_lo <= kW50 && kW50 <= f.w50_hi;
  }
  EXPECT_EQ(fitted, 200);
  EXPECT_GE(held, 182);
  EXPECT_LE(held, 198);
}

// What cannot be fitted says what it can: nothing broke, all broke, or a clean threshold.
TEST(BreakageProbability, DataWithoutADrawAreNamedNotFitted) {
  const BreakageFit none = fit_breakage({{10, false}, {30, false}});
  EXPECT_EQ(none.outcome, BreakageFit::Outcome::none_broke);
  EXPECT_EQ(none.below, 30);
  EXPECT_TRUE(std::isnan(none.above));
  const BreakageFit all = fit_breakage({{10, true}, {30, true}});
  EXPECT_EQ(all.outcome, BreakageFit::Outcome::all_broke);
  EXPECT_EQ(all.above, 10);
  const BreakageFit sep = fit_breakage({{10, false}, {20, false}, {30, true}, {40, true}});
  EXPECT_EQ(sep.outcome, BreakageFit::Outcome::separated);
  EXPECT_EQ(sep.below, 20);
  EXPECT_EQ(sep.above, 30);
  EXPECT_THROW(sep.probability(25), dspdem::Error);
  // Broken and held mixed at one energy only: P is fixed there and nothing else.
  const BreakageFit one = fit_breakage({{10, false}, {20, false}, {20, true}, {30, true}});
  EXPECT_EQ(one.outcome, BreakageFit::Outcome::too_few_mixed);
  EXPECT_EQ(one.mixed_energy, 20);
  std::vector<BreakageTrial> sweep;  // 0, 0, 4 and 10 of 10 at 2.5, 5, 7.5 and 10 m/s
  for (double v : {2.5, 5.0, 7.5, 10.0})
    for (int i = 0; i < 10; ++i) sweep.push_back({0.5 * v * v, v == 10.0 || (v == 7.5 && i < 4)});
  EXPECT_EQ(fit_breakage(sweep).outcome, BreakageFit::Outcome::too_few_mixed);
  // A run held above one that broke, each energy all one way: they cross with no draw.
  const BreakageFit cross = fit_breakage({{10, true}, {20, false}});
  EXPECT_EQ(cross.outcome, BreakageFit::Outcome::too_few_mixed);
  EXPECT_TRUE(std::isnan(cross.mixed_energy));
  // Mixed at two energies: fitted.
  sweep.push_back({50, false});
  EXPECT_EQ(fit_breakage(sweep).outcome, BreakageFit::Outcome::fitted);
}

TEST(BreakageProbability, BadEnergiesAreRefused) {
  EXPECT_THROW(fit_breakage({}), dspdem::Error);
  EXPECT_THROW(fit_breakage({{-1, true}, {5, false}}), dspdem::Error);
  EXPECT_THROW(fit_breakage({{NAN, true}, {5, false}}), dspdem::Error);
  EXPECT_THROW(fit_breakage({{INFINITY, true}, {5, false}}), dspdem::Error);
}

// The bootstrap over groups. With every run its own group (independent draws) it must agree
// with the profile interval; with each group's runs tied (a group breaks at every energy
// above a threshold of its own, drawn from the truth: a mesh hard at one speed is hard at
// all), the runs are worth fewer draws than they count and it must be wider. The data drawn
// with seed 1 and the bootstrap's own default seed give
// widths 1.01 and 1.65 times the profile's with 1000 resamples and 0.94 and 1.86 with the 200
// here (over seeds 1-3 the tied data give 1.65-2.51 with 1000): 0.75-1.33 and above 1.3.
TEST(BreakageProbability, TheBootstrapOverGroupsSeesTiedRuns) {
  std::mt19937_64 rng(1);
  std::vector<BreakageTrial> independent, tied;
  for (int g = 0; g < 20; ++g) {
    const double threshold = kWmin - std::log1p(-((rng() >> 11) * 0x1.0p-53)) / kRate;
    for (double w : levels()) tied.push_back({w, w >= threshold, g});
  }
  int run = 0;
  for (double w : levels())
    for (int i = 0; i < 20; ++i) independent.push_back({w, (rng() >> 11) * 0x1.0p-53 < truth(w), run++});
  auto width_ratio = [](const std::vector<BreakageTrial>& t) {
    const BreakageFit f = fit_breakage(t);
    const BreakageBootstrap b = bootstrap_w50(t, 200);
    EXPECT_EQ(f.outcome, BreakageFit::Outcome::fitted);
    EXPECT_EQ(b.resamples, 200);
    EXPECT_LT(b.not_fitted, 10);
    return (b.w50_hi - b.w50_lo) / (f.w50_hi - f.w50_lo);
  };
  const double r_independent = width_ratio(independent), r_tied = width_ratio(tied);
  EXPECT_GT(r_independent, 0.75);
  EXPECT_LT(r_independent, 1.33);
  EXPECT_GT(r_tied, 1.3);
  // The same seed gives the same draws; one group gives no interval.
  const BreakageBootstrap a = bootstrap_w50(tied, 50, 9), b = bootstrap_w50(tied, 50, 9);
  EXPECT_EQ(a.w50_lo, b.w50_lo);
  EXPECT_EQ(a.w50_hi, b.w50_hi);
  std::vector<BreakageTrial> one = tied;
  for (auto& t : one) t.group = 0;
  const BreakageBootstrap c = bootstrap_w50(one, 50);
  EXPECT_EQ(c.groups, 1);
  EXPECT_TRUE(std::isnan(c.w50_lo));
}

// A resample whose W50 the data do not place is left out and counted, and past 2.5 % of them
// there is no interval: three meshes, one never breaking and two breaking above thresholds of
// their own; a resample of one breaking mesh three times is a clean threshold, 2 in 27 of them.
TEST(BreakageProbability, TheBootstrapGivesNoIntervalWhenTooManyResamplesCannotBeFitted) {
  std::vector<BreakageTrial> t;
  for (double w : levels()) {
    t.push_back({w, false, 0});
    t.push_back({w, w >= 30, 1});
    t.push_back({w, w >= 50, 2});
  }
  const BreakageBootstrap b = bootstrap_w50(t, 400);
  EXPECT_EQ(b.groups, 3);
  EXPECT_GT(b.not_fitted, 10);  // 400 x 2 / 27 = 30 expected
  EXPECT_LT(b.not_fitted, 60);
  EXPECT_TRUE(std::isnan(b.w50_lo));
  // The spread: those have no curve, and neither have the resamples of the never-breaking
  // mesh alone (1 in 27), which W50 keeps as above every run.
  EXPECT_GT(b.spread_left_out, b.not_fitted);
  EXPECT_TRUE(std::isnan(b.spread_lo));
}

// The spread E(0.9) / E(0.1) over resampled groups: on independent draws from the truth (240
// runs, every run its own group) its interval holds the truth's spread and the full data's
// fitted one, and it is the same for the same seed. The truth's is (W_min + ln 10 / rate) /
// (W_min + ln(10/9) / rate) = 3.75 here. With seed 1 and 400 resamples the interval is
// 2.51-4.08 about a fitted 3.18 (measured; a 95 % interval, so another seed's data may miss
// the truth once in twenty).
TEST(BreakageProbability, TheBootstrapsSpreadHoldsTheTruthsOnIndependentDraws) {
  std::mt19937_64 rng(1);
  std::vector<BreakageTrial> t;
  int run = 0;
  for (double w : levels())
    for (int i = 0; i < 20; ++i) t.push_back({w, (rng() >> 11) * 0x1.0p-53 < truth(w), run++});
  const BreakageFit f = fit_breakage(t, false);
  ASSERT_EQ(f.outcome, BreakageFit::Outcome::fitted);
  const BreakageBootstrap b = bootstrap_w50(t, 400);
  EXPECT_EQ(b.spread_left_out, 0);
  const double true_spread = (kWmin + std::log(10.0) / kRate) / (kWmin + std::log(10.0 / 9.0) / kRate);
  const double fitted = f.energy_at(0.9) / f.energy_at(0.1);
  EXPECT_LT(b.spread_lo, true_spread);
  EXPECT_GT(b.spread_hi, true_spread);
  EXPECT_LE(b.spread_lo, fitted);
  EXPECT_GE(b.spread_hi, fitted);
  const BreakageBootstrap again = bootstrap_w50(t, 400);
  EXPECT_EQ(again.spread_lo, b.spread_lo);
  EXPECT_EQ(again.spread_hi, b.spread_hi);
}
