// What `dspdem report CASE.toml` was asked for; every scene's report takes the same.
#pragma once
#include <string>
#include <vector>

namespace dspdem::report {

struct ReportArgs {
  std::string case_file, out_dir;
  std::vector<std::string> sets;
  bool study = false;                ///< also run the speed-against-error sweep
  bool no_render = false;            ///< skip images (numbers and plots only)
  std::string from_run;              ///< analyse this finished run of the same case instead of running it
  bool no_stress_check = false;      ///< skip a scene's extra verification runs (the disc's stress check)
  std::vector<double> speeds;        ///< a sweep over impact speeds (the sphere impact), empty: the scene's own list
  std::vector<double> study_speeds;  ///< speeds of the sphere impact's study, empty: the scene's own (7.5, 20)
  int realisations = 1;  ///< runs per speed of a sweep, each with the mesh turned another way (the sphere impact)
  int jobs = 0;          ///< runs of a sweep or study in parallel processes (0: one per core)
  /// A sweep's runs that an earlier report left in the output folder are kept when they are
  /// the same runs (the case as resolved now, the same dspdem build): finished ones as they
  /// are, interrupted ones continued from their checkpoints. The rest run as usual.
  bool resume = false;
};

}  // namespace dspdem::report
