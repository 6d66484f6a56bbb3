#include "report/run_data.hpp"

#include <algorithm>
#include <filesystem>

#include "core/error.hpp"
#include "core/file.hpp"
#include "render/plot.hpp"

namespace dspdem::report {

namespace fs = std::filesystem;

Series::Series(const std::string& csv_path) : path_(csv_path) { render::read_csv(csv_path, names_, cols_); }

bool Series::has(const std::string& name) const {
  return std::find(names_.begin(), names_.end(), name) != names_.end();
}

const std::vector<double>& Series::operator[](const std::string& name) const {
  for (std::size_t i = 0; i < names_.size(); ++i)
    if (names_[i] == name) return cols_[i];
  std::string known;
  for (const auto& n : names_) known += " " + n;
  fail("'{}' has no column '{}' (columns:{})", path_, name, known);
}

std::optional<RunRecord> run_record(const std::string& dir) {
  const fs::path d(dir);
  if (!fs::exists(d / "summary.json")) return std::nullopt;
  return RunRecord{read_run_summary((d / "summary.json").string()), read_file_if((d / "case.resolved.toml").string())};
}

std::string run_log(const std::string& dir) { return dir + ".log"; }

RunData RunData::open(const std::string& dir) {
  RunData r;
  r.dir = dir;
  const fs::path d(dir);
  auto rec = run_record(dir);
  DSPDEM_CHECK(rec.has_value(), "{}: no summary.json there (not the output folder of a finished run)", dir);
  r.summary = std::move(rec->summary);
  r.resolved_case = std::move(rec->resolved).value_or("");
  r.series = Series((d / "series.csv").string());
  r.frames = render::read_series(dir);
  if (fs::exists(d / "joints.pvd")) r.joint_frames = render::read_series(dir, "joints.pvd");
  return r;
}

double value_at(const std::vector<double>& time, const std::vector<double>& values, double t) {
  const std::size_t k = static_cast<std::size_t>(std::lower_bound(time.begin(), time.end(), t - 1e-15) - time.begin());
  return values[std::min(k, values.size() - 1)];
}

std::string step_text(double dt_start, double dt, const char* unit) {
  if (dt_start > 0 && dt_start != dt) return fmt::format("{:.3g}{} falling to {:.3g}{}", dt_start, unit, dt, unit);
  return fmt::format("{:.3g}{}", dt, unit);
}

}  // namespace dspdem::report
