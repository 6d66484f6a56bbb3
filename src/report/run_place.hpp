// Where a report writes what it derives from a run it did not make (`report --from-run`): the
// run's place in the report's own folder, never the run's folder, which may be another
// report's and is only read.
#pragma once
#include <string>

namespace dspdem::report {

/// Whether `dir` holds a run: finished (summary.json, run.pvd), failed or stopped (failed_run/,
/// interrupted_run/), or running or killed (a staging folder, io/staging.hpp).
bool holds_a_run(const std::string& dir);

/// Makes `place` ready for what a report derives from the run in `run_dir`. Nothing to do when
/// they are one folder. Error when `place` holds another run: derived files beside it would
/// read as its; also when it holds files but no place/derived_from, which records the run a
/// report filled it from: only such a folder is ever emptied, when it was filled from another
/// run (its images would show as this run's).
void prepare_derived_place(const std::string& place, const std::string& run_dir);

}  // namespace dspdem::report
