// core/folder_lock: one writer at a time for a folder (a report's), taken on a lock file the
// kernel drops when the holder ends; the second is refused with the folder named.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <optional>
#include <string>

#include "core/error.hpp"
#include "core/folder_lock.hpp"

using dspdem::Error;
using dspdem::FolderLock;
namespace fs = std::filesystem;

namespace {
fs::path scratch() {
  const fs::path d = fs::temp_directory_path() / ("dspdem_folder_lock_" + std::to_string(::getpid()) + "_" +
                                                  ::testing::UnitTest::GetInstance()->current_test_info()->name());
  fs::remove_all(d);
  return d;
}
}  // namespace

TEST(FolderLock, ASecondHolderIsRefusedUntilTheFirstLetsGo) {
  const fs::path d = scratch() / "rep";
  std::optional<FolderLock> first;
  first.emplace(d.string(), ".report.lock", "another report");
  EXPECT_TRUE(fs::exists(d / ".report.lock"));
  // flock locks belong to the open file, so a second open in this process conflicts as another
  // process's would.
  try {
    FolderLock second(d.string(), ".report.lock", "another report");
    ADD_FAILURE() << "a second lock on a held folder was taken";
  } catch (const Error& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find(d.string()), std::string::npos) << m;
    EXPECT_NE(m.find("another report is writing into this folder now"), std::string::npos) << m;
  }
  std::ofstream(d / "report.md") << "written";
  first.reset();
  EXPECT_FALSE(fs::exists(d / ".report.lock"));
  EXPECT_TRUE(fs::exists(d / "report.md"));  // a folder with files stays
  { FolderLock again(d.string(), ".report.lock", "another report"); }
  EXPECT_TRUE(fs::exists(d / "report.md"));
  fs::remove_all(d.parent_path());
}

TEST(FolderLock, AFolderItMadeAndLeftEmptyGoesWithIt) {
  const fs::path base = scratch();
  fs::create_directories(base / "kept");
  { FolderLock made((base / "new").string(), ".report.lock", "another report"); }
  EXPECT_FALSE(fs::exists(base / "new"));  // a report refused at once leaves no folder
  { FolderLock kept((base / "kept").string(), ".report.lock", "another report"); }
  EXPECT_TRUE(fs::exists(base / "kept"));  // one that was there stays, empty as it was
  fs::remove_all(base);
}
