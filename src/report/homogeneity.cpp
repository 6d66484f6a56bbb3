#include "report/homogeneity.hpp"

#include <algorithm>
#include <cmath>
#include <random>

#include "core/error.hpp"
#include "report/shuffle.hpp"

namespace dspdem::report {

double chi_square_sf(double x, int dof) {
  DSPDEM_CHECK(dof >= 1, "chi_square_sf: {} degrees of freedom (at least 1)", dof);
  if (!(x > 0)) return 1.0;
  const double h = 0.5 * x;
  // Q(dof / 2, h) = [erfc(sqrt h) for odd dof] + sum of e^-h h^a / Gamma(a + 1) over
  // a = 0, 1, ..., dof / 2 - 1 (even) or a = 1/2, 3/2, ..., dof / 2 - 1 (odd); each term in logs
  // so that a large x with many degrees of freedom neither overflows h^a nor underflows e^-h
  // before the two meet.
  const bool odd = dof % 2 == 1;
  double q = odd ? std::erfc(std::sqrt(h)) : 0.0;
  for (double a = odd ? 0.5 : 0.0; a < 0.5 * dof - 0.25; a += 1.0)
    q += std::exp(-h + (a > 0 ? a * std::log(h) : 0.0) - std::lgamma(a + 1.0));
  return std::min(1.0, q);
}

namespace {

// sum k_i^2 / n_i: with every group's size and the total shown fixed, Pearson's statistic
// rises with it alone, so the shuffles compare it.
double spread(const std::vector<int>& sizes, const std::vector<char>& pooled) {
  double s = 0;
  std::size_t at = 0;
  for (int n : sizes) {
    int k = 0;
    for (int j = 0; j < n; ++j) k += pooled[at++];
    s += static_cast<double>(k) * k / n;
  }
  return s;
}

}  // namespace

Homogeneity homogeneity(const std::vector<std::vector<bool>>& groups, int shuffles, std::uint64_t seed) {
  Homogeneity h;
  std::vector<int> sizes;
  std::vector<char> pooled;
  for (const auto& g : groups) {
    if (g.empty()) continue;
    sizes.push_back(static_cast<int>(g.size()));
    for (bool b : g) pooled.push_back(b ? 1 : 0), h.shown += b;
  }
  h.groups = static_cast<int>(sizes.size());
  h.runs = static_cast<int>(pooled.size());
  h.dof = std::max(0, h.groups - 1);
  if (h.groups < 2) return h;
  const double N = h.runs, p = h.shown / N;
  // Expected counts n_i p and n_i (1 - p).
  int cells = 0, small = 0;
  h.min_expected = N;
  for (int n : sizes)
    for (double e : {n * p, n * (1 - p)}) {
      ++cells, small += e < 5;
      h.min_expected = std::min(h.min_expected, e);
    }
  h.chi2_valid = h.min_expected >= 1 && 5 * small <= cells;
  if (h.shown == 0 || h.shown == h.runs) {
    // Nothing to tell apart: every group alike.
    h.p_permutation = 1, h.shuffles = shuffles;
    return h;
  }
  const double observed = spread(sizes, pooled);
  h.between_share = (observed / N - p * p) / (p * (1 - p));
  h.chi2 = N * h.between_share;
  h.p_chi2 = chi_square_sf(h.chi2, h.dof);
  // Ties: the same table in another order gives the same sum, up to its rounding.
  const double tie = 1e-9 * observed;
  std::mt19937_64 g(seed);
  int extreme = 0;
  for (int s = 0; s < shuffles; ++s) {
    shuffle_in_place(pooled, g);
    extreme += spread(sizes, pooled) >= observed - tie;
  }
  h.shuffles = shuffles, h.as_extreme = extreme;
  h.p_permutation = (1.0 + extreme) / (1.0 + shuffles);
  return h;
}

}  // namespace dspdem::report
