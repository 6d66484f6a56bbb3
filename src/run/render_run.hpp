// `dspdem render RUN_DIR`: frames of a run drawn per view, animations and plots.
#pragma once
#include <string>
#include <vector>

namespace dspdem {

struct RenderArgs {
  std::string run_dir;
  std::vector<std::string> views;  ///< empty: from the run's case ([render] views)
  std::string field, camera, cut, frames = "all", range, size;
  double magnify = 0;  ///< 0: from the case
  int jobs = 0;        ///< 0: number of cores
  bool no_animation = false;
  bool edges = false;  ///< element edges (or the case's [render] edges)
  std::string worker;  ///< "k/N": render only frames i with i % N == k (internal)
};

int render_command(const RenderArgs& a);

}  // namespace dspdem
