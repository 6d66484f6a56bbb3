#include "core/folder_lock.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <vector>

#include "core/error.hpp"
#include "core/log.hpp"

namespace dspdem {

namespace fs = std::filesystem;

FolderLock::FolderLock(const std::string& dir, const std::string& file, const std::string& what, NoFlock no_flock)
    : dir_(fs::absolute(dir).lexically_normal()), path_((dir_ / file).string()) {
  if (!dir_.has_filename()) dir_ = dir_.parent_path();  // a trailing slash
  // The file is removed by its holder before it lets go, so a process may lock a file that is
  // no longer the one at the path (opened just before the removal): it then tries again on the
  // new one; and the folder with it, when the holder had made it and left it empty. Close on
  // exec: the runs a report starts must not hold its lock on after it ends. Read-only: a lock
  // file a killed report left is taken by a user who may not write it.
  for (int attempt = 0; attempt < 100; ++attempt) {
    // Made a level at a time from the highest one missing, so that only the folders this lock
    // made count as its own (another process may make one of them meanwhile).
    std::vector<fs::path> missing;
    for (fs::path up = dir_; !fs::exists(up) && up != up.root_path(); up = up.parent_path()) missing.push_back(up);
    std::error_code e;
    for (auto level = missing.rbegin(); level != missing.rend() && !e; ++level)
      if (fs::create_directory(*level, e) && made_top_.empty()) made_top_ = *level;
    // A folder above went meanwhile, or one was made and went again while this made it.
    if (e == std::errc::no_such_file_or_directory || e == std::errc::file_exists) continue;
    DSPDEM_CHECK(!e, "cannot make the folder '{}': {}", dir, e.message());
    const int fd = ::open(path_.c_str(), O_CREAT | O_RDONLY | O_CLOEXEC, 0644);
    if (fd < 0 && errno == ENOENT) continue;  // the folder went meanwhile
    if (fd < 0) {
      const int err = errno;
      remove_made();
      fail("cannot open the lock file '{}': {}", path_, std::strerror(err));
    }
    if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
      const int err = errno;
      if (err == EWOULDBLOCK) {
        ::close(fd);
        throw FolderBusy(fmt::format(
            "{}: {} is writing into this folder now (it holds {}); wait for it to end, or give another folder", dir,
            what, path_));
      }
      if (no_flock == NoFlock::warn)
        log::warn("{}: no lock taken ({}): two writers into this folder at once would not be stopped", dir,
                  std::strerror(err));
      fd_ = fd;  // held open all the same, so that the file goes when this lets go, as a held one does
      return;
    }
    struct stat held;     // filled by fstat before it is read
    struct stat at_path;  // and by stat
    if (::fstat(fd, &held) == 0 && ::stat(path_.c_str(), &at_path) == 0 && held.st_ino == at_path.st_ino &&
        held.st_dev == at_path.st_dev) {
      fd_ = fd;
      return;
    }
    ::close(fd);
  }
  remove_made();
  throw FolderBusy(
      fmt::format("{}: the lock file {} kept changing under this process; another process is taking it", dir, path_));
}

FolderLock::~FolderLock() {
  if (fd_ < 0) return;
  ::unlink(path_.c_str());
  ::close(fd_);
  remove_made();
}

void FolderLock::remove_made() const {
  if (made_top_.empty()) return;
  std::error_code e;
  for (fs::path up = dir_; up != up.root_path(); up = up.parent_path()) {
    if (!fs::remove(up, e) || e) return;  // only while empty: stops harmlessly at the first that is not
    if (up == made_top_) return;
  }
}

bool FolderLock::held(const std::string& dir, const std::string& file) {
  const int fd = ::open((fs::path(dir) / file).c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return false;
  const bool busy = ::flock(fd, LOCK_SH | LOCK_NB) != 0 && errno == EWOULDBLOCK;
  ::close(fd);  // lets go of the shared lock, if it was taken
  return busy;
}

}  // namespace dspdem
