// A permutation test's p when none of its draws reached the observed statistic: reported as an
// upper bound, not as (1 + 0) / (1 + draws), because with no draw reaching it the 95 % upper
// bound on the chance of one doing so is about 3 / draws (the rule of three).
#pragma once

namespace dspdem::report {

inline double p_bound_when_none_reached(int draws) { return 3.0 / draws; }

}  // namespace dspdem::report
