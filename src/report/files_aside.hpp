// Files of a report's folder that an earlier report wrote and this one writes again or may
// not (a table only some options give): set aside before the report writes, dropped once it
// has written its report.md, and put back if it stops first, so that a report that fails
// leaves the earlier one's files as they were beside the earlier report.md it also leaves.
#pragma once
#include <string>
#include <vector>

namespace dspdem::report {

class FilesAside {
 public:
  /// Moves each of `files` (paths relative to `dir`) that exists into DIR/.files_aside/; if
  /// one cannot be moved, puts back those that were and throws Error. A .files_aside/ left by
  /// a report that was killed outright is put back first (its files are the earlier report's).
  FilesAside(const std::string& dir, std::vector<std::string> files);
  FilesAside(const FilesAside&) = delete;
  FilesAside& operator=(const FilesAside&) = delete;
  /// The report is written: the files set aside are dropped.
  void drop();
  /// Not dropped: each of `files` as the earlier report left it (put back over what this one
  /// wrote meanwhile, or removed when the earlier one had none). A file that cannot be put
  /// back stays in DIR/.files_aside/, for the next report into DIR to put back.
  ~FilesAside();

 private:
  void restore(bool remove_new) const;
  std::string dir_, aside_;
  std::vector<std::string> files_, moved_;
  bool dropped_ = false;
};

}  // namespace dspdem::report
