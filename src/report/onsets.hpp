// Where a property first shows in a sweep run on several realisations (meshes, seeds): per
// realisation the lowest swept value (an impact speed, a load rate) at which it holds, and
// the middle of those. A chaotic run (fracture at an impact) can show a property at one
// speed and not at the next, so "first" is the lowest value at which it holds, not a value
// from which on it always does.
#pragma once
#include <cmath>
#include <limits>
#include <vector>

namespace dspdem::report {

struct SweepPoint {
  int realisation = 0;
  double value = 0;    ///< the swept parameter
  bool holds = false;  ///< the property, when known
  bool known = true;   ///< false: the run failed, and whether it holds there is not known
};

struct Onset {
  int realisation = 0;
  /// Lowest value at which the property holds; +infinity when it holds at none swept.
  double first = std::numeric_limits<double>::infinity();
  /// Largest value of a run that did not fail (NaN: every run failed).
  double highest_known = std::nan("");
  /// A failed run lies below `first` (anywhere, when it never holds): the property may have
  /// shown earlier there, so `first` is only an upper bound.
  bool failed_below = false;
};

/// One Onset per realisation that has points, in increasing realisation order. The points
/// may come in any order; values must not be NaN.
std::vector<Onset> first_onsets(const std::vector<SweepPoint>& points);

/// The two middle values of a set, in sorted order (equal for an odd count): the median lies
/// between them.
struct Middle {
  double low = std::nan(""), high = std::nan("");
};

/// The middle of `v` (+infinity entries count as the largest; no NaN entries). Both NaN for
/// an empty v.
Middle middle(std::vector<double> v);

}  // namespace dspdem::report
