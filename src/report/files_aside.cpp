#include "report/files_aside.hpp"

#include <filesystem>

#include "core/error.hpp"

namespace dspdem::report {

namespace fs = std::filesystem;

FilesAside::FilesAside(const std::string& dir, std::vector<std::string> files)
    : dir_(dir), aside_((fs::path(dir) / ".files_aside").string()), files_(std::move(files)) {
  if (fs::exists(aside_)) put_back();
  for (const auto& f : files_) {
    const fs::path from = fs::path(dir_) / f;
    if (!fs::exists(from)) continue;
    const fs::path to = fs::path(aside_) / f;
    fs::create_directories(to.parent_path());
    std::error_code e;
    fs::rename(from, to, e);  // one file system: a rename, never a copy
    DSPDEM_CHECK(!e, "cannot set '{}' aside in '{}': {}", from.string(), aside_, e.message());
  }
}

void FilesAside::drop() {
  dropped_ = true;
  std::error_code e;
  fs::remove_all(aside_, e);
}

void FilesAside::put_back() const {
  // Without throwing: this also runs while an exception leaves the report.
  std::error_code e;
  for (const auto& f : files_) {
    const fs::path at = fs::path(dir_) / f, kept = fs::path(aside_) / f;
    fs::remove(at, e);
    if (fs::exists(kept, e)) fs::rename(kept, at, e);
  }
  fs::remove_all(aside_, e);
}

FilesAside::~FilesAside() {
  if (!dropped_) put_back();
}

}  // namespace dspdem::report
