// Line plots of series.csv columns, drawn with VTK's charts off-screen into a PNG.
#pragma once
#include <string>
#include <vector>

namespace dspdem::render {

struct PlotSpec {
  std::string x;               ///< column for the x axis
  std::vector<std::string> y;  ///< columns drawn against it
  std::string reference_csv;   ///< optional: CSV with the same x and y column names, drawn dashed
  std::string title;
  int width = 1000, height = 600;
  /// Axis titles with units. By default, the column's name, with its unit where the name ends
  /// in one ("time_ms" reads "time [ms]"); for several curves, the unit they share.
  std::string x_title = {}, y_title = {};
};

/// Plots from `csv` into `png`; throws Error naming the file and column if one is missing.
void plot_csv(const std::string& csv, const PlotSpec& spec, const std::string& png);

/// One curve of its own x values (curves of one plot need not share their x).
struct Curve {
  std::string name;
  std::vector<double> x, y;
};

/// Several curves in one chart, e.g. a distribution per run of a sweep; `log_x` draws the
/// x axis on a log scale (x must then be positive). Throws Error for an empty curve list.
void plot_curves(const std::vector<Curve>& curves, const std::string& x_title, const std::string& y_title,
                 const std::string& title, const std::string& png, bool log_x = false, int width = 1000,
                 int height = 600);

/// Reads a numeric CSV with a header row: returns the column names and the columns.
void read_csv(const std::string& path, std::vector<std::string>& names, std::vector<std::vector<double>>& cols);

}  // namespace dspdem::render
