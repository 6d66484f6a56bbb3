#include "report/earlier_reports.hpp"

#include <fmt/format.h>

#include <filesystem>
#include <map>

#include "core/error.hpp"
#include "core/file.hpp"
#include "io/run_summary.hpp"
#include "run/checkpoint.hpp"

namespace dspdem::report {

namespace fs = std::filesystem;

EarlierReportRun find_earlier_report_run(const std::vector<std::string>& roots, const std::string& rel,
                                         const std::string& resolved) {
  EarlierReportRun found;
  for (const auto& root : roots) {
    const fs::path dir = fs::path(root) / rel;
    if (!fs::exists(dir / "summary.json")) {
      if (found.lost_log.empty() && fs::exists(dir.string() + ".log")) found.lost_log = dir.string() + ".log";
      continue;
    }
    const auto ran = read_file_if((dir / "case.resolved.toml").string());
    DSPDEM_CHECK(ran.has_value(), "--from-run {}: {} has a summary.json but no case.resolved.toml to tell its case by",
                 root, dir.string());
    // The case as it ran against the case as asked now (the same overrides, every default
    // filled in by this dspdem): a run of another case, or one made before a key's default
    // changed, is not this report's run.
    DSPDEM_CHECK(same_case(*ran, resolved),
                 "--from-run {}: the run in {} is not a run of this report's case as it resolves now ({}; the "
                 "earlier run's then, this report's now): give the same case and --set overrides it was run with",
                 root, dir.string(), first_difference(*ran, resolved));
    const RunSummary s = read_run_summary((dir / "summary.json").string());
    found.dir = dir.string(), found.root = root, found.build = s.build, found.lost_log.clear();
    if (s.status != "completed")
      found.error = fmt::format("the run in {} {}{}", dir.string(), s.status == "failed" ? "failed" : "was " + s.status,
                                s.message.empty() ? "" : ": " + s.message);
    return found;
  }
  return found;
}

std::string earlier_report_sources(const std::vector<EarlierReportRun>& runs, const std::string& out_dir) {
  // In the order the roots were first met (the order of --from-run for a sweep's plan).
  std::vector<std::string> roots, builds;
  std::map<std::string, int> per_root, per_build;
  for (const auto& r : runs) {
    if (r.dir.empty()) continue;
    if (per_root[r.root]++ == 0) roots.push_back(r.root);
    if (per_build[r.build]++ == 0) builds.push_back(r.build);
  }
  if (roots.empty()) return "";
  auto runs_of = [](int n) { return fmt::format("{} run{}", n, n == 1 ? "" : "s"); };
  std::string s;
  for (const auto& r : roots)
    s += fmt::format("{}`{}` ({})", s.empty() ? "" : ", ", fs::proximate(r, out_dir).string(), runs_of(per_root[r]));
  if (builds.size() == 1) return s + fmt::format(", made by one build of dspdem ({})", builds.front());
  s += fmt::format(", made by {} builds of dspdem: ", builds.size());
  for (std::size_t i = 0; i < builds.size(); ++i)
    s += fmt::format("{}{} ({})", i ? ", " : "", builds[i], runs_of(per_build[builds[i]]));
  return s;
}

}  // namespace dspdem::report
