// `dspdem render RUN_DIR`: frames of a run drawn per view, animations and plots.
#pragma once
#include <string>
#include <vector>

#include "io/case_config.hpp"

namespace dspdem {

struct RenderArgs {
  std::string run_dir;
  /// Where images/ goes; empty: the run's folder. A report reading an earlier report's runs
  /// draws them into its own folder, so that it leaves the earlier one as it was.
  std::string out_dir;
  std::vector<std::string> views;  ///< empty: from the run's case ([render] views)
  std::string field, camera, cut, frames = "all", range, size;
  double magnify = 0;  ///< 0: from the case
  int jobs = 0;        ///< 0: number of cores
  bool no_animation = false;
  bool edges = false;  ///< element edges (or the case's [render] edges)
  std::string worker;  ///< "k/N": render only frames i with i % N == k (internal)
  std::string label;   ///< written in the corner in place of the case's name (a sweep's speed)
};

int render_command(const RenderArgs& a);

/// One colour range for `field` over every frame of several runs (0.5th to 99.5th percentile;
/// from zero for magnitudes, centred on zero for signed stresses), as "MIN:MAX" for
/// RenderArgs::range: runs drawn with it compare colour for colour (a sweep, a study).
/// The case's [render] range_min / range_max, when set, win as in a single run.
std::string common_range(const std::vector<std::string>& run_dirs, const std::string& field, const RenderConfig& rc);

}  // namespace dspdem
