// `dspdem report --resume`: the runs an earlier report left in its folder, kept when they
// finished and continued from their checkpoints when a signal stopped them or they were
// killed outright, provided they are the same runs. For the sphere's sweep (its runs as
// processes) and for every report's own run and study (run in-process).
#pragma once
#include <string>

#include "io/case_config.hpp"
#include "report/report_args.hpp"

namespace dspdem::report {

/// What an earlier report left in a run folder: nothing of use, the same run finished, or the
/// same run unfinished with a checkpoint to go on from (stopped by a signal, or killed
/// outright: `dspdem run --restart DIR` takes the newest checkpoint, find_checkpoint).
enum class Earlier { None, Finished, Interrupted };

/// What earlier_run found, and for Interrupted the checkpoint it judged to be this run's: the
/// one to go on from, in-process or as `dspdem run --restart FILE` (a second search of the
/// folder could find another, should a killed run's folder appear in between, and would read
/// every candidate again).
struct EarlierRun {
  Earlier state = Earlier::None;
  std::string checkpoint;
};

/// Whether run folder `dir` holds the run of the case that resolves to `resolved` (its
/// case.resolved.toml) from an earlier report, and how far it got. It is the same run when
/// this dspdem executable made it (its build id and its file's CRC, as its summary.json or
/// its checkpoint's header records them; not the shared libraries nor a mesh file the case
/// names) and its case, as it ran, is the case as it resolves now (every default filled in,
/// every override applied; same_case leaves out the first comment, which names the case file
/// as it was given). It is continued from the newest checkpoint in `dir` when that is the one
/// its interruption left (interrupted_run/, beside its summary) or the last one a killed run
/// wrote by wall time (its staging folder, its process gone). Anything unreadable: None.
EarlierRun earlier_run(const std::string& dir, const std::string& resolved);

/// Runs `c` into `dir` in this process (run_case, its overrides recorded in its checkpoints so
/// that `dspdem run --restart DIR` can continue it, checkpoints by wall time as `runs` says);
/// with `runs.resume`, keeps the same finished run there instead, or continues the same
/// unfinished one from its checkpoint. Returns which. A finished run it replaces marks the
/// report in `runs.report_dir` outdated (mark_report_outdated).
Earlier run_or_resume(const CaseConfig& c, const std::string& dir, const RunPolicy& runs);

}  // namespace dspdem::report
