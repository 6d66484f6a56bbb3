// Ending a run once its load has passed its peak and fallen (a splitting or bending test
// is over when the specimen has broken; running on only crushes the pieces and costs the
// most, since contact between fragments dominates the step after the peak).
#pragma once
#include <cmath>

#include "core/types.hpp"

namespace dspdem {

/// Watches one signed series value: triggers once |value| has reached at least `min_peak`
/// and then dropped below `fraction` x its largest |value| so far. A pure state machine so
/// it is tested alone; the run loop feeds it every series row.
class PeakDropStop {
 public:
  PeakDropStop(Real fraction, Real min_peak) : fraction_(fraction), min_peak_(min_peak) {}

  /// Feeds one sample; returns true when the run should stop.
  bool update(Real value) {
    const Real a = std::abs(value);
    if (a > peak_) peak_ = a;
    return peak_ > 0 && peak_ >= min_peak_ && a < fraction_ * peak_;
  }
  Real peak() const { return peak_; }
  template <class Ar>
  void persist(Ar& ar) {
    ar(peak_);
  }

 private:
  Real fraction_, min_peak_;
  Real peak_ = 0;
};

}  // namespace dspdem
