// `dspdem report --from-run DIR ...` over a sweep: the runs of earlier reports analysed again
// without running any, from one report's folder or merged from several (a sweep extended by
// another report at new speeds or on more meshes is fitted as one). Each run is taken only
// when it is a run of the case as it resolves now, so that runs of another case, or of the
// same case with other overrides, are never mixed in silently.
#pragma once
#include <cstddef>
#include <string>
#include <vector>

namespace dspdem::report {

/// A planned run as found among the earlier reports' folders.
struct EarlierReportRun {
  std::string dir;    ///< its completed run's folder; empty when no folder holds one
  std::string root;   ///< the report folder its completed run was found in
  std::string build;  ///< the dspdem that made that run (its summary's executable id)
  std::string error;  ///< no completed run, but one that failed or was stopped: why
  /// When no folder holds its summary but one holds its log: that log (the earlier report
  /// started the run and lost it, as opposed to a run it never had).
  std::string lost_log;
  int shadowed = 0;  ///< later folders with a completed copy of it (checked, not taken)
};

/// Looks for the run folder `rel` (below a report's folder, e.g. "speeds/v5") in each of
/// `roots` and takes the first completed run (its summary.json in the folder). Every run
/// found must be of the case that resolves to `resolved` (its case.resolved.toml, compared as
/// same_case does): otherwise throws Error naming the folder and the first line that differs.
/// Without a completed run anywhere, the first that failed or was stopped (its summary in
/// the folder's failed_run/ or interrupted_run/, io/staging.hpp) sets `error`, and the first
/// log of it (`rel`.log, beside its folder: a run killed outright leaves only that) sets
/// `lost_log`; neither: no root ever ran it.
EarlierReportRun find_earlier_report_run(const std::vector<std::string>& roots, const std::string& rel,
                                         const std::string& resolved);

/// Which earlier reports and builds made `runs`, for the report's text: "`A` (12 runs),
/// `B` (8 runs), made by one build of dspdem (ID)" or "... by 2 builds: ID (12 runs), ..."
/// (paths relative to `out_dir`). Runs with an empty dir are left out.
std::string earlier_report_sources(const std::vector<EarlierReportRun>& runs, const std::string& out_dir);

/// Where runs[begin, end) lie, for the report's text: their folder `sub` (e.g. "speeds") of
/// each earlier report that holds any of them, relative to `out_dir`, in the order the runs
/// first meet them: "`../a/speeds/`, `../b/speeds/`". Without --from-run (`runs` empty) the
/// report's own: "`speeds/`". Empty when none of them holds a completed run.
std::string earlier_report_folders(const std::vector<EarlierReportRun>& runs, std::size_t begin, std::size_t end,
                                   const std::string& sub, const std::string& out_dir);

}  // namespace dspdem::report
