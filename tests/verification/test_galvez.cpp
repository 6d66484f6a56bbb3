// The Galvez notched beam end to end (issue 16): `dspdem report cases/galvez_beam.toml` on
// the case as shipped (3583 tets, joints in the crack band, 0.02 m/s), ended once the load
// has fallen to half its peak plus 0.5 ms (about 4.5 min on 1 core; the shipped case runs
// on to a fifth of the peak). No experimental numbers were found
// (src/scenes/galvez_beam/REFERENCE.md), so this checks what the paper describes and what
// must not move:
// - the crack (damaged joints) starts at the notch tip (within one band element, 15 mm),
//   climbs past the middle of the ligament and leans towards the loading side (the
//   mid-plane path ends at x > 0);
// - the peak is quasi-static (kinetic / internal energy there below 0.05; measured 0.03;
//   the 1 ms actuator ramp leaves a ring of up to 0.105 earlier in the loading, which the
//   report prints) and the energy balance closes within 1 % of the largest term;
// - regression: the mid-plane path within 5 mm on average (a third of an element) and
//   15 mm at worst (one element) of the stored path tests/data/galvez_crack_mid.csv, and
//   the cracks view of the last frame within 0.2 % of the pixels of the stored image.
// The run is bitwise the same for any thread count, so the stored values are exact for
// this code; the tolerances allow for changes that move the crack by less than an element.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "render/plot.hpp"
#include "report/crack_sampling.hpp"
#include "scenes/galvez_beam/analysis.hpp"
#include "support/cli.hpp"
#include "support/golden.hpp"

namespace fs = std::filesystem;
using namespace dspdem;

TEST(Galvez, CrackRunsFromTheNotchTowardsTheLoadAndStaysWhereItWas) {
  const fs::path out = fs::temp_directory_path() / "dspdem_galvez_report";
  fs::remove_all(out);
  const fs::path toml = fs::path(DSPDEM_SOURCE_DIR) / "cases/galvez_beam.toml";
  const auto r = testsupport::shell(std::string(DSPDEM_BIN) + " -q report " + toml.string() + " --out " + out.string() +
                                    " --set time.stop_fraction=0.5 --set time.stop_delay=5e-4");
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_TRUE(fs::exists(out / "report.md"));
  const CaseConfig c = read_case((out / "run/case.resolved.toml").string());
  const GalvezResult g = analyse_galvez_run(c, (out / "run").string(), false);
  ASSERT_GE(g.first_crack_frame, 0) << "no joint broke";
  EXPECT_LT(std::abs(g.start_x), 0.015);
  EXPECT_LT(std::abs(g.start_y - g.notch), 0.015);
  EXPECT_GT(g.top_x, 0.0) << "the crack ran away from the loading side";
  EXPECT_GT(g.top_y, g.notch + 0.5 * (g.D - g.notch)) << "the crack stopped in the lower half of the ligament";
  RecordProperty("peak_kN", fmt::format("{:.3f}", 1e-3 * g.P_peak));
  EXPECT_LT(g.ke_ratio_peak, 0.05);
  EXPECT_LT(g.balance_max, 0.01);

  std::vector<std::string> names;
  std::vector<std::vector<double>> cols;
  render::read_csv((fs::path(DSPDEM_SOURCE_DIR) / "tests/data/galvez_crack_mid.csv").string(), names, cols);
  std::vector<std::pair<double, double>> ref;
  for (std::size_t i = 0; i < cols[0].size(); ++i) ref.emplace_back(1e-3 * cols[1][i], 1e-3 * cols[0][i]);
  ASSERT_FALSE(g.path_mid.empty());
  const auto d = report::path_distance(g.path_mid, ref);
  RecordProperty("path_mean_mm", fmt::format("{:.2f}", 1e3 * d.mean));
  RecordProperty("path_hausdorff_mm", fmt::format("{:.2f}", 1e3 * d.hausdorff));
  EXPECT_LT(d.mean, 0.005);
  EXPECT_LT(d.hausdorff, 0.015);

  const fs::path img = out / "run/images/cracks" / fmt::format("frame_{:04d}.png", g.last_frame);
  ASSERT_TRUE(fs::exists(img)) << img;
  if (testsupport::regenerate_golden(img, "galvez_beam_cracks.png")) {
    std::ifstream src(out / "run/crack_mid.csv");
    std::ofstream dst(fs::path(DSPDEM_SOURCE_DIR) / "tests/data/galvez_crack_mid.csv");
    dst << src.rdbuf();
    GTEST_SKIP() << "baseline image and path regenerated";
  }
  testsupport::expect_golden(img, "galvez_beam_cracks.png", "galvez_beam");
}
