#include "report/onsets.hpp"

#include <algorithm>
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

}  // namespace dspdem::report
