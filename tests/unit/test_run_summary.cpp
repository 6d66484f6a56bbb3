// summary.json: what `dspdem run` writes, every report reads back through the same struct.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "core/error.hpp"
#include "io/run_summary.hpp"

using namespace dspdem;
namespace fs = std::filesystem;

TEST(RunSummary, RoundTripKeepsEveryFieldAndNonFiniteEnergies) {
  RunSummary s;
  s.case_name = "disc \"quoted\"", s.case_file = "/a/b.toml", s.status = "failed", s.message = "line1\nline2";
  s.steps = 123456789012, s.dt = 3.0303e-8, s.dt_start = 4.1e-8, s.dt_critical = 3.367e-8, s.dt_limiter = "joint";
  s.dt_limiting_element = 42, s.t_end = 2.5e-3, s.wall_s = 12.5, s.threads = 2, s.processes = 4;
  s.nodes = 52328, s.elements = 13082, s.frames = 31, s.joints = 24779, s.broken_joints = 17;
  s.joint_added_compliance = 0.0175, s.crack_area = 0.0123, s.fragments = 3, s.total_mass = 2.85;
  s.largest_fragment_masses = {1.4, 1.3, 0.15};
  s.element_steps_per_s = 4.5e6;
  s.energy.kinetic = 1.5, s.energy.fracture_I = 0.25, s.energy.balance_error = NAN;
  const fs::path p = fs::temp_directory_path() / "dspdem_summary_roundtrip.json";
  write_run_summary(p.string(), s);
  const RunSummary r = read_run_summary(p.string());
  EXPECT_EQ(r.case_name, s.case_name);
  EXPECT_EQ(r.message, s.message);
  EXPECT_EQ(r.steps, s.steps);
  EXPECT_EQ(r.dt, s.dt);  // 17 significant digits: exact
  EXPECT_EQ(r.dt_start, s.dt_start);
  EXPECT_EQ(r.dt_limiter, "joint");
  EXPECT_EQ(r.joints, 24779);
  EXPECT_EQ(r.processes, 4);
  EXPECT_EQ(r.largest_fragment_masses, s.largest_fragment_masses);
  EXPECT_EQ(r.energy.fracture_I, 0.25);
  EXPECT_TRUE(std::isnan(r.energy.balance_error));  // written as null, never as "nan"
}

TEST(RunSummary, AMissingKeyOrBrokenFileIsNamed) {
  const fs::path p = fs::temp_directory_path() / "dspdem_summary_bad.json";
  std::ofstream(p) << "{\"case\": \"x\"}";
  try {
    read_run_summary(p.string());
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("dspdem_summary_bad.json"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("case_file"), std::string::npos) << e.what();
  }
  std::ofstream(p) << "{\"case\": ";
  EXPECT_THROW(read_run_summary(p.string()), Error);
  EXPECT_THROW(read_run_summary((fs::temp_directory_path() / "dspdem_no_such_summary.json").string()), Error);
}
