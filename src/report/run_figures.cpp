#include "report/run_figures.hpp"

#include <filesystem>

#include "io/case_config.hpp"
#include "render/plot.hpp"
#include "run/render_run.hpp"

namespace dspdem::report {

namespace fs = std::filesystem;

namespace {
fs::path plots_dir(const std::string& files_dir) { return fs::path(files_dir) / "images" / "plots"; }
}  // namespace

void draw_run_frames(const ReportDirs& d, const ReportArgs& a, const std::vector<std::string>& views) {
  if (a.no_render) return;
  RenderArgs ra;
  ra.run_dir = d.run_dir, ra.out_dir = d.files_dir;
  ra.views = views;
  render_command(ra);
}

double drawn_magnification(const std::string& run_dir) {
  const fs::path resolved = fs::path(run_dir) / "case.resolved.toml";
  return fs::exists(resolved) ? read_case(resolved.string()).render.magnify : RenderConfig{}.magnify;
}

RunPlots::RunPlots(const ReportDirs& d) : run_dir_(d.run_dir), files_dir_(d.files_dir) {
  fs::create_directories(plots_dir(files_dir_));
}

void RunPlots::operator()(const std::string& csv, const std::string& x, std::vector<std::string> y,
                          const std::string& title, const std::string& png, const std::string& reference_csv,
                          const std::string& y_title) const {
  // series.csv is the run's: with --from-run it was not copied into the report's files.
  const fs::path from = fs::path(csv == "series.csv" ? run_dir_ : files_dir_) / csv;
  render::PlotSpec spec{x, std::move(y), reference_csv, title};
  spec.y_title = y_title;
  render::plot_csv(from.string(), spec, (plots_dir(files_dir_) / png).string());
}

}  // namespace dspdem::report
