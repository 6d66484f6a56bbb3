#include "report/resume.hpp"

#include <filesystem>

#include "core/log.hpp"
#include "io/staging.hpp"
#include "report/outdated_report.hpp"
#include "report/run_data.hpp"
#include "run/checkpoint.hpp"
#include "run/run_case.hpp"

namespace dspdem::report {

namespace fs = std::filesystem;

EarlierRun earlier_run(const std::string& dir, const std::string& resolved) {
  const fs::path d(dir);
  auto same = [&](const fs::path& run, const char* status) {
    const auto r = run_record(run.string());
    return r && r->resolved && r->summary.status == status && r->summary.build == executable_id() &&
           same_case(*r->resolved, resolved);
  };
  try {
    if (same(d, "completed")) return {Earlier::Finished, {}};
    // The newest checkpoint in the folder (its CRC checked), which `run --restart DIR` would
    // take too: it must be this run's.
    const FoundCheckpoint ckpt = find_checkpoint(dir);
    const fs::path from = fs::path(ckpt.path).parent_path();
    if (from == d / interrupted_folder) {
      if (!same(from, "interrupted")) return {};
    } else if (!left_by_killed_run(from.string())) {
      return {};  // a live run's (another report's, at work in this folder) or none
    }
    // The executable, and with it the build (executable_id begins with checkpoint_build_id).
    if (ckpt.header.executable == executable_id() && same_case(ckpt.header.resolved_toml, resolved))
      return {Earlier::Interrupted, ckpt.path};
  } catch (const std::exception&) {
    // An unreadable summary, folder or checkpoint: the run starts again.
  }
  return {};
}

Earlier run_or_resume(const CaseConfig& c, const std::string& dir, const RunPolicy& runs) {
  const EarlierRun e = runs.resume ? earlier_run(dir, c.resolved_toml) : EarlierRun{};
  if (e.state == Earlier::Finished) {
    log::info("--resume: kept the finished run in {}", dir);
    return e.state;
  }
  RunOptions o;
  o.out_dir = dir;
  o.sets = c.overrides;
  o.checkpoint_wall = runs.checkpoint_wall;
  if (e.state == Earlier::Interrupted) {
    o.restart_file = e.checkpoint;
    log::info("--resume: continuing the run in {} from its checkpoint {}", dir, o.restart_file);
  }
  const RunReplacement earlier(dir);
  try {
    run_case(c, o);
  } catch (...) {
    // Stopped or failed after its commit (a signal then), it has replaced the earlier run all the same.
    if (earlier.replaced()) mark_report_outdated(runs.report_dir, dir);
    throw;
  }
  if (earlier.replaced()) mark_report_outdated(runs.report_dir, dir);
  return e.state;
}

}  // namespace dspdem::report
