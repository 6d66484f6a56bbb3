// Writes a run's outputs into a hidden staging folder inside the output directory and
// moves them into place only when the run completes, so a failed or interrupted run never
// destroys an earlier run's results. A failed run's partial outputs are kept apart in
// DIR/failed_run/.
//
// The process that made a staging folder holds an exclusive flock on its file `.lock` while
// it runs; the kernel drops it when the process ends, however it ends. Whether a staging
// folder's run is gone (its checkpoint free to continue, the folder free to clear) is asked of
// that lock, which is right across PID namespaces (another container writing into the same
// folder) and after a pid is handed out again; the pid in the folder's name is the answer only
// where there is no lock file (a file system without flock).
#pragma once
#include <string>
#include <utility>
#include <vector>

namespace dspdem {

/// The folder a stopped run's outputs and checkpoint are kept in, inside its run folder.
inline constexpr const char* interrupted_folder = "interrupted_run";
/// The folder a failed run's partial outputs are kept in, for a look (never continued).
inline constexpr const char* failed_folder = "failed_run";

class Staging {
 public:
  explicit Staging(const std::string& out_dir);
  /// A distributed run's shared folder: process 0 creates and commits it (owner), named by
  /// its id; the others write into it and leave it alone.
  Staging(const std::string& out_dir, long id, bool owner);
  ~Staging();  ///< removes the staging folder if neither commit() nor keep_failed() ran
  Staging(const Staging&) = delete;
  Staging& operator=(const Staging&) = delete;

  const std::string& path() const { return stage_; }
  const std::string& out_dir() const { return out_; }
  /// Moves every entry of the staging folder into the output directory, replacing entries
  /// of the same name (old ones are removed only after the new ones are in place).
  void commit();
  /// Renames the staging folder to DIR/failed_run (replacing an older one); returns its path.
  std::string keep_failed() { return keep_as(failed_folder); }
  /// Renames the staging folder to DIR/<name> (replacing an older one); returns its path.
  std::string keep_as(const std::string& name);
  /// 0, or k when a folder of this staging folder's name was there already (a killed run's
  /// of the same pid) and was moved aside to `<its path>.<k>`.
  long moved_aside() const { return aside_; }

 private:
  void unlock(const std::string& where);  ///< lets go of the lock and removes its file, now in `where`

  std::string out_, stage_;
  bool done_ = false;
  bool owner_ = true;
  long aside_ = 0;
  int lock_fd_ = -1;
};

/// Whether `dir`'s last component (a trailing slash aside) names a staging folder:
/// `.staging-<pid>`, or one moved aside, `.staging-<pid>.<k>` (not a `.new-staging-<pid>` that
/// is still being set up).
bool is_staging_folder(const std::string& dir);

/// Whether `dir` is one of the folders beside a run's outputs that can hold its checkpoint: a
/// staging folder or `interrupted_run`. Their run folder is the one above them.
bool is_side_folder(const std::string& dir);

/// The first folder on `dir`'s path (`dir` itself included) named as a run's side folder, a
/// staging folder, `interrupted_run` or `failed_run`, or "" when there is none. A run made in
/// one goes with it: its run's restart, end or next run replaces it whole.
std::string side_folder_on_path(const std::string& dir);

/// Whether `dir` is the staging folder of a run whose process is gone: a run killed outright
/// (`.staging-<pid>`, or such a folder moved aside, `.staging-<pid>.<k>`). A live run's (its
/// lock held), or this process's own, is not.
bool left_by_killed_run(const std::string& dir);

/// Writes `text` to `path` through a temporary file and a rename.
void write_file_atomic(const std::string& path, const std::string& text);

/// Writes several files (path, text) together: every one to its temporary file first, then
/// the renames, so that a write that fails (a full disk) replaces none of them (Error).
void write_files_atomic(const std::vector<std::pair<std::string, std::string>>& files);

}  // namespace dspdem
