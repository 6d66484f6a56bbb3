// Where a scene's report goes and which run it reads: DIR (default results/<case>_report)
// and DIR/run, which is run first, or the finished run given with --from-run.
#pragma once
#include <string>

#include "io/case_config.hpp"
#include "report/report_args.hpp"

namespace dspdem::report {

struct ReportDirs {
  std::string dir, run_dir;
};

/// Makes DIR, runs the case into DIR/run (with --resume, keeps or continues the same run an
/// earlier report left there) unless --from-run names a finished run (which must hold a
/// summary.json: Error otherwise), and returns both folders.
ReportDirs prepare_report_run(const CaseConfig& c, const ReportArgs& a);

}  // namespace dspdem::report
