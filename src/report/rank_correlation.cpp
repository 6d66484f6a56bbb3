#include "report/rank_correlation.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>

#include "core/error.hpp"
#include "report/shuffle.hpp"

namespace dspdem::report {

std::vector<double> midranks(const std::vector<double>& v) {
  for (std::size_t i = 0; i < v.size(); ++i)
    DSPDEM_CHECK(!std::isnan(v[i]), "midranks: value {} is NaN (a measure the run did not give)", i);
  std::vector<std::size_t> order(v.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return v[a] < v[b]; });
  std::vector<double> r(v.size());
  for (std::size_t i = 0; i < order.size();) {
    std::size_t j = i;
    while (j + 1 < order.size() && v[order[j + 1]] == v[order[i]]) ++j;
    const double mean = 0.5 * static_cast<double>(i + j) + 1.0;  // ranks i+1 .. j+1
    for (std::size_t k = i; k <= j; ++k) r[order[k]] = mean;
    i = j + 1;
  }
  return r;
}

namespace {

// sum (x_i - mean)(y_i - mean) over the ranks: with both rank sets fixed, rho is this over a
// constant, so the shuffles compare it alone.
double co_spread(const std::vector<double>& rx, const std::vector<double>& ry, double mean) {
  double s = 0;
  for (std::size_t i = 0; i < rx.size(); ++i) s += (rx[i] - mean) * (ry[i] - mean);
  return s;
}

double spread(const std::vector<double>& r, double mean) { return co_spread(r, r, mean); }

}  // namespace

RankCorrelation spearman(const std::vector<double>& x, const std::vector<double>& y, int shuffles, std::uint64_t seed) {
  DSPDEM_CHECK(x.size() == y.size(), "spearman: {} values against {} (they must be paired)", x.size(), y.size());
  DSPDEM_CHECK(shuffles >= 0, "spearman: {} shuffles (at least 0)", shuffles);
  RankCorrelation c;
  c.n = static_cast<int>(x.size());
  const std::vector<double> rx = midranks(x);
  std::vector<double> ry = midranks(y);
  if (c.n < 3) return c;
  const double mean = 0.5 * (c.n + 1);  // of any midranks of n values
  const double sx = spread(rx, mean), sy = spread(ry, mean);
  if (!(sx > 0) || !(sy > 0)) return c;
  c.defined = true;
  const double observed = co_spread(rx, ry, mean);
  c.rho = observed / std::sqrt(sx * sy);
  // Ties: the same pairing in another order sums to the same, up to its rounding.
  const double tie = 1e-9 * std::sqrt(sx * sy);
  std::mt19937_64 g(seed);
  int extreme = 0;
  for (int s = 0; s < shuffles; ++s) {
    shuffle_in_place(ry, g);
    extreme += std::abs(co_spread(rx, ry, mean)) >= std::abs(observed) - tie;
  }
  c.shuffles = shuffles, c.as_extreme = extreme;
  c.p_permutation = (1.0 + extreme) / (1.0 + shuffles);
  return c;
}

}  // namespace dspdem::report
