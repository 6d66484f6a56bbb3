// One writer at a time for a folder: a report holds an exclusive flock on DIR/.report.lock
// while it writes into DIR, so that a second report into the same folder is refused at its
// start instead of both setting the other's files aside, running into the same run folders and
// writing over each other's report; and a render on DIR/.render.lock while it draws into DIR
// (io/run_place.hpp). The kernel drops the lock when the process ends, however it ends, so a
// killed report or render leaves nothing to clear by hand (at most a lock file the next takes).
#pragma once
#include <filesystem>
#include <string>

#include "core/error.hpp"

namespace dspdem {

/// A FolderLock refused because another writer holds the folder now (not for a folder or a
/// lock file that cannot be made: those are plain Errors), so that a caller can tell the two.
class FolderBusy : public Error {
 public:
  using Error::Error;
};

class FolderLock {
 public:
  /// Whether a file system without flock is warned of (the lock is then not taken).
  enum class NoFlock { warn, quiet };

  /// Makes `dir` if need be and takes the lock on `dir/<file>`; FolderBusy naming the folder
  /// when another process holds it (`what` says what holds it, e.g. "another report"), leaving
  /// no folder it made. Where the file system has no flock the lock is not taken (a warning
  /// unless `quiet`), as for the runs' staging folders; its file still goes when this lets go.
  FolderLock(const std::string& dir, const std::string& file, const std::string& what,
             NoFlock no_flock = NoFlock::warn);
  FolderLock(const FolderLock&) = delete;
  FolderLock& operator=(const FolderLock&) = delete;
  /// Removes the lock file while still holding it, then lets go (and removes the folders this
  /// lock made, `dir` and those above it, while they hold nothing else: a report or a render
  /// refused at once leaves no folder).
  ~FolderLock();

  /// Whether another open file holds the lock on `dir/<file>` now (a writer in that folder).
  /// Tested with a shared lock taken and let go at once: a taker in that instant is refused as
  /// if held, so this is for refusing, not for waiting on.
  static bool held(const std::string& dir, const std::string& file);

 private:
  void remove_made() const;
  std::filesystem::path dir_;  ///< absolute, normalised: a later change of folder does not move it
  std::string path_;
  std::filesystem::path made_top_;  ///< the highest folder this lock made, empty when it made none
  int fd_ = -1;
};

}  // namespace dspdem
