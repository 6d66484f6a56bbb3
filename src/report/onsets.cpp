#include "report/onsets.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include "core/error.hpp"

namespace dspdem::report {

std::vector<Onset> first_onsets(const std::vector<SweepPoint>& points) {
  std::map<int, Onset> by;  // ordered by realisation
  for (const SweepPoint& p : points) {
    Onset& o = by.try_emplace(p.realisation, Onset{p.realisation}).first->second;
    if (!p.known) continue;
    if (p.holds) o.first = std::min(o.first, p.value);
    if (!(o.highest_known >= p.value)) o.highest_known = p.value;  // NaN at first: taken
  }
  for (const SweepPoint& p : points)
    if (!p.known && p.value < by[p.realisation].first) by[p.realisation].failed_below = true;
  std::vector<Onset> out;
  out.reserve(by.size());
  for (const auto& [r, o] : by) out.push_back(o);
  return out;
}

Middle middle(std::vector<double> v) {
  if (v.empty()) return {};
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return {v[(n - 1) / 2], v[n / 2]};
}

MedianInterval median_interval(std::vector<double> v, double level) {
  const int n = static_cast<int>(v.size());
  for (std::size_t i = 0; i < v.size(); ++i)
    DSPDEM_CHECK(!std::isnan(v[i]), "internal: value {} of {} for a median's interval is NaN", i, v.size());
  MedianInterval out;
  if (n == 0 || !(level > 0 && level < 1)) return out;
  // Bin(n, 1/2)'s cumulative tail term by term, each P(B = k) from logarithms: 2^-n itself
  // underflows from n = 1075 on.
  const double alpha = (1.0 - level) / 2.0, log_half_n = n * std::log(0.5), log_n1 = std::lgamma(n + 1.0);
  auto pmf = [&](int k) { return std::exp(log_n1 - std::lgamma(k + 1.0) - std::lgamma(n - k + 1.0) + log_half_n); };
  double tail = pmf(0), tail_r = 0;  // tail: P(B <= k); tail_r: P(B <= r - 1) of the rank taken
  int r = 0;
  for (int k = 0; k < (n + 1) / 2 && tail <= alpha; ++k) {
    r = k + 1, tail_r = tail;
    tail += pmf(k + 1);
  }
  if (r == 0) return out;
  std::sort(v.begin(), v.end());
  out.rank = r;
  out.lo = v[r - 1];
  out.hi = v[n - r];
  out.coverage = 1.0 - 2.0 * tail_r;
  return out;
}

}  // namespace dspdem::report
