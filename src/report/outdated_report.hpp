// An earlier report whose runs a new report has begun to replace. Runs are replaced one by one
// as they finish (each through its staging folder, io/staging.hpp), while report.md is written
// only at the end: a report that stops between the two would leave the earlier report.md
// describing runs that are no longer the ones beside it, with nothing to say so. The first
// run a report replaces therefore marks the earlier report.md (and report.html, and the
// summary of headline.json that the figures site shows) as outdated, its text otherwise kept;
// the new report's own files replace all three when it is written.
#pragma once
#include <string>

namespace dspdem::report {

/// The first words of the mark, as report.md carries it (a blockquote under the title).
inline constexpr const char* kOutdatedMark = "> **Outdated.**";

/// Whether run folder `run_dir` holds a finished run, which running into it would replace.
bool holds_finished_run(const std::string& run_dir);

/// Marks the report in `dir` as outdated, naming `replaced` (the run folder just replaced,
/// shown relative to `dir`): the mark goes under report.md's title, report.html is rendered
/// from the marked text, and headline.json's summary begins with it. Does nothing when `dir`
/// is empty or holds no report.md, or when its report.md is marked already (the first
/// replacement is named). Each file is rewritten atomically, the three together; one that
/// cannot be is warned of, not thrown: the runs are what matters, and they are in place.
void mark_report_outdated(const std::string& dir, const std::string& replaced);

}  // namespace dspdem::report
