#include "io/staging.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <set>
#include <string_view>

#include "core/error.hpp"

namespace dspdem {
namespace fs = std::filesystem;

namespace {
constexpr std::string_view staging_prefix = ".staging-";

// A folder's own name, also when its path ends in a slash.
std::string folder_name(const fs::path& dir) {
  return (dir.has_filename() ? dir : dir.parent_path()).filename().string();
}

// The pid in a staging folder's name; 0 for another folder.
long staging_pid(const fs::path& dir) {
  const std::string name = folder_name(dir);
  if (name.rfind(staging_prefix, 0) != 0) return 0;
  return std::strtol(name.c_str() + staging_prefix.size(), nullptr, 10);
}

// The staging folders whose locks this process holds. Its own are not asked of the lock: where
// flock is emulated by POSIX locks (NFS) a process sees no conflict with itself, and closing
// the probe would let go of its own lock.
std::mutex g_held_mutex;
std::set<std::string> g_held;

std::string held_key(const fs::path& dir) {
  std::error_code ec;
  const fs::path p = fs::weakly_canonical(dir, ec);
  return (ec ? dir : p).lexically_normal().string();
}

bool held_here(const fs::path& dir) {
  const std::lock_guard<std::mutex> guard(g_held_mutex);
  return g_held.count(held_key(dir)) > 0;
}

enum class Lock { Held, Free, None };  // None: no lock file, or no flock on this file system

Lock lock_state(const fs::path& dir) {
  const int fd = ::open((dir / ".lock").c_str(), O_RDWR | O_CLOEXEC);
  if (fd < 0) return Lock::None;
  const int r = flock(fd, LOCK_EX | LOCK_NB);
  const int err = errno;
  ::close(fd);  // lets go of the lock if it was taken here
  if (r == 0) return Lock::Free;
  return err == EWOULDBLOCK ? Lock::Held : Lock::None;
}
}  // namespace

bool is_staging_folder(const std::string& dir) { return folder_name(dir).rfind(staging_prefix, 0) == 0; }

bool is_side_folder(const std::string& dir) { return is_staging_folder(dir) || folder_name(dir) == interrupted_folder; }

std::string side_folder_on_path(const std::string& dir) {
  fs::path up;
  for (const fs::path& part : fs::absolute(dir).lexically_normal()) {
    up /= part;
    if (!part.empty() && (is_side_folder(up.string()) || part == failed_folder)) return up.string();
  }
  return {};
}

bool left_by_killed_run(const std::string& dir) {
  const long pid = staging_pid(fs::path(dir));
  if (pid <= 0 || held_here(dir)) return false;
  switch (lock_state(dir)) {
    case Lock::Held:
      return false;  // its run is at work, in this container or another
    case Lock::Free:
      return true;  // the kernel let go of it: its run is gone
    case Lock::None:
      break;
  }
  // No lock (a file system without flock): by the pid, which a process of another PID namespace
  // can mislead. A folder of this process's pid that it does not hold is an earlier process's
  // (pids repeat, in a container started anew).
  return pid == static_cast<long>(getpid()) || (kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH);
}

Staging::Staging(const std::string& out_dir) : Staging(out_dir, static_cast<long>(getpid()), true) {}

Staging::Staging(const std::string& out_dir, long id, bool owner) : out_(out_dir), owner_(owner) {
  stage_ = (fs::path(out_) / fmt::format("{}{}", staging_prefix, id)).string();
  if (!owner) return;
  std::error_code ec;
  fs::create_directories(out_, ec);
  DSPDEM_CHECK(!ec && fs::is_directory(out_), "output directory '{}' cannot be created: {}", out_, ec.message());
  // A folder of this name is a killed run's whose pid this process has been given again (pids
  // repeat, in a container started anew): its checkpoint may be what this run restarts from,
  // so it is moved aside, not emptied. Unless a run at work holds it: a run of the same pid in
  // another container, writing into the same folder.
  if (fs::exists(stage_, ec)) {
    DSPDEM_CHECK(lock_state(stage_) != Lock::Held && !held_here(stage_),
                 "output directory '{}': a run at work holds its staging folder '{}' (a run of the same pid in "
                 "another container?): give this run another --out",
                 out_, stage_);
    for (aside_ = 1; fs::exists(stage_ + "." + std::to_string(aside_), ec); ++aside_) {
    }
    fs::rename(stage_, stage_ + "." + std::to_string(aside_), ec);
    DSPDEM_CHECK(!ec, "cannot move the earlier staging folder '{}' aside: {}", stage_, ec.message());
  }
  // Made and locked under a name no one looks at, then renamed into place: no one sees the
  // staging folder without its lock. The lock file is closed on exec, so that a process this
  // one starts (a sweep's run) does not hold it on after this one ends. Where flock fails there
  // is no lock file, and left_by_killed_run goes by the pid.
  const fs::path fresh = fs::path(out_) / fmt::format(".new-staging-{}", id);
  fs::remove_all(fresh, ec);  // a leftover of a process of this pid that died right here
  fs::create_directories(fresh, ec);
  DSPDEM_CHECK(!ec, "cannot create staging folder '{}': {}", fresh.string(), ec.message());
  lock_fd_ = ::open((fresh / ".lock").c_str(), O_CREAT | O_RDWR | O_CLOEXEC, 0644);
  if (lock_fd_ >= 0 && flock(lock_fd_, LOCK_EX | LOCK_NB) != 0) {
    ::close(lock_fd_);
    lock_fd_ = -1;
    ::unlink((fresh / ".lock").c_str());
  }
  fs::rename(fresh, stage_, ec);
  if (ec) {
    if (lock_fd_ >= 0) ::close(lock_fd_), lock_fd_ = -1;
    fs::remove_all(fresh);
    fail("cannot create staging folder '{}': {}", stage_, ec.message());
  }
  if (lock_fd_ >= 0) {
    const std::lock_guard<std::mutex> guard(g_held_mutex);
    g_held.insert(held_key(stage_));
  }
}

Staging::~Staging() {
  if (done_ || !owner_) return;
  unlock(stage_);
  std::error_code ec;
  fs::remove_all(stage_, ec);
}

void Staging::unlock(const std::string& where) {
  if (lock_fd_ < 0) return;
  {
    const std::lock_guard<std::mutex> guard(g_held_mutex);
    g_held.erase(held_key(stage_));
  }
  ::unlink((fs::path(where) / ".lock").c_str());
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
  unlock(stage_);
  fs::remove_all(stage_);
  // A successful run supersedes an earlier failure's or interruption's partial outputs, and
  // the staging folders of earlier runs that were killed (their process gone).
  fs::remove_all(fs::path(out_) / failed_folder);
  fs::remove_all(fs::path(out_) / interrupted_folder);
  std::error_code ec;
  for (fs::directory_iterator it(out_, ec), end; !ec && it != end; it.increment(ec)) {
    const bool mine = aside_ > 0 && it->path() == fs::path(stage_ + "." + std::to_string(aside_));  // moved aside
    if (mine || left_by_killed_run(it->path().string())) fs::remove_all(it->path(), ec);
  }
  done_ = true;
}

std::string Staging::keep_as(const std::string& name) {
  if (!owner_) return stage_;  // only the process that made the folder moves it
  const fs::path dst = fs::path(out_) / name;
  // Held until the folder has its new name: until then it holds the newest checkpoint.
  fs::remove_all(dst);
  fs::rename(stage_, dst);
  unlock(dst.string());
  done_ = true;
  return dst.string();
}

namespace {
void write_temporary(const std::string& tmp, const std::string& text) {
  std::ofstream f(tmp, std::ios::binary);
  DSPDEM_CHECK(f.good(), "cannot write '{}'", tmp);
  f << text;
  f.flush();
  DSPDEM_CHECK(f.good(), "error while writing '{}'", tmp);
}
}  // namespace

void write_file_atomic(const std::string& path, const std::string& text) { write_files_atomic({{path, text}}); }

void write_files_atomic(const std::vector<std::pair<std::string, std::string>>& files) {
  std::size_t written = 0;
  try {
    for (; written < files.size(); ++written) write_temporary(files[written].first + ".tmp", files[written].second);
  } catch (...) {
    std::error_code ignore;  // the one that failed too: it may be there, half written
    for (std::size_t i = 0; i <= written && i < files.size(); ++i) fs::remove(files[i].first + ".tmp", ignore);
    throw;
  }
  // Renames within a folder do not fail short of a broken disk; should one, the rest are not
  // made and their temporaries go, and the message names the file.
  for (std::size_t i = 0; i < files.size(); ++i) {
    std::error_code e;
    fs::rename(files[i].first + ".tmp", files[i].first, e);
    if (!e) continue;
    const std::string why = e.message();
    for (std::size_t j = i; j < files.size(); ++j) fs::remove(files[j].first + ".tmp", e);
    fail("cannot replace '{}' by its new version: {}{}", files[i].first, why,
         i > 0 ? fmt::format(" (the {} before it of the {} written together were replaced)", i, files.size()) : "");
  }
}

}  // namespace dspdem
