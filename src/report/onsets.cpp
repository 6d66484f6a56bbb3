#include "report/onsets.hpp"

#include <algorithm>
#include <cmath>
#include <map>

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
  MedianInterval out;
  if (n == 0 || !(level > 0 && level < 1)) return out;
  // Bin(n, 1/2)'s cumulative tail, term by term from P(B = 0) = 2^-n (n is a count of runs,
  // at most a few hundred: 2^-n stays a normal double up to n = 1022).
  const double alpha = (1.0 - level) / 2.0;
  double term = std::ldexp(1.0, -n), tail = term;
  int r = 0;
  double tail_r = 0;  // P(B <= r - 1) of the rank taken
  for (int k = 0; k < (n + 1) / 2 && tail <= alpha; ++k) {
    r = k + 1, tail_r = tail;
    term *= static_cast<double>(n - k) / (k + 1);
    tail += term;
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
