// `dspdem report --resume`: the runs an earlier report left in its folder, kept when they
// finished and continued from their checkpoints when a signal stopped them, provided they
// are the same runs. For the sphere's sweep (its runs as processes) and for every report's
// own run and study (run in-process).
#pragma once
#include <string>

#include "io/case_config.hpp"

namespace dspdem::report {

/// What an earlier report left in a run folder.
enum class Earlier { None, Finished, Interrupted };

/// Whether run folder `dir` holds the run of the case that resolves to `resolved` (its
/// case.resolved.toml) from an earlier report, and how far it got. It is the same run when
/// its summary.json names this dspdem executable (its build id and its file's CRC; not the
/// shared libraries nor a mesh file the case names) and its case, as it ran, is the case as it
/// resolves now (every default filled in, every override applied; same_case leaves out the
/// first comment, which names the case file as it was given). A run is continued only from the
/// checkpoint its own interruption left (interrupted_run/, with its summary); a run killed
/// outright left no summary there and starts again. Anything unreadable: None.
Earlier earlier_run(const std::string& dir, const std::string& resolved);

/// Runs `c` into `dir` in this process (run_case, its overrides recorded in its checkpoints so
/// that `dspdem run --restart DIR` can continue it); with `resume`, keeps the same finished run
/// there instead, or continues the same interrupted one from its checkpoint. Returns which.
Earlier run_or_resume(const CaseConfig& c, const std::string& dir, bool resume);

}  // namespace dspdem::report
