// One writer at a time for a folder: a report holds an exclusive flock on DIR/.report.lock
// while it writes into DIR, so that a second report into the same folder is refused at its
// start instead of both setting the other's files aside, running into the same run folders and
// writing over each other's report. The kernel drops the lock when the process ends, however
// it ends, so a killed report leaves nothing to clear by hand.
#pragma once
#include <string>

namespace dspdem {

class FolderLock {
 public:
  /// Makes `dir` if need be and takes the lock on `dir/<file>`; Error naming the folder when
  /// another process holds it (`what` says what holds it, e.g. "another report"). Where the file
  /// system has no flock the lock is not taken (a warning), as for the runs' staging folders.
  FolderLock(const std::string& dir, const std::string& file, const std::string& what);
  FolderLock(const FolderLock&) = delete;
  FolderLock& operator=(const FolderLock&) = delete;
  /// Removes the lock file while still holding it, then lets go (and removes `dir` when this
  /// lock made it and it holds nothing else: a report refused at once leaves no folder).
  ~FolderLock();

 private:
  std::string dir_, path_;
  int fd_ = -1;
  bool made_dir_ = false;
};

}  // namespace dspdem
