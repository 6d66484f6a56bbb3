// An earlier report whose runs a new report has begun to replace. Runs are replaced one by one
// as they finish (each through its staging folder, io/staging.hpp), while report.md is written
// only at the end: a report that stops between the two would leave the earlier report.md
// describing runs that are no longer the ones beside it, with nothing to say so. The first
// run a report replaces therefore marks the earlier report.md (and report.html, and the
// summary of headline.json that the figures site shows) as outdated, its text otherwise kept;
// the new report's own files replace all three when it is written.
#pragma once
#include <optional>
#include <string>

namespace dspdem::report {

/// The first words of the mark, as report.md carries it (a blockquote under the title).
inline constexpr const char* kOutdatedMark = "> **Outdated.**";

/// What a run folder held before a run into it, to tell afterwards whether that run replaced a
/// finished one: its summary.json as a file (device, inode, modification time), or a run
/// whose commit was cut short (run.pvd there, no summary.json), or what an earlier report
/// derived there from another run (--from-run: its derived_from, io/run_place.hpp), which a
/// run empties (clear_derived_place) before it starts. Decided by the files, not by how the
/// run ended: a run stopped or killed after its commit has replaced the earlier one.
class RunReplacement {
 public:
  explicit RunReplacement(std::string run_dir);
  /// Whether a finished run was there before and another run's summary.json is there now, or
  /// the derived files that were there are gone.
  bool replaced() const;
  const std::string& dir() const { return dir_; }

 private:
  struct FileId {
    unsigned long long dev = 0, ino = 0;
    long long mtime_ns = 0;
    bool operator==(const FileId&) const = default;
  };
  static std::optional<FileId> summary_id(const std::string& dir);
  std::string dir_;
  bool held_ = false, derived_ = false;
  std::optional<FileId> before_;
};

/// Marks the report in `dir` as outdated, naming `replaced` (the run folder just replaced,
/// shown relative to `dir`): the mark goes under report.md's title, report.html is rendered
/// from the marked text, and headline.json's summary begins with it (skipped, with a warning,
/// when headline.json cannot be read). Does nothing when `dir` is empty or holds no report.md,
/// or when its report.md is marked already (the first replacement is named). The files are
/// rewritten atomically, together. Never throws: what fails is warned of, since the runs are
/// what matters, and they are in place.
void mark_report_outdated(const std::string& dir, const std::string& replaced);

}  // namespace dspdem::report
