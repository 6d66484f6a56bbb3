// The report document builder: links relative to the report wherever the run is, tables
// that refuse ragged rows, Markdown in the order it was built.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/error.hpp"
#include "report/document.hpp"

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

TEST(Document, ARaggedTableRowIsAnError) {
  report::Document d("/tmp", "/tmp/run");
  EXPECT_THROW(d.table({"a", "b"}, {{"1"}}), Error);
}
