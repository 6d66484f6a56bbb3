// The Brazilian disc scene on an unstructured mesh (issue 15): the shipped case
// (cases/brazilian_disc.toml: split_plane = 0, curved jaws, the coupled law with the
// inter-element shear parameters in the core and the paper's in the bearing zones) on a
// coarse 12 mm mesh, jaws 4x faster, so CI can afford it (under a minute on 2 cores). What it
// must show: the splitting strength within 15 % of f_t (the CI tolerance; this mesh
// measured -7.1 %, 10 to 7.6 mm between +4.9 and +9.9 %), two halves, and a crack that runs
// along the loaded diameter: the traced path's mean |x| within one element of x = 0
// (measured 6.6 mm here). Its last frame is also the disc's golden fragments image.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "io/case_config.hpp"
#include "run/run_case.hpp"
#include "scenes/brazilian_disc/analysis.hpp"
#include "support/cli.hpp"
#include "support/golden.hpp"

using namespace dspdem;
namespace fs = std::filesystem;

TEST(DiscUnaligned, SplitsAlongTheDiameterWithinFifteenPercentOfTheStrength) {
  const Real h = 0.012;
  const CaseConfig c =
      read_case(std::string(DSPDEM_SOURCE_DIR) + "/cases/brazilian_disc.toml",
                {override_of("mesh.brazilian_disc.size", h), override_of("walls.0.velocity", Vec3(0, -0.08, 0)),
                 override_of("walls.1.velocity", Vec3(0, 0.08, 0)), override_of("time.end", 2e-3),
                 override_of("output.frame_interval", 5e-5), override_of("time.stop_fraction", 0.3)});
  ASSERT_EQ(c.mesh_num.at("split_plane"), 0) << "the shipped case must be unaligned";
  const fs::path dir = fs::temp_directory_path() / "dspdem_test_disc_unaligned";
  fs::remove_all(dir);
  RunOptions o;
  o.out_dir = dir.string();
  ASSERT_EQ(run_case(c, o), 0);
  const DiscResult r = analyse_disc_run(c, dir.string(), "");
  RecordProperty("split_error_pct", std::to_string(100 * r.split_err));
  RecordProperty("crack_path_mean_x_mm", std::to_string(1e3 * r.crack_path_mean_x));
  EXPECT_LT(std::abs(r.split_err), 0.15) << "2P/(pi D L) = " << r.split << " Pa against f_t = " << r.ft;
  ASSERT_GE(r.mass_fractions.size(), 2u);
  // Two halves: the second piece over 35 % of the mass (measured 0.42 here, 0.44-0.45 on the
  // finer meshes; the crushed band between them holds 2-5 %).
  EXPECT_GT(r.mass_fractions[1], 0.35);
  ASSERT_GT(r.crack_path_slices, r.crack_path_bins / 2) << "the crack does not cross the disc";
  EXPECT_LT(r.crack_path_mean_x, h);

  // Regression: the fragments view of the last frame (the split disc) against the stored
  // image; a change that moves the crack off the loaded diameter or breaks the disc
  // differently changes far more than 0.2 % of the pixels.
  const auto rr = testsupport::shell("env -u DISPLAY " + std::string(DSPDEM_BIN) + " -q render " + dir.string() +
                                     " --frames last --view fragments");
  ASSERT_EQ(rr.code, 0) << rr.out;
  fs::path img;
  for (const auto& e : fs::directory_iterator(dir / "images" / "fragments")) img = std::max(img, e.path());
  if (testsupport::regenerate_golden(img, "brazilian_disc_fragments.png")) GTEST_SKIP() << "baseline regenerated";
  testsupport::expect_golden(img, "brazilian_disc_fragments.png", "brazilian_disc");
}
