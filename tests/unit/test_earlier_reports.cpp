// report --from-run over several earlier reports' folders: which run is taken, that runs of
// another case are refused, and how the sources are named.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "core/error.hpp"
#include "io/run_summary.hpp"
#include "io/staging.hpp"
#include "report/earlier_reports.hpp"
#include "report/run_data.hpp"

using namespace dspdem;
namespace fs = std::filesystem;

namespace {

const std::string kCase = "# Resolved from cases/a.toml (every default filled in)\n[case]\nname = 'a'\nspeed = 5.0\n";

class EarlierReports : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("dspdem_earlier_reports_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  // A run folder `root`/speeds/v5 as a run leaves it: its summary and its resolved case, in
  // the folder when it completed, in failed_run/ or interrupted_run/ inside it when not
  // (io/staging.hpp).
  std::string put_run(const std::string& root, const std::string& resolved, const std::string& build,
                      const std::string& status = "completed") {
    fs::path d = dir_ / root / "speeds" / "v5";
    if (status != "completed") d /= status == "failed" ? failed_folder : interrupted_folder;
    fs::create_directories(d);
    RunSummary s;
    s.status = status, s.build = build, s.message = status == "completed" ? "" : "NaN at step 7";
    write_run_summary((d / "summary.json").string(), s);
    std::ofstream(d / "case.resolved.toml") << resolved;
    return (dir_ / root).string();
  }
  fs::path dir_;
};

}  // namespace

TEST_F(EarlierReports, TheFirstFolderWithTheRunGivesIt) {
  const std::string a = put_run("a", kCase, "build A"), b = put_run("b", kCase, "build B");
  const auto r = report::find_earlier_report_run({b, a}, "speeds/v5", kCase);
  EXPECT_EQ(r.root, b);
  EXPECT_EQ(r.build, "build B");
  EXPECT_EQ(r.dir, (fs::path(b) / "speeds" / "v5").string());
  EXPECT_TRUE(r.error.empty()) << r.error;
  EXPECT_EQ(r.shadowed, 1);  // a's copy, checked and not taken
  // A folder that does not hold it is passed over.
  const std::string empty = (dir_ / "empty").string();
  fs::create_directories(empty);
  EXPECT_EQ(report::find_earlier_report_run({empty, a}, "speeds/v5", kCase).root, a);
  // None holds it: no folder, and no lost run.
  const auto none = report::find_earlier_report_run({a, b}, "speeds/v7.5", kCase);
  EXPECT_TRUE(none.dir.empty());
  EXPECT_TRUE(none.lost_log.empty());
}

TEST_F(EarlierReports, ALogWithoutItsRunIsALostRunUnlessALaterFolderHasIt) {
  const std::string a = (dir_ / "a").string();
  fs::create_directories(dir_ / "a" / "speeds");
  std::ofstream(dir_ / "a" / "speeds" / "v5.log") << "killed\n";
  const auto lost = report::find_earlier_report_run({a}, "speeds/v5", kCase);
  EXPECT_TRUE(lost.dir.empty());
  EXPECT_EQ(lost.lost_log, (dir_ / "a" / "speeds" / "v5.log").string());
  const std::string b = put_run("b", kCase, "build B");
  const auto found = report::find_earlier_report_run({a, b}, "speeds/v5", kCase);
  EXPECT_EQ(found.root, b);
  EXPECT_TRUE(found.lost_log.empty());
}

TEST_F(EarlierReports, ARunOfAnotherCaseIsRefusedNamingTheLineAndTheOriginLineIsNoDifference) {
  std::string other = kCase;
  other.replace(other.find("5.0"), 3, "7.5");
  const std::string a = put_run("a", other, "build A");
  try {
    report::find_earlier_report_run({a}, "speeds/v5", kCase);
    FAIL() << "a run of another case was taken";
  } catch (const Error& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find((fs::path(a) / "speeds" / "v5").string()), std::string::npos) << m;
    EXPECT_NE(m.find("line 4: 'speed = 7.5' then, 'speed = 5.0' now"), std::string::npos) << m;
  }
  // The first comment names the case file as it was given: another path is the same case.
  std::string moved = kCase;
  moved.replace(moved.find("cases/a.toml"), 12, "/abs/cases/a.toml");
  const std::string b = put_run("b", moved, "build B");
  EXPECT_EQ(report::find_earlier_report_run({b}, "speeds/v5", kCase).root, b);
}

