#include "report/report_dirs.hpp"

#include <filesystem>

#include "core/error.hpp"
#include "report/resume.hpp"

namespace dspdem::report {

namespace fs = std::filesystem;

ReportDirs prepare_report_run(const CaseConfig& c, const ReportArgs& a) {
  ReportDirs d;
  d.dir = a.out_dir.empty() ? (fs::path("results") / (c.name + "_report")).string() : a.out_dir;
  // One folder only: report_command refuses several for a scene without a velocity sweep.
  d.run_dir = a.from_runs.empty() ? (fs::path(d.dir) / "run").string() : a.from_runs.front();
  fs::create_directories(d.dir);
  if (a.from_runs.empty()) {
    run_or_resume(c, d.run_dir, a.runs);
  } else {
    DSPDEM_CHECK(fs::exists(fs::path(d.run_dir) / "summary.json"),
                 "--from-run {}: no summary.json there (not the output folder of a finished run)", d.run_dir);
  }
  return d;
}

}  // namespace dspdem::report
