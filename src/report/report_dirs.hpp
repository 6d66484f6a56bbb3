// Where a scene's report goes and which run it reads: DIR (default results/<case>_report)
// and DIR/run, which is run first, or the finished run given with --from-run. What the report
// derives from the run (its CSV files and images) goes to DIR/run in both cases, so that a run
// given with --from-run, perhaps another report's, is only read.
#pragma once
#include <string>

#include "io/case_config.hpp"
#include "report/report_args.hpp"

namespace dspdem::report {

struct ReportDirs {
  std::string dir, run_dir;
  /// DIR/run: the run itself, or with --from-run of another folder its place here.
  std::string files_dir;
  /// The run's folder as the report's text names it: relative to DIR, with a final slash.
  std::string run_from_dir() const;
};

/// The report's folder: --out, else results/<case>_report.
std::string report_folder(const CaseConfig& c, const ReportArgs& a);

/// Makes DIR, runs the case into DIR/run (with --resume, keeps or continues the same run an
/// earlier report left there) unless --from-run names a finished run (which must hold a
/// summary.json: Error otherwise; DIR/run, where the report then writes, is made ready by
/// take_derived_place), and returns the folders.
ReportDirs prepare_report_run(const CaseConfig& c, const ReportArgs& a);

}  // namespace dspdem::report
