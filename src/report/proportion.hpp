// A count of runs that show a property, read as a proportion with its uncertainty. The
// sphere's realisations (issue 18) give counts like "3 of 10"; with ten draws near p = 0.2
// the count alone spreads by about 1.3, so a report that gives "1 of 10" and one that gives
// "3 of 10" can be the same finding. The interval says so.
//
// Wilson's score interval (E. B. Wilson, J. Am. Stat. Assoc. 22:209-212, 1927), without
// continuity correction: the p whose score test does not reject k of n. Unlike the normal
// approximation p +- z sqrt(p (1 - p) / n) it stays inside [0, 1] and does not collapse to
// a point at k = 0 or k = n, which is where small realisation counts often sit; R. G.
// Newcombe (Stat. Med. 17:857-872, 1998) compares it with six other methods and recommends it.
#pragma once
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace dspdem::report {

struct ProportionInterval {
  double lo = 0, hi = 1;
};

/// The two-sided Wilson score interval for k successes in n trials at the normal quantile z
/// (1.96: 95 %). n = 0 gives [0, 1]: no draws, no information.
inline ProportionInterval wilson_interval(int k, int n, double z = 1.959963984540054) {
  if (n <= 0) return {};
  const double nn = n, p = std::clamp(k / nn, 0.0, 1.0), z2 = z * z;
  const double denom = 1.0 + z2 / nn;
  const double centre = (p + z2 / (2.0 * nn)) / denom;
  const double half = z * std::sqrt(p * (1.0 - p) / nn + z2 / (4.0 * nn * nn)) / denom;
  // At k = 0 the bounds' lower end is 0 exactly (centre and half are equal), at k = n the
  // upper is 1: set so, for rounding leaves a residue of 1e-18 there.
  return {k <= 0 ? 0.0 : std::max(0.0, centre - half), k >= n ? 1.0 : std::min(1.0, centre + half)};
}

/// "k of n (95 %: lo-hi)": a count with its Wilson interval, so that two reports' counts can be
/// read against each other.
inline std::string count_of(int k, int n) {
  const ProportionInterval i = wilson_interval(k, n);
  return fmt::format("{} of {} (95 %: {:.2f}-{:.2f})", k, n, i.lo, i.hi);
}

}  // namespace dspdem::report
