#include "report/report_dirs.hpp"

#include <filesystem>

#include "core/error.hpp"
#include "io/run_place.hpp"
#include "report/resume.hpp"

namespace dspdem::report {

namespace fs = std::filesystem;

std::string ReportDirs::run_from_dir() const { return fs::relative(run_dir, dir).string() + "/"; }

std::string report_folder(const CaseConfig& c, const ReportArgs& a) {
  return a.out_dir.empty() ? (fs::path("results") / (c.name + "_report")).string() : a.out_dir;
}

ReportDirs prepare_report_run(const CaseConfig& c, const ReportArgs& a) {
  ReportDirs d;
  d.dir = report_folder(c, a);
  d.files_dir = (fs::path(d.dir) / "run").string();
  // One folder only: report_command refuses several for a scene without a velocity sweep.
  d.run_dir = a.from_runs.empty() ? d.files_dir : a.from_runs.front();
  if (a.from_runs.empty()) {
    fs::create_directories(d.dir);  // DIR/run, filled from another run by an earlier report, is emptied by the run
    run_or_resume(c, d.run_dir, a.runs);
    return d;
  }
  DSPDEM_CHECK(fs::exists(fs::path(d.run_dir) / "summary.json"),
               "--from-run {}: no summary.json there (not the output folder of a finished run)", d.run_dir);
  take_derived_place(d.files_dir, d.run_dir);  // DIR/run may be the run itself: then nothing to do
  return d;
}

}  // namespace dspdem::report
