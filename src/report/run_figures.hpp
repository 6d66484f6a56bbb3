// A single-run scene report's figures of its run: the frames drawn into the report's place
// (DIR/run/images/<view>/) and its tables plotted into DIR/run/images/plots/, as report.md
// links them. Shared by the disc, the beams and the packing; the sphere's sweep draws its own.
#pragma once
#include <string>
#include <vector>

#include "report/report_args.hpp"
#include "report/report_dirs.hpp"

namespace dspdem::report {

/// Draws the run's frames into the report's files with the case's views, or `views` when given;
/// nothing with --no-render.
void draw_run_frames(const ReportDirs& d, const ReportArgs& a, const std::vector<std::string>& views = {});

/// The displacement magnification the run's frames are drawn with: its case.resolved.toml's
/// [render] magnify, as `render` reads it (1 without that file). A report's captions say this,
/// not its own case's, which a report --from-run of an older run may not share.
double drawn_magnification(const std::string& run_dir);

/// Plots of the report's tables: made once per report, it makes images/plots/.
class RunPlots {
 public:
  explicit RunPlots(const ReportDirs& d);
  /// Columns `y` of `csv` against `x` into images/plots/`png`, with `reference_csv` dashed when
  /// given. `csv` is one of the report's files (DIR/run), or the run's own series.csv, which
  /// with --from-run lies in the run given. `y_title` names the left axis of several curves
  /// (one curve's is its column's name).
  void operator()(const std::string& csv, const std::string& x, std::vector<std::string> y, const std::string& title,
                  const std::string& png, const std::string& reference_csv = "", const std::string& y_title = "") const;

 private:
  std::string run_dir_, files_dir_;
};

}  // namespace dspdem::report
