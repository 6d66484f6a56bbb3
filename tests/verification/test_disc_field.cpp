// The elastic field of the Brazilian disc scene against the point-load solution (paper
// eqs. 24-25, src/scenes/brazilian_disc/REFERENCE.md), on the report's stress-check mesh: the check
// that `dspdem report` runs beside the scene. The scene's own mesh (7.6 mm linear tets) is
// too coarse near the plates for this; the check's case is built from the scene's file.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <filesystem>

#include "io/case_config.hpp"
#include "scenes/brazilian_disc/analysis.hpp"
#include "scenes/brazilian_disc/stress_check.hpp"

using namespace dspdem;
namespace fs = std::filesystem;

namespace {
// The scene's profile frame, from its run (`dspdem report cases/brazilian_disc.toml`: frame
// 23, t = 2.3 ms, 29.48 kN, 83 % of its 35.47 kN peak): the report gives the check these.
constexpr Real kSceneProfileTime = 2.3e-3, kSceneProfileLoad = 29.48e3;
CaseConfig scene() { return read_case(fmt::format("{}/cases/brazilian_disc.toml", DSPDEM_SOURCE_DIR), {}); }
}  // namespace

TEST(DiscField, StressCheckCaseChangesOnlyMeshJointsRateAndLoading) {
  const CaseConfig s = scene();
  const Real t = kSceneProfileTime;
  const CaseConfig c = stress_check_case(s, t, kSceneProfileLoad);
  EXPECT_NEAR(c.mesh_num.at("size"), 0.66 * s.mesh_num.at("size"), 1e-12);
  EXPECT_NEAR(c.mesh_num.at("load_size"), s.mesh_num.at("size") / 7.6, 1e-12);
  EXPECT_EQ(c.mesh_num.at("diameter"), s.mesh_num.at("diameter"));
  EXPECT_EQ(c.mesh_num.at("split_plane"), s.mesh_num.at("split_plane"));
  for (const auto& b : c.bodies) EXPECT_EQ(b.fracture, BodyConfig::Fracture::None);
  ASSERT_EQ(c.walls.size(), s.walls.size());
  for (std::size_t i = 0; i < c.walls.size(); ++i) {
    EXPECT_TRUE(c.walls[i].wall.velocity_target.isApprox(4 * s.walls[i].wall.velocity_target));
    // The scene's curved jaws become the paper's flat plates, whose field the point-load
    // solution is, touching the disc where the jaws do.
    EXPECT_EQ(c.walls[i].wall.type, contact::Wall::Type::Box);
    EXPECT_EQ(c.walls[i].wall.name, s.walls[i].wall.name);
    EXPECT_NEAR(std::abs(c.walls[i].wall.centre(1)) - c.walls[i].wall.half(1), 0.5 * s.mesh_num.at("diameter"), 1e-12);
  }
  EXPECT_NEAR(c.t_end, 1.25 * t / 4, 1e-15);  // a bound: the run ends at the profile load
  EXPECT_EQ(c.stop_series, s.walls[0].wall.name + "_fy");
  EXPECT_EQ(c.stop_reach, kSceneProfileLoad);
  EXPECT_NEAR(c.frame_interval, s.frame_interval / 4, 1e-15);
  EXPECT_EQ(c.materials.size(), s.materials.size());
  EXPECT_EQ(c.contact.enabled, s.contact.enabled);
  EXPECT_EQ(c.contact.settings.step_fraction, 1.0);  // the plates load slowly: the contact's full step
  EXPECT_NE(c.resolved_toml.find("fracture = 'none'"), std::string::npos);
}

TEST(DiscField, SigmaAlongTheDiameterWithinFivePercentOnTheCheckMesh) {
  // The acceptance: sigma_xx along the loaded diameter within 5 % L2 of the
  // analytic solution before cracking (over the central 80 %, 16 bins, each element against
  // the field's mean over it), read as the report reads it: at the scene's profile load.
  // Measured 3.1 % (sigma_yy 2.5 %; the same to 0.03 points with the contact's default
  // half step, which takes 1.6 times the steps); the scene's 7.6 mm mesh gives
  // about 24 %. Over meshes of this kind it was 2.7-4.6 %: the tolerance is the issue's
  // 5 %, not a fit to this run. The run stops once the top plate carries the target load
  // (17781 steps, against 21661 to its bound; the same profile frame and figures).
  const CaseConfig c = stress_check_case(scene(), kSceneProfileTime, kSceneProfileLoad);
  const fs::path dir = fs::temp_directory_path() / "dspdem_test_disc_field";
  fs::remove_all(dir);
  const DiscResult r = run_stress_check(c, dir.string());
  RecordProperty("l2_xx_pct", std::to_string(100 * r.l2_xx));
  RecordProperty("l2_yy_pct", std::to_string(100 * r.l2_yy));
  RecordProperty("P_profile_kN", std::to_string(1e-3 * r.P_profile));
  EXPECT_NEAR(r.P_profile / kSceneProfileLoad, 1.0, 0.05);  // a frame near the target load
  EXPECT_EQ(r.joints, 0);
  EXPECT_LT(r.l2_xx, 0.05);
  EXPECT_LT(r.l2_yy, 0.05);
  EXPECT_LT(std::abs(r.centre_xx), 0.05);
  EXPECT_LT(std::abs(r.centre_yy), 0.05);
  fs::remove_all(dir);
}
