// `dspdem render RUN_DIR... --montage OUT.png`: one image of several runs at one time, a
// panel per run and per row (a view, optionally cut), each panel labelled with its run; all
// panels framed by the first run's first frame so they compare pixel by pixel.
#pragma once
#include <string>
#include <vector>

namespace dspdem {

struct MontageArgs {
  std::vector<std::string> run_dirs;  ///< one column each, in order
  std::vector<std::string> labels;    ///< written on each column's panels (default: the run folder's name)
  double time = -1;                   ///< simulated time [s] of the frames; < 0: each run's last frame
  std::vector<double> times;          ///< per run instead of `time` (e.g. a time after each run's first contact)
  /// One row per entry: "view" or "view:cut" (view: stress, fragments, cracks; cut: none, x, y, z).
  std::vector<std::string> rows = {"fragments"};
  std::string camera;             ///< default: the first run's case
  std::string field;              ///< stress rows: default the first run's case
  std::string range;              ///< stress rows: MIN:MAX (default: 0.5-99.5 percentiles over the panels)
  int width = 640, height = 480;  ///< of one panel
  /// Frame the panels on the first run's drawn frame and its walls (a heap in its box) instead
  /// of on its first frame's bodies (what moves stays in view).
  bool frame_walls = false;
  std::string out;  ///< PNG to write, through a temporary name; ".png" is added to a name without it
};

/// What a montage drew: per run, the frame used and its time.
struct MontageFrames {
  std::vector<std::size_t> frame;
  std::vector<double> time;
};

/// Draws and writes the montage. Throws Error for a missing run, an unknown view or cut, a
/// cracks row for a run without joints, labels that do not match the runs, or an output name
/// that is a folder or has another image type's extension (.jpg, .pdf, ...).
MontageFrames write_montage(const MontageArgs& a);

}  // namespace dspdem
