#include "scenes/sphere_impact/pattern_over_time.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>

#include "report/proportion.hpp"
#include "scenes/sphere_impact/pattern.hpp"

namespace dspdem::sphere {

namespace {
namespace fs = std::filesystem;
constexpr double kStep = 0.25e-3;  // between the times read

// The speeds whose pattern a history can judge.
bool readable(double v) {
  const SpeedBand b = speed_band(v);
  return b == SpeedBand::Whole || b == SpeedBand::FewLarge;
}
}  // namespace

std::optional<bool> pattern_at(const SphereImpactResult& r, double after_contact) {
  if (r.history.empty() || !readable(r.speed) || after_contact > r.compared_after_contact() + kSameTime) return {};
  const SphereImpactResult::PiecesAt* at = r.history_at(after_contact);
  if (at == nullptr) return {};
  // The criteria the compared frame is judged by (pattern_met).
  if (speed_band(r.speed) == SpeedBand::FewLarge) return SphereImpactResult::few_large(at->large_pieces);
  return !SphereImpactResult::cut_through(at->largest, at->second);
}

std::vector<double> reading_times(double last) {
  std::vector<double> t;
  // Half a step short of `last`: the compared frame is the one nearest the compared time, on
  // either side of it, and the counts above already read it there.
  for (int k = 0; kPaperTime + k * kStep < last - 0.5 * kStep; ++k) t.push_back(kPaperTime + k * kStep);
  return t;
}

std::vector<PatternCount> pattern_over_time(const std::vector<double>& times, const std::vector<double>& speeds,
                                            const std::vector<std::vector<RealisationRun>>& by_speed) {
  std::vector<PatternCount> out;
  for (double t : times) {
    PatternCount c;
    c.after_contact = t;
    std::map<int, std::pair<int, int>> mesh;  // orientation: speeds read, speeds with the pattern
    int speeds_read = 0;
    for (std::size_t si = 0; si < speeds.size(); ++si) {
      if (!readable(speeds[si])) continue;
      ++speeds_read;
      int met = 0, read = 0;
      for (const RealisationRun& run : by_speed[si]) {
        const std::optional<bool> p = run.result ? pattern_at(*run.result, t) : std::nullopt;
        c.runs.push_back({run.orientation, speeds[si], p.has_value(), p.value_or(false)});
        if (!p) continue;
        ++read, met += *p;
        auto& [r, m] = mesh[run.orientation];
        ++r, m += *p;
      }
      c.met.push_back(met), c.read.push_back(read);
    }
    for (const auto& [o, rm] : mesh)
      if (rm.first == speeds_read) ++c.every_read, c.every_met += rm.second == speeds_read;
    out.push_back(std::move(c));
  }
  return out;
}

void pattern_over_time_section(report::Document& doc, const std::vector<double>& speeds,
                               const std::vector<std::vector<RealisationRun>>& by_speed, const std::string& dir) {
  // The earliest compared frame bounds the times every run can be read at.
  double last = INFINITY;
  int no_history = 0;  // runs of the speeds read that failed or have no history
  std::vector<double> read_speeds, not_read;
  for (std::size_t si = 0; si < speeds.size(); ++si) {
    (readable(speeds[si]) ? read_speeds : not_read).push_back(speeds[si]);
    for (const RealisationRun& run : by_speed[si]) {
      const bool has = run.result && !run.result->history.empty();
      if (has) last = std::min(last, run.result->compared_after_contact());
      no_history += readable(speeds[si]) && !has;
    }
  }
  if (!std::isfinite(last)) return;  // no run with a history
  const std::vector<double> times = reading_times(last);
  if (times.empty() || read_speeds.empty()) return;
  const std::vector<PatternCount> counts = pattern_over_time(times, speeds, by_speed);
  if (*std::max_element(counts.front().read.begin(), counts.front().read.end()) < 2) return;

  const bool every = read_speeds.size() > 1;
  std::vector<std::string> head = {"after the contact [ms]"};
  for (double v : read_speeds) head.push_back(fmt::format("{:g} m/s: {}", v, expected_pattern(v)));
  if (every) head.push_back(fmt::format("at {} m/s alike", fmt::join(read_speeds, ", ")));
  std::vector<std::vector<std::string>> rows;
  std::ofstream csv(fs::path(dir) / kPatternOverTimeCsv);
  // scope: "speed", or "every" for the meshes read at all the speeds read (speed left empty).
  csv << "after_contact_ms,scope,speed,meshes_read,with_pattern\n";
  for (const PatternCount& c : counts) {
    std::vector<std::string> row = {fmt::format("{:.2f}", 1e3 * c.after_contact)};
    for (std::size_t k = 0; k < read_speeds.size(); ++k) {
      row.push_back(c.read[k] > 0 ? report::count_of(c.met[k], c.read[k]) : "-");
      csv << fmt::format("{:.3f},speed,{:g},{},{}\n", 1e3 * c.after_contact, read_speeds[k], c.read[k], c.met[k]);
    }
    if (every) {
      row.push_back(c.every_read > 0 ? report::count_of(c.every_met, c.every_read) : "-");
      csv << fmt::format("{:.3f},every,,{},{}\n", 1e3 * c.after_contact, c.every_read, c.every_met);
    }
    rows.push_back(std::move(row));
  }
  // Each run, for comparing two sweeps of the same meshes (another variant, another build) mesh
  // by mesh at each time without reading every run's pieces_time.csv again; the columns as
  // orientations.csv's, paper_pattern empty where the run could not be read.
  std::ofstream runs_csv(fs::path(dir) / kPatternOverTimeRunsCsv);
  runs_csv << "after_contact_ms,speed,orientation,paper_pattern\n";
  for (const PatternCount& c : counts)
    for (const PatternRead& r : c.runs)
      runs_csv << fmt::format("{:.3f},{:g},{},{}\n", 1e3 * c.after_contact, r.speed, r.orientation,
                              r.read ? std::to_string(int(r.met)) : "");
  std::string text = fmt::format(
      "The paper's pattern read at earlier times. The runs go on to {:.3f} ms after the contact or later, past the "
      "paper's {:g} ms: each run is read from its history at its last frame at or before each time, every {:g} ms "
      "from the paper's moment to half a step before the earliest compared frame (the counts above read each run at "
      "its own). A speed's pattern is the paper's at that speed.",
      1e3 * last, 1e3 * kPaperTime, 1e3 * kStep);
  if (every)
    text += fmt::format(
        " The last column counts the meshes whose runs at {} m/s could all be read and all show it{}.",
        fmt::join(read_speeds, ", "),
        not_read.empty() ? "" : ", so it is not the count at every speed run when other speeds were run too");
  if (!not_read.empty())
    text += fmt::format(
        " Not read over time: {} m/s (20 m/s and above need the single elements, which the history does not keep; "
        "a speed between 5 and 20 m/s other than 7.5 is not one the paper describes).",
        fmt::join(not_read, ", "));
  if (no_history > 0) text += fmt::format(" Left out: {} run(s) that failed or have no history.", no_history);
  doc.para(text +
           " Also in `pattern_over_time.csv`, and each run in `pattern_over_time_runs.csv` (empty where it "
           "could not be read).");
  doc.table(head, rows);
}

}  // namespace dspdem::sphere
