// The Galvez notched beam end to end (issue 16): `dspdem report cases/galvez_beam.toml` on
// the case as shipped (3583 tets, joints in the crack band, 0.02 m/s, the second top line
// held: the nonproportional loading), ended once the load has fallen to half its peak plus
// 0.5 ms (about 70 s on 2 cores): the run of the figures site (the scene's quick_args), which
// the first test reads (support/quick_report.hpp). No experimental numbers were found
// (src/scenes/galvez_beam/REFERENCE.md), so this checks what the mechanics and the paper
// describe and what must not move:
// - the crack (damaged joints, weighted by their width) starts at the notch tip (within one
//   band element, 15 mm), climbs into the top quarter of the ligament and curves towards the
//   loading line: its highest mid-plane point lies more than half way to that line (at
//   +75 mm; measured +55 mm; the free beam's crack, below, ends at +10 mm; joints stop at
//   the band's edge, +70 mm, so the crack cannot pass the line);
// - the peak is quasi-static (kinetic / internal energy there below 0.05; measured 0.005)
//   and the energy balance closes within 1 % of the largest term;
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
#include "support/quick_report.hpp"

namespace fs = std::filesystem;
using namespace dspdem;

TEST(Galvez, CrackRunsFromTheNotchTowardsTheLoadAndStaysWhereItWas) {
  const fs::path out = testsupport::quick_report("galvez_beam");
  ASSERT_TRUE(fs::exists(out / "report.md"));
  const CaseConfig c = read_case((out / "run/case.resolved.toml").string());
  ASSERT_TRUE(c.stop_fraction == 0.5 && c.stop_delay == 5e-4) << "the run is not the one this test is for";
  const GalvezResult g = analyse_galvez_run(c, (out / "run").string(), "");
  ASSERT_GE(g.first_crack_frame, 0) << "no joint broke";
  EXPECT_LT(std::abs(g.start_x), 0.015);
  EXPECT_LT(std::abs(g.start_y - g.notch), 0.015);
  EXPECT_TRUE(g.outer_held);
  EXPECT_GT(g.top_y, g.notch + 0.75 * (g.D - g.notch)) << "the crack stopped below the top quarter of the ligament";
  EXPECT_GT(g.top_x, 0.5 * g.load_x) << "the crack did not curve towards the loading line";
  RecordProperty("peak_kN", fmt::format("{:.3f}", 1e-3 * g.P_peak));
  RecordProperty("top_x_mm", fmt::format("{:.1f}", 1e3 * g.top_x));
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

// The test's other loading condition (Galvez et al. 1998 ran both): the second top line, at
// x = -75 mm, free (the proportional loading, a spring K = 0) instead of held. The beam is
// then in three-point bending with the load D/2 beside the notch; beam theory puts the
// ligament's mean shear stress at 0.04 of its bending stress, so the crack starts nearly in
// mode I and only leans towards the load, where the held beam's crack curves (measured: the
// mid-plane path at x = +10 mm at y = 144.5 mm, against the held beam's +55 mm). Checked: it
// starts at the notch tip, climbs past the middle of the ligament, and ends on the loading
// side but within its inner third (0 < x < 25 mm: a crack curving like the held one's would
// end beyond half way); quasi-static at the peak and the ledger within 1 %. No experimental
// trajectory was found, so these bounds are the mechanics, not a record. The run ends as the
// figures site's does (half the peak plus 0.5 ms), not at the shipped case's stop (a fifth
// plus 0.3 ms): its crack has then reached the same height, y = 144.5 mm, at x = +7.5 mm
// against +10 mm, and the run takes 80 s on 2 cores instead of 100 s (2-core AMD EPYC).
TEST(Galvez, FreeAtItsSecondTopLineTheBeamOnlyLeansItsCrackTowardsTheLoad) {
  const fs::path out = fs::temp_directory_path() / "dspdem_galvez_proportional";
  fs::remove_all(out);
  const fs::path toml = fs::path(DSPDEM_SOURCE_DIR) / "cases/galvez_beam.toml";
  std::string free;
  const CaseConfig shipped = read_case(toml.string());
  for (std::size_t i = 0; i < shipped.boundaries.size(); ++i)
    if (shipped.boundaries[i].group == "load_outer")
      free += fmt::format(" --set 'boundary.{0}.type=\"force\"' --set 'boundary.{0}.value=[0.0,0.0,0.0]'", i);
  ASSERT_FALSE(free.empty()) << "the shipped case no longer holds load_outer";
  const auto r = testsupport::shell(std::string(DSPDEM_BIN) + " -q report " + toml.string() + " --no-render --out " +
                                    out.string() + free + " --set time.stop_fraction=0.5 --set time.stop_delay=5e-4");
  ASSERT_EQ(r.code, 0) << r.out;
  const CaseConfig c = read_case((out / "run/case.resolved.toml").string());
  const GalvezResult g = analyse_galvez_run(c, (out / "run").string(), "");
  EXPECT_FALSE(g.outer_held);
  ASSERT_GE(g.first_crack_frame, 0) << "no joint broke";
  EXPECT_LT(std::abs(g.start_x), 0.015);
  EXPECT_LT(std::abs(g.start_y - g.notch), 0.015);
  EXPECT_GT(g.top_y, g.notch + 0.5 * (g.D - g.notch)) << "the crack stopped in the lower half of the ligament";
  EXPECT_GT(g.top_x, 0.0) << "the crack ran away from the loading side";
  EXPECT_LT(g.top_x, g.load_x / 3) << "the crack curved as if the second top line were held";
  RecordProperty("peak_kN", fmt::format("{:.3f}", 1e-3 * g.P_peak));
  RecordProperty("top_x_mm", fmt::format("{:.1f}", 1e3 * g.top_x));
  EXPECT_LT(g.ke_ratio_peak, 0.05);
  EXPECT_LT(g.balance_max, 0.01);
}
