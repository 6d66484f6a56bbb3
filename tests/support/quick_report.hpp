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

/// BUILD/figures/<scene>; fails the calling test when the fixture left no report there or
/// the report is older than the dspdem it should come from (the test executable run by hand
/// after a rebuild, without ctest: `ctest -R <test>` runs the fixture first).
inline std::filesystem::path quick_report(const std::string& scene) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::path(DSPDEM_BUILD_DIR) / "figures" / scene;
  const fs::path log = fs::path(DSPDEM_BUILD_DIR) / "figures/logs" / (scene + ".log");
  if (!fs::exists(dir / "report.md")) {
    ADD_FAILURE() << "no report in " << dir << ": the ctest fixture figures_quick makes it (its log: " << log << ")";
  } else if (fs::last_write_time(dir / "report.md") < fs::last_write_time(DSPDEM_BIN)) {
    ADD_FAILURE() << "the report in " << dir << " is older than " << DSPDEM_BIN
                  << ": run the test through ctest (-R), which makes it again first";
  }
  return dir;
}

}  // namespace dspdem::testsupport
