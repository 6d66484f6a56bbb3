#include "run/estimate.hpp"

#include <fmt/format.h>
#include <omp.h>

#include <cmath>
#include <cstdio>

#include "core/timer.hpp"
#include "run/output_schedule.hpp"

namespace dspdem {

std::string format_duration(double s) {
  if (!std::isfinite(s)) return "?";
  if (s < 120) return fmt::format("{:.0f}s", s);
  if (s < 7200) return fmt::format("{:.0f}m{:02.0f}s", std::floor(s / 60), std::fmod(s, 60));
  return fmt::format("{:.0f}h{:02.0f}m", std::floor(s / 3600), std::fmod(s / 60, 60));
}

long frames_of_run(const CaseConfig& c, Real dt, long n_steps) {
  // The run's own schedule (run/run_case.cpp), its time summed step by step as the
  // integrator sums it: the same rounding at an interval's end.
  const Real tol = 1e-12 * c.t_end;
  long frames = 1;
  Real t = 0, next = c.frame_interval;
  for (long s = 0; s < n_steps; ++s) {
    t += dt;
    if (t >= next - tol || s + 1 == n_steps) {
      ++frames;
      next = next_output_time(next, t, c.frame_interval, tol);
    }
  }
  return frames;
}

void estimate_run(const CaseConfig& c, Model& model, Real dt, long n_steps, bool stops, bool falls,
                  const std::function<void(const Integrator&)>& check,
                  const std::function<void(Integrator&)>& after_step, double seconds) {
  Integrator it(model, dt);
  check(it);
  Timer wall;
  long k = 0;
  while (k < n_steps && (k == 0 || wall.seconds() < seconds)) {
    it.step();
    after_step(it);
    ++k;
  }
  const double spent = wall.seconds(), per_step = k > 0 ? spent / static_cast<double>(k) : 0;
  const char* bound = falls && stops ? "about " : falls ? "at least " : stops ? "at most " : "";
  fmt::print("estimate (nothing written): {}{} steps of {:.4g} s to t = {:.6g} s, {}{} frames\n", bound, n_steps, dt,
             static_cast<double>(n_steps) * dt, stops ? "at most " : "", frames_of_run(c, dt, n_steps));
  fmt::print(
      "the first {} steps took {:.2f} s ({:.3g} element-steps/s, {} threads): at that rate the {} steps take {}{}\n", k,
      spent, static_cast<double>(k) * static_cast<double>(model.fem.n_elements) / spent, omp_get_max_threads(), n_steps,
      format_duration(per_step * static_cast<double>(n_steps)),
      k == n_steps ? ""
      : stops      ? "; steps grow dearer as joints break and pieces touch, many times over where they pile up "
                     "(README, run --estimate), and the run may stop well before them"
                   : ", a lower bound: steps grow dearer as joints break and pieces touch, many times over where "
                     "they pile up (README, run --estimate), and frames take their own time");
  std::fflush(stdout);
}

}  // namespace dspdem
