// A report written again into its folder sets the earlier report's optional files aside:
// dropped once the new report is written, put back (and the new ones removed) when it stops
// first, also after a report killed outright left them aside; none lost when one cannot be
// set aside.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "core/error.hpp"
#include "report/files_aside.hpp"

using dspdem::report::FilesAside;
namespace fs = std::filesystem;

namespace {

class FilesAsideTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("dspdem_files_aside_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_ / "images");
    put("a.csv", "earlier a"), put("images/b.png", "earlier b"), put("kept.csv", "not listed");
  }
  void TearDown() override { fs::remove_all(dir_); }
  void put(const std::string& f, const std::string& text) const { std::ofstream(dir_ / f) << text; }
  std::string get(const std::string& f) const {
    if (!fs::exists(dir_ / f)) return "(none)";
    std::ostringstream s;
    s << std::ifstream(dir_ / f).rdbuf();
    return s.str();
  }
  const std::vector<std::string> listed_ = {"a.csv", "images/b.png", "c.csv"};
  fs::path dir_;
};

}  // namespace

TEST_F(FilesAsideTest, AWrittenReportDropsTheEarlierFilesItDidNotWriteAgain) {
  {
    FilesAside aside(dir_.string(), listed_);
    EXPECT_EQ(get("a.csv"), "(none)");  // aside while the report writes
    put("a.csv", "new a"), put("c.csv", "new c");
    aside.drop();
  }
  EXPECT_EQ(get("a.csv"), "new a");
  EXPECT_EQ(get("c.csv"), "new c");
  EXPECT_EQ(get("images/b.png"), "(none)");  // the earlier report's, not written again
  EXPECT_EQ(get("kept.csv"), "not listed");
  EXPECT_FALSE(fs::exists(dir_ / ".files_aside"));
}

TEST_F(FilesAsideTest, AReportThatStopsLeavesTheEarlierFilesAsTheyWere) {
  try {
    FilesAside aside(dir_.string(), listed_);
    put("a.csv", "new a"), put("c.csv", "new c");
    throw std::runtime_error("stopped");
  } catch (const std::runtime_error&) {
  }
  EXPECT_EQ(get("a.csv"), "earlier a");
  EXPECT_EQ(get("images/b.png"), "earlier b");
  EXPECT_EQ(get("c.csv"), "(none)");  // the earlier report had none
  EXPECT_EQ(get("kept.csv"), "not listed");
  EXPECT_FALSE(fs::exists(dir_ / ".files_aside"));
}

TEST_F(FilesAsideTest, FilesAReportKilledOutrightLeftAsideArePutBackFirst) {
  // As a killed report leaves it: the earlier files aside, its own half-written ones in place.
  fs::create_directories(dir_ / ".files_aside" / "images");
  for (const char* f : {"a.csv", "images/b.png"}) fs::rename(dir_ / f, dir_ / ".files_aside" / f);
  put("a.csv", "half written"), put("c.csv", "half written");
  { FilesAside aside(dir_.string(), listed_); }  // stops too, without a report
  EXPECT_EQ(get("a.csv"), "earlier a");
  EXPECT_EQ(get("images/b.png"), "earlier b");
  // Not set aside by the killed report, so not told from one it had not reached: left.
  EXPECT_EQ(get("c.csv"), "half written");
  EXPECT_FALSE(fs::exists(dir_ / ".files_aside"));
}

TEST_F(FilesAsideTest, FilesAsideAreStillPutBackWhenTheirFolderWasRemovedMeanwhile) {
  fs::create_directories(dir_ / ".files_aside" / "images");
  fs::rename(dir_ / "images/b.png", dir_ / ".files_aside/images/b.png");
  fs::remove_all(dir_ / "images");
  { FilesAside aside(dir_.string(), listed_); }
  EXPECT_EQ(get("images/b.png"), "earlier b");
  EXPECT_FALSE(fs::exists(dir_ / ".files_aside"));
}

TEST_F(FilesAsideTest, FilesThatCannotBeSetAsideAreRefusedWithTheOthersPutBack) {
  // The folder `sub` after its own file: the file goes aside into .files_aside/sub/, and the
  // folder then cannot go onto that one. Nothing of the earlier report is lost.
  fs::create_directories(dir_ / "sub");
  put("sub/f.csv", "earlier f");
  EXPECT_THROW(FilesAside(dir_.string(), {"a.csv", "sub/f.csv", "sub"}), dspdem::Error);
  EXPECT_EQ(get("a.csv"), "earlier a");
  EXPECT_EQ(get("sub/f.csv"), "earlier f");
  EXPECT_FALSE(fs::exists(dir_ / ".files_aside"));
}
