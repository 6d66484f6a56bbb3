#include "report/onsets.hpp"

#include <algorithm>
#include <cmath>
#include <map>

namespace dspdem::report {

std::vector<Onset> first_onsets(const std::vector<SweepPoint>& points) {
  std::map<int, double> first;  // ordered by realisation
  for (const SweepPoint& p : points) {
    double& f = first.try_emplace(p.realisation, std::numeric_limits<double>::infinity()).first->second;
    if (p.holds) f = std::min(f, p.value);
  }
  std::vector<Onset> out;
  out.reserve(first.size());
  for (const auto& [r, f] : first) out.push_back({r, f});
  return out;
}

Middle middle(std::vector<double> v) {
  if (v.empty()) return {std::nan(""), std::nan("")};
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return {v[(n - 1) / 2], v[n / 2]};
}

}  // namespace dspdem::report
