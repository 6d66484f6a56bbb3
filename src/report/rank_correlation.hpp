// Whether one measure of the runs goes with another, with no assumption on how either is
// distributed: Spearman's rank correlation (C. Spearman, Am. J. Psychol. 15:72-101, 1904),
// the Pearson correlation of the midranks (ties share the mean of their ranks), and its
// two-sided permutation p (the observed pairing counted among the shuffles: B. Phipson and
// G. K. Smyth, Stat. Appl. Genet. Mol. Biol. 9:39, 2010, so never zero). Why a permutation
// test: a scene's runs are often tens, values censored at one time (an event that never came)
// are tied at the end, and the t approximation to rho's distribution wants neither.
#pragma once
#include <cstdint>
#include <vector>

namespace dspdem::report {

/// The ranks 1..n of `v`, ties given the mean of the ranks they share; +-infinity is ranked
/// as a value (a time that never came is later than every other). NaN: Error.
std::vector<double> midranks(const std::vector<double>& v);

/// Pairings drawn by default: the p's standard error is then under 0.0016 at p = 0.05.
inline constexpr int kSpearmanShuffles = 20000;

struct RankCorrelation {
  int n = 0;
  /// False when either measure takes one value on every run (or n < 3): no rho, p = 1.
  bool defined = false;
  double rho = 0;
  double p_permutation = 1;  ///< two-sided: (1 + as_extreme) / (1 + shuffles)
  int shuffles = 0, as_extreme = 0;
};

/// Spearman's rho of paired `x` and `y` (the same length; Error otherwise) and its permutation
/// p with `shuffles` pairings drawn from a generator seeded with `seed`: the same p on every
/// machine and thread count. shuffles < 0: Error.
RankCorrelation spearman(const std::vector<double>& x, const std::vector<double>& y, int shuffles = kSpearmanShuffles,
                         std::uint64_t seed = 20261206);

}  // namespace dspdem::report
