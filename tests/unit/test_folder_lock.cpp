// core/folder_lock: one writer at a time for a folder (a report's), taken on a lock file the
// kernel drops when the holder ends; the second is refused with the folder named.
#include <gtest/gtest.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <thread>
#include <vector>

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

// A file system without flock (some network mounts), stood in for: this executable's flock is
// the one FolderLock calls, and it fails as such a file system does while the flag is set.
std::atomic<bool> no_flock{false};
}  // namespace

extern "C" int flock(int fd, int operation) {
  if (no_flock) {
    errno = ENOLCK;
    return -1;
  }
  return static_cast<int>(::syscall(SYS_flock, fd, operation));
}

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
  } catch (const dspdem::FolderBusy& e) {  // told from a folder that cannot be made
    const std::string m = e.what();
    EXPECT_NE(m.find(d.string()), std::string::npos) << m;
    EXPECT_NE(m.find("another report is writing into this folder now"), std::string::npos) << m;
  }
  EXPECT_TRUE(FolderLock::held(d.string(), ".report.lock"));
  std::ofstream(d / "report.md") << "written";
  first.reset();
  EXPECT_FALSE(FolderLock::held(d.string(), ".report.lock"));
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
  // Nor the folders made above it, up to the first that was there.
  { FolderLock made((base / "kept" / "x" / "y" / "z").string(), ".report.lock", "another report"); }
  EXPECT_FALSE(fs::exists(base / "kept" / "x"));
  EXPECT_TRUE(fs::exists(base / "kept"));
  // Named through '..' and with a trailing slash: the same folders, and they go as well.
  { FolderLock made((base / "kept" / "x" / ".." / "w" / "v" / "").string(), ".report.lock", "another report"); }
  EXPECT_FALSE(fs::exists(base / "kept" / "w"));
  EXPECT_FALSE(fs::exists(base / "kept" / "x"));
  {
    FolderLock made((base / "kept" / "x" / "y").string(), ".report.lock", "another report");
    std::ofstream(base / "kept" / "x" / "mine.txt") << "written meanwhile";
  }
  EXPECT_FALSE(fs::exists(base / "kept" / "x" / "y"));
  EXPECT_TRUE(fs::exists(base / "kept" / "x" / "mine.txt"));  // a folder with files stays
  fs::remove_all(base / "kept" / "x");
  { FolderLock kept((base / "kept").string(), ".report.lock", "another report"); }
  EXPECT_TRUE(fs::exists(base / "kept"));  // one that was there stays, empty as it was
  fs::remove_all(base);
}

TEST(FolderLock, NeverTwoHoldersWhileManyTakeAndLetGo) {
  // The holder removes the lock file before it lets go, and the folder when it made it: a
  // taker that opened the old file, or whose folder went, must try again rather than hold a
  // lock on a file no longer at the path beside the next holder. Threads stand in for
  // processes (flock locks belong to the open file). A taker refused because another holds
  // the lock tries again; none may ever find another holding it at the same time.
  const fs::path base = scratch();
  fs::create_directories(base);
  const std::string d = (base / "rep").string();  // made and removed again and again
  std::atomic<int> holding{0}, most{0}, taken{0};
  std::vector<std::thread> takers;
  for (int t = 0; t < 4; ++t)
    takers.emplace_back([&] {
      for (int got = 0; got < 300;) {
        try {
          const FolderLock lock(d, ".report.lock", "another taker");
          const int now = ++holding;
          int seen = most.load();
          while (now > seen && !most.compare_exchange_weak(seen, now)) {
          }
          std::this_thread::yield();
          --holding;
          ++got;
          ++taken;
        } catch (const Error& e) {
          if (std::string(e.what()).find("is writing into this folder now") == std::string::npos) {
            ADD_FAILURE() << e.what();  // anything else would repeat: fail, not hang
            return;
          }
          std::this_thread::yield();  // held by another: try again
        }
      }
    });
  for (auto& t : takers) t.join();
  EXPECT_EQ(taken.load(), 1200);
  EXPECT_EQ(most.load(), 1);
  fs::remove_all(base);
}

TEST(FolderLock, WithoutFlockItWarnsAndStillRemovesItsFile) {
  const fs::path d = scratch() / "nfs";
  struct NoFlock {
    NoFlock() { no_flock = true; }
    ~NoFlock() { no_flock = false; }  // also when a check below throws
  };
  {
    const NoFlock on;
    ::testing::internal::CaptureStderr();
    {
      const FolderLock unlocked(d.string(), ".render.lock", "a render");
      EXPECT_TRUE(fs::exists(d / ".render.lock"));
      // Not held: nothing stops a second writer there. That this is taken shows the failing
      // flock reached FolderLock.
      EXPECT_NO_THROW(FolderLock(d.string(), ".render.lock", "a render", FolderLock::NoFlock::quiet));
    }
    const std::string said = ::testing::internal::GetCapturedStderr();
    EXPECT_NE(said.find(d.string() + ": no lock taken"), std::string::npos) << said;
    EXPECT_EQ(said.find("no lock taken"), said.rfind("no lock taken")) << said;  // the quiet one said nothing
  }
  EXPECT_FALSE(fs::exists(d / ".render.lock"));  // left behind by every render before
  EXPECT_FALSE(fs::exists(d));                   // and the folder it made, now empty
  // With flock back, the same calls pass through to the system's: a held lock refuses a second.
  const FolderLock held(d.string(), ".render.lock", "a render");
  EXPECT_THROW(FolderLock(d.string(), ".render.lock", "a render"), dspdem::FolderBusy);
}
