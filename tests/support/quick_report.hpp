// A scene's CI-sized report, as the scene tests read it. The ctest fixture figures_quick
// (`dspdem figures --quick`) runs every scene's report with its quick_args
// (src/scenes/registry.cpp) into BUILD/figures/<scene> for the figures site; the scene tests
// that check that same run read it there instead of running it again (about two minutes of
// CI on 2 cores). Tests that need other settings run their own.
#pragma once
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

namespace dspdem::testsupport {

/// BUILD/figures/<scene>; fails the calling test when the fixture left no report there.
inline std::filesystem::path quick_report(const std::string& scene) {
  const std::filesystem::path dir = std::filesystem::path(DSPDEM_BUILD_DIR) / "figures" / scene;
  EXPECT_TRUE(std::filesystem::exists(dir / "report.md"))
      << "no report in " << dir << ": the ctest fixture figures_quick makes it (its log: "
      << (std::filesystem::path(DSPDEM_BUILD_DIR) / "figures/logs" / (scene + ".log")) << ")";
  return dir;
}

}  // namespace dspdem::testsupport
