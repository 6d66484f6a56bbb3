// An earlier report whose runs a new report has begun to replace is marked outdated: under its
// title, its text otherwise kept, in report.md, report.html and headline.json together; once
// (the first run replaced is the one named); and nothing is made where there is no report. A
// run has replaced what was in its folder when another summary.json or no derived files are there.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <string>

#include "core/file.hpp"
#include "io/staging.hpp"
#include "report/document.hpp"
#include "report/headline.hpp"
#include "report/outdated_report.hpp"

namespace fs = std::filesystem;
using namespace dspdem::report;

namespace {

class OutdatedReport : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("dspdem_outdated_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_ / "run");
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string get(const char* f) const { return dspdem::read_file((dir_ / f).string()); }
  fs::path dir_;
};

TEST_F(OutdatedReport, MarksTheEarlierReportUnderItsTitleOnceKeepingItsText) {
  Document doc(dir_.string(), (dir_ / "run").string());
  doc.title("A scene").para("The strength is 2.5 MPa.").section("Runs").para("One run.");
  doc.headline().scene = "scene", doc.headline().title = "A scene", doc.headline().summary = "What was run.";
  doc.write();
  const std::string md = get("report.md");
  ASSERT_EQ(md.rfind("# A scene\n\n", 0), 0U);

  mark_report_outdated(dir_.string(), (dir_ / "speeds" / "v5").string());
  const std::string marked = get("report.md");
  const std::string head =
      "# A scene\n\n> **Outdated.** A report started into this folder has replaced a run this text "
      "describes (`speeds/v5/`, at ";
  ASSERT_EQ(marked.rfind(head, 0), 0U) << marked;
  // The mark is one paragraph; below it, the earlier text as it was.
  const std::size_t end = marked.find("\n\n", head.size());
  ASSERT_NE(end, std::string::npos);
  EXPECT_EQ(marked.substr(end + 1), md.substr(std::string("# A scene\n").size()));
  EXPECT_NE(marked.find("finishes it.\n\n"), std::string::npos) << marked;
  // report.html is the marked text rendered; the headline's summary begins with the mark.
  const std::string html = get("report.html");
  EXPECT_NE(html.find("<strong>Outdated.</strong>"), std::string::npos) << html;
  EXPECT_LT(html.find("<strong>Outdated.</strong>"), html.find("The strength is 2.5 MPa."));
  const Headline h = read_headline((dir_ / "headline.json").string());
  EXPECT_EQ(h.summary.rfind("**Outdated.** A report started", 0), 0U) << h.summary;
  EXPECT_NE(h.summary.find("What was run."), std::string::npos) << h.summary;

  // A second run replaced: the first one named stays, nothing changes.
  mark_report_outdated(dir_.string(), (dir_ / "speeds" / "v7.5").string());
  EXPECT_EQ(get("report.md"), marked);
  EXPECT_EQ(get("report.html"), html);
}

TEST_F(OutdatedReport, NoReportNoFolderOrATitlelessOne) {
  // No report folder given, or none written there: nothing is made.
  mark_report_outdated("", (dir_ / "run").string());
  mark_report_outdated(dir_.string(), (dir_ / "run").string());
  EXPECT_FALSE(fs::exists(dir_ / "report.md"));
  EXPECT_FALSE(fs::exists(dir_ / "report.html"));
  // A report.md without a title line is marked at its top; without a headline.json none is made.
  dspdem::write_file_atomic((dir_ / "report.md").string(), "Some text.\n");
  mark_report_outdated(dir_.string(), (dir_ / "run").string());
  const std::string marked = get("report.md");
  EXPECT_EQ(marked.rfind("> **Outdated.** A report started into this folder has replaced a run this text describes "
                         "(`run/`, at ",
                         0),
            0U)
      << marked;
  EXPECT_EQ(marked.substr(marked.size() - std::string("\n\nSome text.\n").size()), "\n\nSome text.\n");
  EXPECT_FALSE(fs::exists(dir_ / "headline.json"));
}

TEST_F(OutdatedReport, ARunReplacesAFinishedRunOrDerivedFilesOnlyWhenTheirFilesChange) {
  const std::string run = (dir_ / "run").string(), summary = (dir_ / "run" / "summary.json").string();
  // A fresh place: whatever a run leaves there replaces nothing.
  const RunReplacement fresh(run);
  dspdem::write_file_atomic(summary, "{\"status\": \"completed\"}");
  EXPECT_FALSE(fresh.replaced());
  // A finished run left as it was (kept, or a run that failed or stopped before its commit):
  // not replaced.
  const RunReplacement kept(run);
  EXPECT_FALSE(kept.replaced());
  // Another summary.json committed in its place (a rename over it, as a run's commit does),
  // whatever the content: replaced.
  dspdem::write_file_atomic(summary, "{\"status\": \"completed\"}");
  EXPECT_TRUE(kept.replaced());
  // A commit cut short (run.pvd left, its summary.json gone): the next run's replaces it.
  fs::remove(summary);
  dspdem::write_file_atomic((dir_ / "run" / "run.pvd").string(), "<VTKFile/>");
  const RunReplacement cut(run);
  EXPECT_FALSE(cut.replaced());
  dspdem::write_file_atomic(summary, "{}");
  EXPECT_TRUE(cut.replaced());
  // What an earlier report derived there from another run (--from-run), emptied by the run
  // before it starts: replaced as soon as it is gone, before any summary.
  const std::string place = (dir_ / "place").string();
  fs::create_directories(place);
  dspdem::write_file_atomic((dir_ / "place" / "derived_from").string(), "/elsewhere/run\n");
  const RunReplacement derived(place);
  EXPECT_FALSE(derived.replaced());
  fs::remove(dir_ / "place" / "derived_from");
  EXPECT_TRUE(derived.replaced());
}

TEST_F(OutdatedReport, AnUnreadableHeadlineLeavesItButMarksTheReport) {
  dspdem::write_file_atomic((dir_ / "report.md").string(), "# A scene\n\nText.\n");
  dspdem::write_file_atomic((dir_ / "headline.json").string(), "{ not json");
  mark_report_outdated(dir_.string(), (dir_ / "run").string());
  EXPECT_NE(get("report.md").find("> **Outdated.**"), std::string::npos);
  EXPECT_NE(get("report.html").find("<strong>Outdated.</strong>"), std::string::npos);
  EXPECT_EQ(get("headline.json"), "{ not json");
}

}  // namespace
