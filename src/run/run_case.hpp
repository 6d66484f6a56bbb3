// A whole run of a case: mesh, model, stable step, time loop, frames, series, summary.
#pragma once
#include <string>

#include "io/case_config.hpp"

namespace dspdem {

struct RunOptions {
  std::string out_dir;
  bool progress = false;  ///< progress line on stderr
};

/// Runs the case and writes DIR/{run.pvd, frames/, series.csv, summary.json,
/// case.resolved.toml}. Returns 0 on success. Throws Error for bad input; on numerical
/// trouble writes the partial results to DIR/failed_run and throws NumericalError.
int run_case(const CaseConfig& c, const RunOptions& opt);

}  // namespace dspdem
