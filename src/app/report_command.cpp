#include "app/report_command.hpp"

#include <filesystem>

#include "core/error.hpp"
#include "core/folder_lock.hpp"
#include "core/log.hpp"
#include "io/case_config.hpp"
#include "io/run_place.hpp"
#include "report/report_dirs.hpp"
#include "run/run_case.hpp"
#include "run/series_units.hpp"
#include "scenes/registry.hpp"

namespace dspdem {

int report_command(const report::ReportArgs& args) {
  report::ReportArgs a = args;
  CaseConfig c = read_case(a.case_file, a.sets);
  if (a.from_runs.size() == 1) {
    // Analyse the run as it ran: its resolved case holds the overrides it was run with
    // (mesh size, speeds), which the case file alone does not. (A sweep's report folder has
    // none: its runs are checked against the case as given, report/earlier_reports.hpp.)
    const auto resolved = std::filesystem::path(a.from_runs.front()) / "case.resolved.toml";
    if (std::filesystem::exists(resolved)) {
      if (!a.sets.empty()) log::warn("--from-run: the run's own case.resolved.toml is analysed; --set is ignored");
      const std::string given = scenes::of_case(c).name;
      c = read_case(resolved.string());
      // A run of another scene would be reported as that scene's under this case's command.
      const std::string ran = scenes::of_case(c).name;
      DSPDEM_CHECK(ran == given,
                   "{}: --from-run {} is a run of the scene '{}' (its case.resolved.toml), and this case is the scene "
                   "'{}': give a run of this case, or report that run with its own case",
                   a.case_file, a.from_runs.front(), ran, given);
    } else if (std::filesystem::exists(std::filesystem::path(a.from_runs.front()) / "summary.json")) {
      // Every run writes its resolved case beside its summary: without it the case given here
      // would be analysed as the run's, overrides and all, and the report's numbers read against
      // the wrong settings (a probe's: a run's 0.1 ms frames reported as the case's 0.2 ms).
      // (A folder without a summary is refused as not a finished run, by the scene's report.)
      DSPDEM_CHECK(scenes::of_case(c).speed_sweep,
                   "--from-run {}: no case.resolved.toml there, which every run writes beside its results: not a run's "
                   "folder, or one damaged; give the folder of a run this case made",
                   a.from_runs.front());
    }
  }
  // Each run of a sweep would refuse such a monitor at its own start; refused here, the
  // report stops before it makes its folder or starts a run. Also with --from-run: such a
  // run's series.csv holds the name twice, which no analysis can read by name.
  check_monitor_columns(c);
  const scenes::Scene& scene = scenes::of_case(c);
  DSPDEM_CHECK(
      scene.speed_sweep || (a.speeds.empty() && a.study_speeds.empty() && a.realisations == 1 && a.draws == 1),
      "{}: --speeds, --study-speeds, --realisations and --draws belong to a velocity sweep; scene '{}' has none",
      c.path, scene.name);
  DSPDEM_CHECK(scene.speed_sweep || a.from_runs.size() <= 1,
               "{}: --from-run given {} times: scene '{}' analyses one run (several folders merge the runs of a "
               "velocity sweep)",
               c.path, a.from_runs.size(), scene.name);
  DSPDEM_CHECK(!a.runs.resume || a.from_runs.empty(),
               "--resume and --from-run: --from-run analyses an earlier report's runs without running any; --resume "
               "keeps those of this report's folder that are still this report's runs and runs the rest");
  set_setup_stop_hint(
      " (in the report's run then starting); the same report with --resume keeps the runs that finished and "
      "runs the rest");
  // Held until the report is written or stops: a second report into the folder meanwhile is
  // refused here, before it changes anything in it.
  const std::string dir = report::report_folder(c, a);
  const FolderLock lock(dir, report_lock_file, "another report");
  a.runs.report_dir = dir;
  // A folder a render or another report's run place took from a run: a later render or run
  // into it would empty it, this report with it.
  if (const auto from = derived_from(dir))
    fail("{} holds what a render or a report drew from the run in {} (its derived_from); give --out another folder",
         dir, *from);
  try {
    return scene.report(c, a);
  } catch (const Interrupted& e) {
    // A run stopped after its set-up keeps its checkpoint (one still in it, or a sweep's job
    // not started, starts again).
    throw Interrupted(std::string(e.what()) +
                          "; the same report with --resume keeps the runs that finished and continues the stopped ones",
                      e.step, e.time);
  }
}

}  // namespace dspdem
