// summary.json: what `dspdem run` writes, every report reads back through the same struct.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "core/error.hpp"
#include "core/file.hpp"
#include "io/run_summary.hpp"

using namespace dspdem;
namespace fs = std::filesystem;

TEST(RunSummary, RoundTripKeepsEveryFieldAndNonFiniteEnergies) {
  RunSummary s;
  s.case_name = "disc \"quoted\"", s.case_file = "/a/b.toml", s.status = "failed", s.message = "line1\nline2";
  s.build = "0.1.0 abc GNU 12.2.0 Release exe 0123abcd";
  s.steps = 123456789012, s.dt = 3.0303e-8, s.dt_start = 4.1e-8, s.dt_critical = 3.367e-8, s.dt_limiter = "joint";
  s.dt_limiting_element = 42, s.t_end = 2.5e-3, s.wall_s = 12.5, s.threads = 2, s.processes = 4;
  s.nodes = 52328, s.elements = 13082, s.frames = 31, s.joints = 24779, s.broken_joints = 17;
  s.joint_added_compliance = 0.0175, s.crack_area = 0.0123, s.fragments = 3, s.total_mass = 2.85;
  s.largest_fragment_masses = {1.4, 1.3, 0.15};
  s.monitor_joints = {{"contact_cracks", 200}, {"upper_half_cracks", 2100}};
  s.element_steps_per_s = 4.5e6;
  s.energy.kinetic = 1.5, s.energy.fracture_I = 0.25, s.energy.kick = 3.5e-7, s.energy.balance_error = NAN;
  s.born_split = {7, 0.125, 0.4}, s.born_unseen = {1, 2.5, 0.3}, s.born_wall = {0, 0.0, 0.0};
  const fs::path p = fs::temp_directory_path() / "dspdem_summary_roundtrip.json";
  write_run_summary(p.string(), s);
  const RunSummary r = read_run_summary(p.string());
  EXPECT_EQ(r.case_name, s.case_name);
  EXPECT_EQ(r.message, s.message);
  EXPECT_EQ(r.build, s.build);
  EXPECT_EQ(r.steps, s.steps);
  EXPECT_EQ(r.dt, s.dt);  // 17 significant digits: exact
  EXPECT_EQ(r.dt_start, s.dt_start);
  EXPECT_EQ(r.dt_limiter, "joint");
  EXPECT_EQ(r.joints, 24779);
  EXPECT_EQ(r.processes, 4);
  EXPECT_EQ(r.largest_fragment_masses, s.largest_fragment_masses);
  EXPECT_EQ(r.monitor_joints, s.monitor_joints);
  EXPECT_EQ(r.energy.fracture_I, 0.25);
  EXPECT_TRUE(std::isnan(r.energy.balance_error));  // written as null, never as "nan"
  EXPECT_EQ(r.energy.kick, 3.5e-7);
  EXPECT_EQ(r.born_split.pairs, 7);
  EXPECT_EQ(r.born_split.energy, 0.125);
  EXPECT_EQ(r.born_split.max_ratio, 0.4);
  EXPECT_EQ(r.born_unseen.pairs, 1);
  EXPECT_EQ(r.born_unseen.energy, 2.5);
  EXPECT_EQ(r.born_wall.pairs, 0);
}

// A run without contact, or a run folder written before the pairs first found overlapping
// were recorded, has no such object: they read as unknown. A half-written one is named.
TEST(RunSummary, PairsFoundOverlappingAreUnknownWhenNotWrittenAndNamedWhenBroken) {
  RunSummary s;
  s.case_name = "c", s.status = "completed";
  const fs::path p = fs::temp_directory_path() / "dspdem_summary_born.json";
  write_run_summary(p.string(), s);
  RunSummary r = read_run_summary(p.string());
  EXPECT_EQ(r.born_split.pairs, -1);
  EXPECT_TRUE(std::isnan(r.born_unseen.energy));
  EXPECT_EQ(r.born_wall.pairs, -1);
  std::string text = read_file_if(p.string()).value();
  ASSERT_EQ(text.find("contacts_born_overlapping"), std::string::npos);
  const std::size_t end = text.rfind('}');
  text.insert(end, ", \"contacts_born_overlapping\": {\"split\": {\"pairs\": 1, \"energy\": 2.0, \"max_ratio\": 0.1}}");
  std::ofstream(p) << text;
  try {
    read_run_summary(p.string());
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("contacts_born_overlapping.unseen"), std::string::npos) << e.what();
  }
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

// Joint monitors' box sizes: absent without such monitors (and in older folders), a wrong
// type named.
TEST(RunSummary, MonitorJointsAreOptionalAndCheckedWhenThere) {
  RunSummary s;
  s.case_name = "c", s.status = "completed";
  const fs::path p = fs::temp_directory_path() / "dspdem_summary_monitor_joints.json";
  write_run_summary(p.string(), s);
  std::string text = read_file_if(p.string()).value();
  EXPECT_EQ(text.find("monitor_joints"), std::string::npos) << "written only when there are joint monitors";
  EXPECT_TRUE(read_run_summary(p.string()).monitor_joints.empty());
  const std::size_t at = text.find("\"fragments\"");
  ASSERT_NE(at, std::string::npos);
  text.insert(at, "\"monitor_joints\": {\"low\": 2.5},\n  ");
  std::ofstream(p) << text;
  try {
    read_run_summary(p.string());
    ADD_FAILURE() << "a non-integer joint count was read";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("monitor_joints 'low'"), std::string::npos) << e.what();
  }
}

// Run folders written before the ledger's kick term was recorded have no "kick": it reads
// as unknown, and the rest of the summary as written.
TEST(RunSummary, AFolderWithoutTheKickTermReadsItAsUnknown) {
  RunSummary s;
  s.case_name = "c", s.status = "completed";
  s.energy.kick = 0.5, s.energy.balance_error = 2e-5;
  const fs::path p = fs::temp_directory_path() / "dspdem_summary_kick.json";
  write_run_summary(p.string(), s);
  std::string text = read_file_if(p.string()).value();
  const std::string key = "\"kick\": 0.5,";
  const std::size_t at = text.find(key);
  ASSERT_NE(at, std::string::npos) << text;
  text.erase(at, key.size());
  std::ofstream(p) << text;
  const RunSummary r = read_run_summary(p.string());
  EXPECT_TRUE(std::isnan(r.energy.kick));
  EXPECT_EQ(r.energy.balance_error, 2e-5);
}
