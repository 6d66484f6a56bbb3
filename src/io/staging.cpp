#include "io/staging.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "core/error.hpp"

namespace dspdem {
namespace fs = std::filesystem;

namespace {
// The pid in a staging folder's name; 0 for another folder.
long staging_pid(const fs::path& dir) {
  const std::string name = dir.filename().string();
  if (name.rfind(".staging-", 0) != 0) return 0;
  return std::strtol(name.c_str() + 9, nullptr, 10);
}
}  // namespace

bool left_by_killed_run(const std::string& dir) {
  const long pid = staging_pid(fs::path(dir));
  if (pid <= 0 || pid == static_cast<long>(getpid())) return false;
  const int fd = ::open((fs::path(dir) / ".lock").c_str(), O_RDWR | O_CLOEXEC);
  if (fd >= 0) {
    const int r = flock(fd, LOCK_EX | LOCK_NB);
    const int err = errno;
    ::close(fd);                           // lets go of the lock if it was taken here
    if (r == 0) return true;               // nobody holds it: its run is gone
    if (err == EWOULDBLOCK) return false;  // its run holds it
  }
  // No lock file (a file system without flock): by the pid, which another PID namespace or a
  // pid handed out again can mislead.
  return kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH;
}

Staging::Staging(const std::string& out_dir) : Staging(out_dir, static_cast<long>(getpid()), true) {}

Staging::Staging(const std::string& out_dir, long id, bool owner) : out_(out_dir), owner_(owner) {
  stage_ = (fs::path(out_) / fmt::format(".staging-{}", id)).string();
  if (!owner) return;
  std::error_code ec;
  fs::create_directories(out_, ec);
  DSPDEM_CHECK(!ec && fs::is_directory(out_), "output directory '{}' cannot be created: {}", out_, ec.message());
  // A folder of this name is a killed run's whose pid this process has been given again (pids
  // repeat, in a container started anew): its checkpoint may be what this run restarts from,
  // so it is moved aside, not emptied.
  if (fs::exists(stage_, ec)) {
    for (aside_ = 1; fs::exists(stage_ + "." + std::to_string(aside_), ec); ++aside_) {
    }
    fs::rename(stage_, stage_ + "." + std::to_string(aside_), ec);
    DSPDEM_CHECK(!ec, "cannot move the earlier staging folder '{}' aside: {}", stage_, ec.message());
  }
  fs::create_directories(stage_, ec);
  DSPDEM_CHECK(!ec, "cannot create staging folder '{}': {}", stage_, ec.message());
  // Locked under another name, then renamed: no one sees a .lock that is not held. Closed on
  // exec, so that a process this one starts (a sweep's run) does not hold it on after this one
  // ends. Where flock fails there is no lock file, and left_by_killed_run goes by the pid.
  const std::string tmp = stage_ + "/.lock.tmp";
  lock_fd_ = ::open(tmp.c_str(), O_CREAT | O_RDWR | O_CLOEXEC, 0644);
  if (lock_fd_ >= 0 &&
      (flock(lock_fd_, LOCK_EX | LOCK_NB) != 0 || ::rename(tmp.c_str(), (stage_ + "/.lock").c_str()))) {
    ::close(lock_fd_);
    lock_fd_ = -1;
    ::unlink(tmp.c_str());
  }
}

Staging::~Staging() {
  if (done_ || !owner_) return;
  unlock();
  std::error_code ec;
  fs::remove_all(stage_, ec);
}

void Staging::unlock() {
  if (lock_fd_ < 0) return;
  ::unlink((stage_ + "/.lock").c_str());
  ::close(lock_fd_);
  lock_fd_ = -1;
}

void Staging::commit() {
  std::vector<fs::path> old;
  for (const auto& entry : fs::directory_iterator(stage_)) {
    if (entry.path().filename() == ".lock") continue;  // held until the outputs are in place
    const fs::path dst = fs::path(out_) / entry.path().filename();
    if (fs::exists(dst)) {
      const fs::path aside = fs::path(out_) / (".old-" + entry.path().filename().string());
      fs::remove_all(aside);
      fs::rename(dst, aside);
      old.push_back(aside);
    }
    fs::rename(entry.path(), dst);
  }
  for (const auto& p : old) fs::remove_all(p);
  unlock();
  fs::remove_all(stage_);
  // A successful run supersedes an earlier failure's or interruption's partial outputs, and
  // the staging folders of earlier runs that were killed (their process gone).
  fs::remove_all(fs::path(out_) / "failed_run");
  fs::remove_all(fs::path(out_) / "interrupted_run");
  std::error_code ec;
  for (fs::directory_iterator it(out_, ec), end; !ec && it != end; it.increment(ec)) {
    const bool mine = staging_pid(it->path()) == static_cast<long>(getpid());  // moved aside by this run
    if (mine || left_by_killed_run(it->path().string())) fs::remove_all(it->path(), ec);
  }
  done_ = true;
}

std::string Staging::keep_as(const std::string& name) {
  if (!owner_) return stage_;  // only the process that made the folder moves it
  const fs::path dst = fs::path(out_) / name;
  unlock();
  fs::remove_all(dst);
  fs::rename(stage_, dst);
  done_ = true;
  return dst.string();
}

void write_file_atomic(const std::string& path, const std::string& text) {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream f(tmp, std::ios::binary);
    DSPDEM_CHECK(f.good(), "cannot write '{}'", tmp);
    f << text;
    f.flush();
    DSPDEM_CHECK(f.good(), "error while writing '{}'", tmp);
  }
  fs::rename(tmp, path);
}

}  // namespace dspdem
