#include "report/earlier_reports.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <optional>

#include "core/error.hpp"
#include "io/run_summary.hpp"
#include "io/staging.hpp"
#include "report/run_data.hpp"
#include "run/checkpoint.hpp"

namespace dspdem::report {

namespace fs = std::filesystem;

namespace {

// The run a folder holds (its summary and its case), checked to be of the case `resolved`;
// nothing when the folder has no summary.json.
std::optional<RunSummary> run_in(const std::string& root, const fs::path& dir, const std::string& resolved) {
  const auto r = run_record(dir.string());
  if (!r) return std::nullopt;
  const auto& ran = r->resolved;
  DSPDEM_CHECK(ran.has_value(), "--from-run {}: {} has a summary.json but no case.resolved.toml to tell its case by",
               root, dir.string());
  // The case as it ran against the case as asked now (the same overrides, every default
  // filled in by this dspdem): a run of another case, or one made before a key's default
  // changed, is not this report's run.
  DSPDEM_CHECK(same_case(*ran, resolved),
               "--from-run {}: the run in {} is not a run of this report's case as it resolves now ({}; the earlier "
               "run's then, this report's now): give the same case and --set overrides it was run with; if they are, "
               "a default has changed since the run was made, and the run is not this dspdem's",
               root, dir.string(), first_difference(*ran, resolved));
  return r->summary;
}

// The report folders that hold a completed run of runs[begin, end), in the order the runs
// first meet them.
std::vector<std::string> roots_in_order(const std::vector<EarlierReportRun>& runs, std::size_t begin, std::size_t end) {
  std::vector<std::string> roots;
  for (std::size_t i = begin; i < std::min(end, runs.size()); ++i)
    if (!runs[i].dir.empty() && std::find(roots.begin(), roots.end(), runs[i].root) == roots.end())
      roots.push_back(runs[i].root);
  return roots;
}

}  // namespace

EarlierReportRun find_earlier_report_run(const std::vector<std::string>& roots, const std::string& rel,
                                         const std::string& resolved) {
  EarlierReportRun found, stopped;  // the completed run taken; the first failed or stopped one
  for (const auto& root : roots) {
    const fs::path dir = fs::path(root) / rel;
    if (const auto s = run_in(root, dir, resolved)) {
      if (!found.dir.empty()) {
        ++found.shadowed;  // a later folder's copy, checked but not taken
        continue;
      }
      found.dir = dir.string(), found.root = root, found.build = s->build;
      continue;
    }
    // A run that failed or was stopped leaves its summary in a folder of its own inside the
    // run folder (io/staging.hpp), and its report's log beside the run folder.
    for (const char* kept : {failed_folder, interrupted_folder})
      if (const auto s = run_in(root, dir / kept, resolved); s && stopped.error.empty()) {
        stopped.error =
            fmt::format("the run in {} {}{}", dir.string(), s->status == "failed" ? "failed" : "was " + s->status,
                        s->message.empty() ? "" : ": " + s->message);
      }
    if (const std::string log = run_log(dir.string()); stopped.lost_log.empty() && fs::exists(log))
      stopped.lost_log = log;
  }
  // A completed run anywhere is taken over one that failed or was stopped elsewhere (a sweep
  // run again into another folder after a failure).
  return found.dir.empty() ? stopped : found;
}

std::string earlier_report_sources(const std::vector<EarlierReportRun>& runs, const std::string& out_dir) {
  // In the order the runs first meet them.
  const std::vector<std::string> roots = roots_in_order(runs, 0, runs.size());
  std::vector<std::string> builds;
  std::map<std::string, int> per_root, per_build;
  int shadowed = 0;
  for (const auto& r : runs) {
    if (r.dir.empty()) continue;
    ++per_root[r.root];
    if (per_build[r.build]++ == 0) builds.push_back(r.build);
    shadowed += r.shadowed > 0;
  }
  if (roots.empty()) return "";
  auto runs_of = [](int n) { return fmt::format("{} run{}", n, n == 1 ? "" : "s"); };
  std::string s;
  for (const auto& r : roots)
    s += fmt::format("{}`{}` ({})", s.empty() ? "" : ", ", fs::proximate(r, out_dir).string(), runs_of(per_root[r]));
  auto build = [](const std::string& b) { return b.empty() ? std::string("not recorded") : b; };
  if (builds.size() == 1) {
    s += fmt::format(", made by one build of dspdem ({})", build(builds.front()));
  } else {
    s += fmt::format(", made by {} builds of dspdem: ", builds.size());
    for (std::size_t i = 0; i < builds.size(); ++i)
      s += fmt::format("{}{} ({})", i ? ", " : "", build(builds[i]), runs_of(per_build[builds[i]]));
  }
  if (shadowed > 0) s += fmt::format("; {} also in a later folder, taken from the first", runs_of(shadowed));
  return s;
}

std::string earlier_report_folders(const std::vector<EarlierReportRun>& runs, std::size_t begin, std::size_t end,
                                   const std::string& sub, const std::string& out_dir) {
  if (runs.empty()) return fmt::format("`{}/`", sub);
  std::string s;
  for (const auto& r : roots_in_order(runs, begin, end))
    s += fmt::format("{}`{}/`", s.empty() ? "" : ", ", fs::proximate(fs::path(r) / sub, out_dir).string());
  return s;
}

}  // namespace dspdem::report
