// Golden-image checks shared by the scene tests: compare a rendered frame with its stored
// baseline in tests/regression/images/ through `dspdem imgdiff` (threshold 0.2 % of the
// pixels: a one-pixel shift and anti-aliasing give 0; another frame of the same run or
// another camera changes several per cent). On failure the new image and the difference
// are kept in BUILD/tests/image_failures (CI keeps that folder). With DSPDEM_REGEN_IMAGES
// set, the baseline is overwritten instead and the caller should skip.
#pragma once
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <string>

#include "support/cli.hpp"

namespace dspdem::testsupport {

/// True when the baseline was regenerated (the caller then skips).
inline bool regenerate_golden(const std::filesystem::path& img, const std::string& baseline) {
  if (!std::getenv("DSPDEM_REGEN_IMAGES")) return false;
  std::filesystem::copy_file(img, std::filesystem::path(DSPDEM_SOURCE_DIR) / "tests/regression/images" / baseline,
                             std::filesystem::copy_options::overwrite_existing);
  return true;
}

/// Expects `img` to match tests/regression/images/<baseline>; `name` names the kept files.
inline void expect_golden(const std::filesystem::path& img, const std::string& baseline, const std::string& name) {
  namespace fs = std::filesystem;
  ASSERT_TRUE(fs::exists(img)) << img;
  const fs::path base = fs::path(DSPDEM_SOURCE_DIR) / "tests/regression/images" / baseline;
  const fs::path fails = fs::path(DSPDEM_BUILD_DIR) / "tests/image_failures";
  fs::create_directories(fails);
  const fs::path diff = fails / (name + ".diff.png");
  const CliResult r = shell(std::string(DSPDEM_BIN) + " imgdiff " + img.string() + " " + base.string() +
                            " --threshold 0.002 --diff " + diff.string());
  if (r.code != 0)
    fs::copy_file(img, fails / (name + ".png"), fs::copy_options::overwrite_existing);
  else
    fs::remove(diff);
  EXPECT_EQ(r.code, 0) << r.out << "\nnew image and difference kept in " << fails;
}

}  // namespace dspdem::testsupport
