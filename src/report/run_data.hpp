// A finished run folder opened for analysis: its summary, its series by column name, its
// frames (and the joints frames when there are joints), and its resolved case text. Every
// scene's analysis starts here instead of reading the files itself.
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "io/run_summary.hpp"
#include "render/series.hpp"

namespace dspdem::report {

/// series.csv as columns.
class Series {
 public:
  Series() = default;
  explicit Series(const std::string& csv_path);
  /// The column called `name`; throws Error naming the file and the columns it has.
  const std::vector<double>& operator[](const std::string& name) const;
  bool has(const std::string& name) const;
  std::size_t rows() const { return cols_.empty() ? 0 : cols_.front().size(); }

 private:
  std::string path_;
  std::vector<std::string> names_;
  std::vector<std::vector<double>> cols_;
};

/// What a run folder records of the run it holds: its summary.json, and the case as it ran
/// (its case.resolved.toml; none when that file is missing). Read by --resume, which keeps a
/// run only when it is the same, by --from-run, which refuses a run of another case, and by
/// RunData::open.
struct RunRecord {
  RunSummary summary;
  std::optional<std::string> resolved;
};

/// The record of the run in `dir`; nothing when the folder has no summary.json.
std::optional<RunRecord> run_record(const std::string& dir);

/// The log a report's run process writes beside its folder ("<dir>.log"): where a killed run
/// leaves the only trace of itself.
std::string run_log(const std::string& dir);

struct RunData {
  std::string dir;
  RunSummary summary;
  Series series;
  std::vector<render::FrameRef> frames;
  std::vector<render::FrameRef> joint_frames;  ///< empty without joints
  std::string resolved_case;                   ///< case.resolved.toml, as run

  /// Opens DIR; throws Error naming what is missing (summary.json, series.csv, run.pvd).
  static RunData open(const std::string& dir);
};

/// Series value at time t: the row at or just after t (series are sampled finer than frames).
double value_at(const std::vector<double>& time, const std::vector<double>& values, double t);

/// A run's step for a report: "3.1e-08 s", or "1.67e-07 s falling to 1.36e-07 s" when it
/// fell during the run (extrinsic insertion lowers it as joints open). `unit` follows each
/// value ("" in a table whose header gives the unit).
std::string step_text(double dt_start, double dt, const char* unit = " s");

}  // namespace dspdem::report
