// What `dspdem report CASE.toml` was asked for; every scene's report takes the same.
#pragma once
#include <string>
#include <vector>

#include "run/run_case.hpp"

namespace dspdem::report {

/// How a report makes the runs it makes in its own process or as processes of a sweep.
struct RunPolicy {
  /// A run that an earlier report left in its folder is kept when it is the same run (the case
  /// as resolved now, the same dspdem executable) and finished, continued from its checkpoint
  /// when a signal stopped it or it was killed outright; the rest run as usual.
  bool resume = false;
  /// Their checkpoints by wall time (RunOptions::checkpoint_wall) [s]; 0: never.
  double checkpoint_wall = kCheckpointWallDefault;
  /// The report's folder, whose earlier report.md a run that replaces one of its finished
  /// runs marks outdated (report/outdated_report.hpp); empty: none.
  std::string report_dir;
};

struct ReportArgs {
  std::string case_file, out_dir;
  std::vector<std::string> sets;
  bool study = false;      ///< also run the speed-against-error sweep
  bool no_render = false;  ///< skip images (numbers and plots only)
  /// Analyse earlier runs of the same case instead of running them: a finished run's folder,
  /// or for a velocity sweep one or more earlier reports' folders (report/earlier_reports.hpp).
  std::vector<std::string> from_runs;
  bool no_stress_check = false;      ///< skip a scene's extra verification runs (the disc's stress check)
  std::vector<double> speeds;        ///< a sweep over impact speeds (the sphere impact), empty: the scene's own list
  std::vector<double> study_speeds;  ///< speeds of the sphere impact's study, empty: the scene's own (7.5, 20)
  int realisations = 1;  ///< runs per speed of a sweep, each with the mesh turned another way (the sphere impact)
  int draws = 1;         ///< runs of each of those on the same mesh, the speed nudged (the sphere impact)
  int jobs = 0;          ///< runs of a sweep or study in parallel processes (0: one per core)
  RunPolicy runs;        ///< --resume and --checkpoint-wall
};

}  // namespace dspdem::report
