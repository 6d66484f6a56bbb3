// The report document builder: links relative to the report wherever the run is, tables
// that refuse ragged rows, Markdown in the order it was built.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/error.hpp"
#include "report/document.hpp"
#include "report/headline.hpp"
#include "report/run_data.hpp"
#include "report/site.hpp"

using namespace dspdem;
namespace fs = std::filesystem;

TEST(Document, LinksAreRelativeToTheReportAndTheTextComesInOrder) {
  const fs::path base = fs::temp_directory_path() / "dspdem_document";
  fs::remove_all(base);
  fs::create_directories(base / "rep");
  fs::create_directories(base / "runs/a");
  report::Document d((base / "rep").string(), (base / "runs/a").string());
  d.title("T").section("S").para("p").figures({{"x", "images/x.png"}, {"y", "images/y.png"}});
  d.table({"a", "b"}, {{"1", "2"}});
  EXPECT_EQ(d.text(),
            "# T\n\n## S\n\np\n\n![x](../runs/a/images/x.png)\n![y](../runs/a/images/y.png)\n\n| a | b |\n|---|---|\n| "
            "1 | 2 |\n\n");
  EXPECT_EQ(d.run_link(""), "../runs/a/");
  // A run inside the report's folder (the default DIR/run).
  EXPECT_EQ(report::Document((base / "rep").string(), (base / "rep/run").string()).run_link("s.csv"), "run/s.csv");
  const std::string path = d.write();
  std::ifstream f(path);
  std::stringstream ss;
  ss << f.rdbuf();
  EXPECT_EQ(ss.str(), d.text());
}

TEST(Document, AStepThatFellDuringTheRunIsGivenFirstAndLast) {
  EXPECT_EQ(report::step_text(3e-8, 3e-8), "3e-08 s");
  EXPECT_EQ(report::step_text(0, 3e-8), "3e-08 s");  // a summary without dt_start
  EXPECT_EQ(report::step_text(1.67e-7, 1.36e-7), "1.67e-07 s falling to 1.36e-07 s");
  EXPECT_EQ(report::step_text(1.67e-7, 1.36e-7, ""), "1.67e-07 falling to 1.36e-07");  // a table's cell
}

TEST(Document, ARaggedTableRowIsAnError) {
  report::Document d("/tmp", "/tmp/run");
  EXPECT_THROW(d.table({"a", "b"}, {{"1"}}), Error);
}

namespace {
std::string slurp(const fs::path& p) {
  std::ifstream f(p);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}
}  // namespace

TEST(Document, WritesTheSamePageAsHtmlWithTablesAndPlayableAnimations) {
  const fs::path base = fs::temp_directory_path() / "dspdem_document_html";
  fs::remove_all(base);
  fs::create_directories(base / "run/images/stress");
  for (const char* f : {"run/images/stress.mp4", "run/images/stress.ogv", "run/images/stress/frame_0000.png"})
    std::ofstream(base / f) << "x";
  report::Document d(base.string(), (base / "run").string());
  d.title("Scene <1>").para("Some `code` and **bold**.").table({"a", "b"}, {{"1", "2"}});
  d.animation("stress", "images/stress", "images/stress/frame_0000.png");
  d.animation("cracks", "images/cracks", "images/cracks/frame_0000.png");  // no files: nothing
  d.write();
  const std::string html = slurp(base / "report.html");
  EXPECT_NE(html.find("<title>Scene &lt;1&gt;</title>"), std::string::npos) << html;
  EXPECT_NE(html.find("<table>"), std::string::npos) << "GitHub tables not rendered";
  EXPECT_NE(html.find("<code>code</code>"), std::string::npos);
  EXPECT_NE(html.find("<source src=\"run/images/stress.mp4\" type=\"video/mp4\">"), std::string::npos) << html;
  EXPECT_NE(html.find("<source src=\"run/images/stress.ogv\" type=\"video/ogg\">"), std::string::npos);
  EXPECT_NE(html.find("poster=\"run/images/stress/frame_0000.png\""), std::string::npos);
  EXPECT_EQ(html.find("cracks"), std::string::npos) << "an animation without files was linked";
  EXPECT_EQ(html.find("http"), std::string::npos) << "the page must read offline";
  // No headline given: no headline.json.
  EXPECT_FALSE(fs::exists(base / "headline.json"));
}

TEST(Headline, RoundTripsAndTheSiteListsEveryScene) {
  const fs::path base = fs::temp_directory_path() / "dspdem_site";
  fs::remove_all(base);
  fs::create_directories(base / "reports/a/run/images");
  fs::create_directories(base / "reports/b");
  std::ofstream(base / "reports/a/run/images/x.png") << "x";
  report::Document d((base / "reports/a").string(), (base / "reports/a/run").string());
  d.title("A");
  report::Headline& h = d.headline();
  h.scene = "a", h.title = "Scene A (paper 2.9)", h.summary = "What A is.";
  h.rows = {{"strength", "2.54 MPa", "2.25 MPa | -2 %", "yes", "T.One"}, {"balance", "-", "1e-3", "no", ""}};
  d.thumbnail("x", "images/x.png");
  h.wall_s = 12.5;
  d.write();
  const report::Headline r = report::read_headline((base / "reports/a/headline.json").string());
  EXPECT_EQ(r.scene, "a");
  EXPECT_EQ(r.title, h.title);
  ASSERT_EQ(r.rows.size(), 2u);
  EXPECT_EQ(r.rows[0].dspdem, "2.25 MPa | -2 %");
  EXPECT_EQ(r.rows[1].agrees, "no");
  EXPECT_EQ(r.rows[0].test, "T.One");
  ASSERT_EQ(r.images.size(), 1u);
  EXPECT_EQ(r.images[0].second, "run/images/x.png");
  EXPECT_DOUBLE_EQ(r.wall_s, 12.5);

  report::SiteInfo info;
  info.made_by = "dspdem figures", info.set = "test";
  const report::SiteWritten site = report::write_site({(base / "reports/a").string(), (base / "reports/b").string()},
                                                      (base / "site").string(), info);
  EXPECT_EQ(site.failed, 1u) << "the folder without a headline";
  const std::string html = slurp(site.index);
  EXPECT_NE(html.find("Scene A (paper 2.9)"), std::string::npos);
  EXPECT_NE(html.find("src=\"../reports/a/run/images/x.png\""), std::string::npos) << html;
  EXPECT_NE(html.find("href=\"../reports/a/report.html\""), std::string::npos);
  EXPECT_NE(html.find("<span class=\"no\">no</span>"), std::string::npos);
  // The folder without a headline is listed as failed, not dropped.
  EXPECT_NE(html.find("report failed"), std::string::npos);
  EXPECT_NE(html.find("no headline.json"), std::string::npos);
  const std::string md = slurp(base / "site/index.md");
  EXPECT_NE(md.find("| [Scene A (paper 2.9)](../reports/a/report.md) | strength | 2.54 MPa | 2.25 MPa \\| -2 % | yes | "
                    "`T.One` |"),
            std::string::npos)
      << md;
}

TEST(Headline, ABrokenFileIsNamed) {
  const fs::path p = fs::temp_directory_path() / "dspdem_bad_headline.json";
  std::ofstream(p) << "{\"scene\": 3}";
  try {
    report::read_headline(p.string());
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(p.string()), std::string::npos) << e.what();
  }
}
