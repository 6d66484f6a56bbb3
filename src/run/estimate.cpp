#include "run/estimate.hpp"

#include <fmt/format.h>
#include <omp.h>

#include <cmath>

#include "core/log.hpp"
#include "core/timer.hpp"
#include "time/integrator.hpp"

namespace dspdem {

std::string format_duration(double s) {
  if (!std::isfinite(s)) return "?";
  if (s < 120) return fmt::format("{:.0f}s", s);
  if (s < 7200) return fmt::format("{:.0f}m{:02.0f}s", std::floor(s / 60), std::fmod(s, 60));
  return fmt::format("{:.0f}h{:02.0f}m", std::floor(s / 3600), std::fmod(s / 60, 60));
}

void estimate_run(const CaseConfig& c, Model& model, Real dt, long n_steps, const std::string& bound, double seconds) {
  Integrator it(model, dt);
  Timer wall;
  long k = 0;
  while (k < n_steps && (k == 0 || wall.seconds() < seconds)) {
    it.step();
    ++k;
  }
  const double spent = wall.seconds(), per_step = spent / static_cast<double>(k);
  const long frames = c.frame_interval > 0 ? static_cast<long>(std::floor(c.t_end / c.frame_interval + 1e-9)) + 1 : 1;
  log::info("  estimate (nothing written): {}{} steps of {:.4g} s to t = {:.6g} s, {} frames", bound, n_steps, dt,
            c.t_end, frames);
  log::info(
      "  the first {} steps took {:.2f} s ({:.3g} element-steps/s, {} threads): at that rate the run's steps take {}{}",
      k, spent, static_cast<double>(k) * static_cast<double>(model.fem.n_elements) / spent, omp_get_max_threads(),
      format_duration(per_step * static_cast<double>(n_steps)),
      k < n_steps ? ", a lower bound: steps grow dearer as joints break and pieces touch, many times over where "
                    "they pile up (README, run --estimate), and frames take their own time"
                  : "");
}

}  // namespace dspdem
