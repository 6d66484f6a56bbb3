// A whole run of a case: mesh, model, stable step, time loop, frames, series, summary.
#pragma once
#include <string>
#include <vector>

#include "io/case_config.hpp"

namespace dspdem {

struct RunOptions {
  std::string out_dir;
  bool progress = false;  ///< progress line on stderr
  /// Simulated time between checkpoints (DIR/checkpoint.bin while the run goes on); 0: none
  /// by simulated time (one when a signal stops the run, and by checkpoint_wall).
  double checkpoint_every = 0;
  /// Also one every this many seconds of wall time (one process only: the processes of a
  /// distributed run would not agree on the step); 0: never. What a run killed outright (SIGKILL,
  /// out of memory, a lost machine) goes on from: `dspdem run --restart DIR`.
  double checkpoint_wall = 0;
  /// Continue from this checkpoint (run/checkpoint.hpp) instead of t = 0; the case must be
  /// the one it was written for. Its folder holds the outputs written up to it.
  std::string restart_file;
  std::vector<std::string> sets;  ///< the --set overrides, recorded in checkpoints
  /// Set up and time the first steps only, writing nothing (run/estimate.hpp).
  bool estimate = false;
  /// Tests: behave as if SIGTERM arrived during this step (-1: never).
  long interrupt_at_step = -1;
};

/// `dspdem run`'s and the reports' wall time between checkpoints [s]: ten minutes lost at most
/// to a kill, for a file written in well under a second (the sphere impact's 4332 tetrahedra:
/// 74 ms each, 20 of them adding 1.5 s to a 3.8 s run on a 2-core AMD EPYC).
constexpr double kCheckpointWallDefault = 600;

/// Exit status of `dspdem run` stopped by SIGINT, SIGTERM or SIGHUP (after its checkpoint).
constexpr int kExitInterrupted = 5;

/// What a signal during a run's set-up (which exits at once, nothing of that run written)
/// adds to its message: a report that runs its case in its own process says how to keep the
/// runs it finished before. Set before the run, for the rest of the process.
void set_setup_stop_hint(const std::string& hint);

/// Runs the case and writes DIR/{run.pvd, frames/, series.csv, summary.json,
/// case.resolved.toml}. Returns 0 on success. Throws Error for bad input; on numerical
/// trouble writes the partial results to DIR/failed_run and throws NumericalError. Stopped
/// by SIGINT, SIGTERM or SIGHUP it writes a checkpoint at the end of the step, keeps the outputs so far
/// in DIR/interrupted_run and throws Interrupted; a second signal exits at once.
int run_case(const CaseConfig& c, const RunOptions& opt);

}  // namespace dspdem
