// Where a property first shows in a sweep run on several realisations (meshes, seeds): per
// realisation the lowest swept value (an impact speed, a load rate) at which it holds, and
// the middle of those. A chaotic run (fracture at an impact) can show a property at one
// speed and not at the next, so "first" is the lowest value at which it holds, not a value
// from which on it always does.
#pragma once
#include <limits>
#include <vector>

namespace dspdem::report {

struct SweepPoint {
  int realisation = 0;
  double value = 0;  ///< the swept parameter
  bool holds = false;
};

struct Onset {
  int realisation = 0;
  /// Lowest value at which the property holds; +infinity when it holds at none swept.
  double first = std::numeric_limits<double>::infinity();
};

/// One Onset per realisation that has points, in increasing realisation order. The points
/// may come in any order.
std::vector<Onset> first_onsets(const std::vector<SweepPoint>& points);

/// The two middle values of `v` in sorted order (equal for an odd count): the median is
/// between them. +infinity entries count as the largest. Both NaN for an empty v.
struct Middle {
  double low, high;
};
Middle middle(std::vector<double> v);

}  // namespace dspdem::report
