// Whether several groups of yes/no runs share one probability: the meshes of the sphere
// impact, each run several times with an imperceptible change (`report --draws`), show a
// few large pieces in 9 of 10 runs on one mesh and in none of 10 on another (issue 18,
// session 91). Chance on each mesh alone would spread such counts by about 1.5; the test
// says whether the meshes differ by more, and the share of the outcome's variance between
// them says by how much.
//
// The chi-square test of homogeneity of a k x 2 table (K. Pearson 1900; any text, e.g.
// A. Agresti, Categorical Data Analysis, 3rd ed., 2013, section 3.2), with the permutation
// test of the same statistic beside it: with ten runs a group the expected counts often fall
// below the five the chi-square's approximation wants, and the permutation test needs no
// such approximation. Its p counts the observed labelling among the shuffles (B. Phipson and
// G. K. Smyth, Stat. Appl. Genet. Mol. Biol. 9:39, 2010), so it is never zero.
#pragma once
#include <cstdint>
#include <vector>

namespace dspdem::report {

/// P(X >= x) for X chi-square distributed with `dof` >= 1 degrees of freedom, in closed form
/// (the regularised upper incomplete gamma Q(dof / 2, x / 2) for integer dof: a finite sum of
/// Poisson terms for even dof, with erfc for odd).
double chi_square_sf(double x, int dof);

/// The test over groups of outcomes (true: the run shows the event). Groups may differ in size;
/// an empty group is left out.
struct Homogeneity {
  int groups = 0;           ///< non-empty groups
  int runs = 0, shown = 0;  ///< all runs, and those that show the event
  double chi2 = 0;          ///< Pearson's statistic (0 when every run or none shows it)
  int dof = 0;              ///< groups - 1
  double p_chi2 = 1;        ///< chi_square_sf(chi2, dof)
  /// The least expected count of a cell, and whether the chi-square's approximation holds by
  /// Cochran's rule (W. G. Cochran, Biometrics 10:417-451, 1954): every expected count at least
  /// 1 and at most a fifth of them below 5.
  double min_expected = 0;
  bool chi2_valid = false;
  double p_permutation = 1;  ///< (1 + as_extreme) / (1 + shuffles)
  int shuffles = 0;
  int as_extreme = 0;  ///< the shuffles whose statistic reached the runs'
  /// Of the variance of the outcome over all runs, p (1 - p), the part between the groups'
  /// shares: sum n_i (p_i - p)^2 / N over p (1 - p); the rest, the mean of p_i (1 - p_i), is
  /// chance within a group. chi2 = runs * between_share. 0 when every run or none shows it.
  double between_share = 0;
};

/// The test of `groups`, the permutation test with `shuffles` relabellings drawn from a
/// generator seeded with `seed` (the same p on every machine and thread count).
Homogeneity homogeneity(const std::vector<std::vector<bool>>& groups, int shuffles = 20000,
                        std::uint64_t seed = 20261205);

}  // namespace dspdem::report