TEST_F(EarlierReports, AFailedOrStoppedRunGivesItsReasonUnlessAnotherFolderCompletedIt) {
  const std::string a = put_run("a", kCase, "build A", "failed");
  std::ofstream(dir_ / "a" / "speeds" / "v5.log") << "NaN\n";
  const auto r = report::find_earlier_report_run({a}, "speeds/v5", kCase);
  EXPECT_TRUE(r.dir.empty());
  EXPECT_NE(r.error.find("v5 failed: NaN at step 7"), std::string::npos) << r.error;
  EXPECT_EQ(r.lost_log, (dir_ / "a" / "speeds" / "v5.log").string());
  const std::string b = put_run("b", kCase, "build B", "interrupted");
  EXPECT_NE(report::find_earlier_report_run({b}, "speeds/v5", kCase).error.find("v5 was interrupted"),
            std::string::npos);
  // A completed run in a later folder is taken over the failed one.
  const std::string c = put_run("c", kCase, "build C");
  const auto done = report::find_earlier_report_run({a, b, c}, "speeds/v5", kCase);
  EXPECT_EQ(done.root, c);
  EXPECT_TRUE(done.error.empty()) << done.error;
  // The failed run is of its case too: one of another case is refused there as well.
  std::string other = kCase;
  other.replace(other.find("5.0"), 3, "7.5");
  const std::string d = put_run("d", other, "build D", "failed");
  EXPECT_THROW(report::find_earlier_report_run({d, c}, "speeds/v5", kCase), Error);
}

TEST_F(EarlierReports, SourcesNameEachFolderAndEachBuildWithItsRuns) {
  const std::vector<report::EarlierReportRun> one = {
      {"/r/a/speeds/v5", "/r/a", "B1", "", ""}, {"/r/a/speeds/v7.5", "/r/a", "B1", "", ""}, {"", "", "", "", "x.log"}};
  EXPECT_EQ(report::earlier_report_sources(one, "/r/out"), "`../a` (2 runs), made by one build of dspdem (B1)");
  const std::vector<report::EarlierReportRun> two = {{"/r/b/speeds/v5", "/r/b", "B2", "", ""},
                                                     {"/r/a/speeds/v5", "/r/a", "B1", "", ""},
                                                     {"/r/a/speeds/v7.5", "/r/a", "B1", "", ""}};
  EXPECT_EQ(report::earlier_report_sources(two, "/r/out"),
            "`../b` (1 run), `../a` (2 runs), made by 2 builds of dspdem: B2 (1 run), B1 (2 runs)");
  EXPECT_EQ(report::earlier_report_sources({}, "/r/out"), "");
  // A run also in a later folder is named; a summary without a build says so.
  std::vector<report::EarlierReportRun> again = one;
  again[0].shadowed = 2, again[0].build = again[1].build = "";
  EXPECT_EQ(report::earlier_report_sources(again, "/r/out"),
            "`../a` (2 runs), made by one build of dspdem (not recorded); 1 run also in a later folder, taken from the "
            "first");
}

TEST_F(EarlierReports, FoldersOfARangeOfRunsAreThoseOfTheReportsThatHoldThem) {
  // The sweep's own speeds (runs 0-1) from b then a; the turned meshes' (2-3) from a alone,
  // one of them lost; without --from-run the report's own folder.
  const std::vector<report::EarlierReportRun> runs = {{"/r/b/speeds/v5", "/r/b", "B", "", ""},
                                                      {"/r/a/speeds/v7.5", "/r/a", "B", "", ""},
                                                      {"/r/a/orientations/v5_o1", "/r/a", "B", "", ""},
                                                      {"", "", "", "", "/r/c/orientations/v7.5_o1.log"}};
  EXPECT_EQ(report::earlier_report_folders(runs, 0, 2, "speeds", "/r/out"), "`../b/speeds/`, `../a/speeds/`");
  EXPECT_EQ(report::earlier_report_folders(runs, 2, 4, "orientations", "/r/out"), "`../a/orientations/`");
  EXPECT_EQ(report::earlier_report_folders(runs, 3, 4, "orientations", "/r/out"), "");
  EXPECT_EQ(report::earlier_report_folders({}, 0, 2, "speeds", "/r/out"), "`speeds/`");
  // A folder given as . (the report's own, --from-run .).
  EXPECT_EQ(report::earlier_report_folders({{"./speeds/v5", ".", "B", "", ""}}, 0, 1, "speeds", "."), "`speeds/`");
}

TEST_F(EarlierReports, ARunsRecordIsItsSummaryAndItsCaseAsRun) {
  // A folder without summary.json holds no run; one without its case is read, the case
  // missing (what each reader then makes of that is its own: --from-run refuses it).
  const std::string root = put_run("a", kCase, "build A");
  const auto r = report::run_record(root + "/speeds/v5");
  ASSERT_TRUE(r.has_value());
  EXPECT_EQ(r->summary.build, "build A");
  ASSERT_TRUE(r->resolved.has_value());
  EXPECT_EQ(*r->resolved, kCase);
  EXPECT_FALSE(report::run_record(root + "/speeds").has_value());
  fs::remove(fs::path(root) / "speeds" / "v5" / "case.resolved.toml");
  const auto no_case = report::run_record(root + "/speeds/v5");
  ASSERT_TRUE(no_case.has_value());
  EXPECT_FALSE(no_case->resolved.has_value());
  EXPECT_THROW(report::find_earlier_report_run({root}, "speeds/v5", kCase), Error);
  // The log a report's run process writes beside its folder, where a lost run is looked for.
  EXPECT_EQ(report::run_log(root + "/speeds/v5"), root + "/speeds/v5.log");
}
