// report/run_figures: a report's captions say the magnification the run's frames were drawn
// with, the run's own (its case.resolved.toml), not the report's case's: a report --from-run
// of an older run drawn unmagnified said "displacement x100" under images drawn x1.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "report/run_figures.hpp"

namespace fs = std::filesystem;

TEST(RunFigures, TheMagnificationSaidIsTheOneTheRunIsDrawnWith) {
  const fs::path run = fs::temp_directory_path() / ("dspdem_run_figures_" + std::to_string(getpid()));
  fs::remove_all(run);
  fs::create_directories(run);
  // Without case.resolved.toml, render draws with the default settings: x1.
  EXPECT_EQ(dspdem::report::drawn_magnification(run.string()), 1.0);
  // The Galvez case as shipped draws x100; the run's resolved case here says x1.
  std::ifstream in(fs::path(DSPDEM_SOURCE_DIR) / "cases/galvez_beam.toml");
  std::stringstream text;
  text << in.rdbuf();
  std::string s = text.str();
  const std::string shipped = "magnify = 100.0";
  const auto at = s.find(shipped);
  ASSERT_NE(at, std::string::npos) << "cases/galvez_beam.toml no longer draws x100: this test needs another case";
  std::ofstream(run / "case.resolved.toml") << s;
  EXPECT_EQ(dspdem::report::drawn_magnification(run.string()), 100.0);
  s.replace(at, shipped.size(), "magnify = 1.0");
  std::ofstream(run / "case.resolved.toml") << s;
  EXPECT_EQ(dspdem::report::drawn_magnification(run.string()), 1.0);
  fs::remove_all(run);
}
