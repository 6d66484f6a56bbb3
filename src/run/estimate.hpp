// `dspdem run CASE --estimate`: what a run will cost before it is started (a batch queue's
// wall-time request): the case is set up as for the run (meshed, the model built, its step
// found), its first steps are timed in memory for a few seconds, and nothing is written but
// the mesh cache.
#pragma once
#include <functional>
#include <string>

#include "core/types.hpp"
#include "io/case_config.hpp"
#include "time/integrator.hpp"
#include "time/model.hpp"

namespace dspdem {

/// Wall time spent stepping for the estimate [s] (or less, when the run is shorter).
inline constexpr double kEstimateSeconds = 3.0;

/// The frames a run of `n_steps` steps of `dt` writes: at t = 0, at each [output]
/// frame_interval passed, and at its last step, as the run schedules them.
long frames_of_run(const CaseConfig& c, Real dt, long n_steps);

/// Steps `model` from its start with the step `dt` for up to `seconds` of wall time or `n_steps`
/// steps, and prints to stdout (also with -q: it is the command's answer) the run's steps, frames
/// and the wall time its steps take at that rate. `stops`: the run ends on a load drop, so it
/// takes at most n_steps; `falls`: its step falls as joints open (extrinsic insertion), so it
/// takes at least n_steps. `check` sees the integrator before the first step (what the run
/// checks only then: its stop_series column); `after_step` does after each step what the run
/// does then besides its frames (its extrinsic checks and series rows), and is timed with it.
void estimate_run(const CaseConfig& c, Model& model, Real dt, long n_steps, bool stops, bool falls,
                  const std::function<void(const Integrator&)>& check,
                  const std::function<void(Integrator&)>& after_step, double seconds = kEstimateSeconds);

/// "42s", "3m05s", "2h10m" ("?" when not finite).
std::string format_duration(double seconds);

}  // namespace dspdem
