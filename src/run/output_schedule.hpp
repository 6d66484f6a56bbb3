// A run's output times (frames, series rows, checkpoints): next, next + interval, ...
#pragma once
#include <cmath>
#include <limits>

#include "core/types.hpp"

namespace dspdem {

/// The first time of the schedule `next`, `next + interval`, ... that lies beyond `t + tol`.
/// It adds the interval as a sum, whose rounding the output times have always had, but never
/// spins: an interval below the spacing of the doubles near `t` (1e-30 s at t = 1e-6 s) leaves
/// the sum where it is, and a step many intervals long would add it thousands of times. Both
/// jump to the first time past in one go; an interval below a step's length then means an
/// output at every step, which is what was asked.
inline Real next_output_time(Real next, Real t, Real interval, Real tol) {
  const Real past = t + tol;
  for (int k = 0; k < 64 && next <= past; ++k) next += interval;
  if (next > past) return next;
  next += std::floor((past - next) / interval) * interval;
  while (next <= past) {
    const Real moved = next + interval;
    next = moved > next ? moved : std::nextafter(past, std::numeric_limits<Real>::infinity());
  }
  return next;
}

}  // namespace dspdem
