#include "report/files_aside.hpp"

#include <algorithm>
#include <filesystem>

#include "core/error.hpp"

namespace dspdem::report {

namespace fs = std::filesystem;

FilesAside::FilesAside(const std::string& dir, std::vector<std::string> files)
    : dir_(dir), aside_((fs::path(dir) / ".files_aside").string()), files_(std::move(files)) {
  // A killed report's: what it set aside is the earlier report's, put back over what it wrote.
  // A listed file it did not set aside is left where it is: which of those it wrote cannot be
  // told from one it had not reached yet.
  fs::remove_all(aside_ + ".dropped");  // a drop that stopped partway: nothing to keep
  if (fs::exists(aside_)) {
    moved_ = files_;
    restore(false);
    moved_.clear();
    DSPDEM_CHECK(!fs::exists(aside_),
                 "'{}' holds files an earlier report set aside that cannot all be put back; put them back into '{}' "
                 "by hand (or remove them) and run the report again",
                 aside_, dir_);
  }
  try {
    for (const auto& f : files_) {
      const fs::path from = fs::path(dir_) / f;
      if (!fs::exists(from)) continue;
      const fs::path to = fs::path(aside_) / f;
      fs::create_directories(to.parent_path());
      fs::rename(from, to);  // a rename within the folder, never a copy
      moved_.push_back(f);
    }
  } catch (const fs::filesystem_error& e) {
    restore(false);  // only what was moved; the files not reached are still in place
    fail("cannot set the earlier report's files aside in '{}': {}", aside_, e.what());
  }
}

void FilesAside::drop() {
  dropped_ = true;
  // Renamed first, in one step: a drop that stops partway must not leave files that the next
  // report would put back over this one's.
  std::error_code e;
  const std::string gone = aside_ + ".dropped";
  fs::remove_all(gone, e);
  fs::rename(aside_, gone, e);
  fs::remove_all(gone, e);
}

void FilesAside::restore(bool remove_new) const {
  // Without throwing: this also runs while an exception leaves the report. The folder aside
  // goes only when every file in it went back, so a file that could not is never lost.
  std::error_code e;
  bool all_back = true;
  for (const auto& f : files_) {
    const fs::path at = fs::path(dir_) / f, kept = fs::path(aside_) / f;
    const bool was = std::find(moved_.begin(), moved_.end(), f) != moved_.end();
    if (was && fs::exists(kept, e)) {
      fs::remove(at, e);
      fs::create_directories(at.parent_path(), e);  // images/ may have gone meanwhile
      fs::rename(kept, at, e);
      all_back = all_back && !e;
    } else if (!was && remove_new) {
      fs::remove(at, e);  // the earlier report had none: this report's, beside its report.md
    }
  }
  if (all_back) fs::remove_all(aside_, e);
}

FilesAside::~FilesAside() {
  if (!dropped_) restore(true);
}

}  // namespace dspdem::report
