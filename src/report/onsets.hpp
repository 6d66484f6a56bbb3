// Where a property first shows in a sweep run on several realisations (meshes, seeds): per
// realisation the lowest swept value (an impact speed, a load rate) at which it holds, and
// the middle of those. A chaotic run (fracture at an impact) can show a property at one
// speed and not at the next, so "first" is the lowest value at which it holds, not a value
// from which on it always does.
#pragma once
#include <fmt/format.h>

#include <cmath>
#include <limits>
#include <string>
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

/// A distribution-free interval for the median of the population the values were drawn from:
/// the order statistics x(r) and x(n - r + 1) with r the largest rank whose binomial tail
/// P(B <= r - 1), B ~ Bin(n, 1/2), is at most (1 - level) / 2, so that the interval covers the
/// median with probability at least `coverage` >= level whatever the distribution (W. R.
/// Thompson, Ann. Math. Stat. 7:122-128, 1936; the ranks as tabled by M. J. Campbell and M. J.
/// Gardner, BMJ 296:1454-1456, 1988); exactly `coverage` for continuous values, more with ties
/// (swept speeds, frame times). Why order statistics: the values (times, speeds) are censored,
/// a mesh that never came apart counted as +infinity, and ranks need nothing else of them as
/// long as every value is censored at the same point (the runs read to one time): a value
/// censored early could lie below the median and lift x(r). An upper end of +infinity says
/// the median may lie beyond what was run.
struct MedianInterval {
  double lo = std::nan(""), hi = std::nan("");
  double coverage = std::nan("");  ///< 1 - 2 P(B <= r - 1): what the ranks guarantee
  int rank = 0;                    ///< r (1-based); 0: too few values for `level` (n <= 5 at 95 %)
};

/// As `middle`: +infinity entries count as the largest; a NaN entry is an error (it has no
/// rank); `level` in (0, 1), else rank 0.
MedianInterval median_interval(std::vector<double> v, double level = 0.95);

/// "lo to hi (c %)", each end written by `write` (which says what +infinity means), c the
/// coverage the ranks guarantee; one end when both are the same; `too_few` at rank 0.
template <class Write>
std::string median_interval_text(const MedianInterval& i, Write write, const std::string& too_few) {
  if (i.rank == 0) return too_few;
  const std::string lo = write(i.lo), hi = write(i.hi);
  return fmt::format("{} ({:.1f} %)", lo == hi ? lo : lo + " to " + hi, 100 * i.coverage);
}

}  // namespace dspdem::report
