// A whole run of a case: mesh, model, stable step, time loop, frames, series, summary.
#pragma once
#include <string>
#include <vector>

#include "io/case_config.hpp"

namespace dspdem {

struct RunOptions {
  std::string out_dir;
  bool progress = false;  ///< progress line on stderr
  /// Simulated time between checkpoints (DIR/checkpoint.bin while the run goes on); 0: only
  /// when a signal stops the run.
  double checkpoint_every = 0;
  /// Continue from this checkpoint (run/checkpoint.hpp) instead of t = 0; the case must be
  /// the one it was written for. Its folder holds the outputs written up to it.
  std::string restart_file;
  std::vector<std::string> sets;  ///< the --set overrides, recorded in checkpoints
  /// Tests: behave as if SIGTERM arrived during this step (-1: never).
  long interrupt_at_step = -1;
};

/// Exit status of `dspdem run` stopped by SIGINT/SIGTERM (after its checkpoint).
constexpr int kExitInterrupted = 5;

/// Runs the case and writes DIR/{run.pvd, frames/, series.csv, summary.json,
/// case.resolved.toml}. Returns 0 on success. Throws Error for bad input; on numerical
/// trouble writes the partial results to DIR/failed_run and throws NumericalError. Stopped
/// by SIGINT/SIGTERM it writes a checkpoint at the end of the step, keeps the outputs so far
/// in DIR/interrupted_run and throws Interrupted; a second signal exits at once.
int run_case(const CaseConfig& c, const RunOptions& opt);

}  // namespace dspdem
