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
};

/// Plots from `csv` into `png`; throws Error naming the file and column if one is missing.
void plot_csv(const std::string& csv, const PlotSpec& spec, const std::string& png);

/// Reads a numeric CSV with a header row: returns the column names and the columns.
void read_csv(const std::string& path, std::vector<std::string>& names, std::vector<std::vector<double>>& cols);

}  // namespace dspdem::render
