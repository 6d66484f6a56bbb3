#include "scenes/sphere_impact/split_timing.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "render/plot.hpp"
#include "report/onsets.hpp"
#include "report/proportion.hpp"

namespace dspdem::sphere {

namespace {
namespace fs = std::filesystem;

// A time in ms; +infinity: `none`.
std::string ms_or(double t, const char* none) {
  return std::isinf(t) ? std::string(none) : fmt::format("{:.3f}", 1e3 * t);
}

// The two middle values in ms, as onset_table prints them ("a" or "a to b").
std::string middle_ms(const std::vector<double>& v, const char* none) {
  const report::Middle m = report::middle(v);
  return m.low == m.high ? ms_or(m.low, none) : ms_or(m.low, none) + " to " + ms_or(m.high, none);
}

// The median's distribution-free interval (report::median_interval) in ms, with the coverage
// its ranks guarantee.
std::string median_interval_ms(const std::vector<double>& v, const char* none) {
  return report::median_interval_text(
      report::median_interval(v), [none](double t) { return ms_or(t, none); }, "too few meshes");
}
}  // namespace

int SplitTiming::by_end(double before) const {
  int n = 0;
  for (std::size_t i = 0; i < first.size(); ++i) n += first[i] >= 0 && first[i] <= end[i] - before + kSameTime;
  return n;
}

SplitTiming split_timing(double speed, const std::vector<RealisationRun>& runs) {
  SplitTiming s;
  s.speed = speed;
  for (const RealisationRun& run : runs) {
    if (run.result == nullptr || run.result->history.empty()) {
      ++s.left_out;
      continue;
    }
    // The history runs up to the compared frame (analysis.hpp), so its first two large
    // pieces are the compared frame's or earlier.
    s.first.push_back(run.result->t_two_large());
    s.end.push_back(run.result->compared_after_contact());
  }
  return s;
}

std::vector<double> came_free(const std::vector<double>& first) {
  std::vector<double> t;
  for (double f : first)
    if (f >= 0) t.push_back(f);
  std::sort(t.begin(), t.end());
  return t;
}

std::vector<std::pair<double, int>> steps(const SplitTiming& s) {
  std::vector<std::pair<double, int>> out;
  int at = 0;
  for (double t : came_free(s.first)) {
    ++at;
    if (!out.empty() && out.back().first == t)
      out.back().second = at;
    else
      out.emplace_back(t, at);
  }
  return out;
}

std::string freed_range(const std::vector<double>& first) {
  const std::vector<double> t = came_free(first);
  if (t.empty()) return first.empty() ? std::string("-") : fmt::format("none (0 of {})", first.size());
  const std::string when = t.front() == t.back() ? fmt::format("{:.3f}", 1e3 * t.front())
                                                 : fmt::format("{:.3f}-{:.3f}", 1e3 * t.front(), 1e3 * t.back());
  return fmt::format("{} ({} of {})", when, t.size(), first.size());
}

void split_timing_section(report::Document& doc, const std::vector<double>& speeds,
                          const std::vector<std::vector<RealisationRun>>& by_speed, const std::string& dir) {
  std::vector<SplitTiming> per_speed;
  std::vector<double> too_few;  // speeds with fewer than two runs to read
  for (std::size_t si = 0; si < speeds.size(); ++si) {
    SplitTiming s = split_timing(speeds[si], by_speed[si]);
    if (s.meshes() < 2)
      too_few.push_back(speeds[si]);
    else
      per_speed.push_back(std::move(s));
  }
  if (per_speed.empty()) return;

  std::vector<std::vector<std::string>> rows;
  std::vector<render::Curve> curves;
  std::ofstream csv(fs::path(dir) / kLargePiecesTimeCsv);
  csv << "speed,after_contact_ms,meshes,with_two_large\n";
  for (const SplitTiming& s : per_speed) {
    const int n = s.meshes(), k = s.by_end(), k_before = s.by_end(kLateWindow);
    const auto [lo, hi] = std::minmax_element(s.end.begin(), s.end.end());
    const std::string ends =
        *hi - *lo < 5e-7 ? fmt::format("{:.3f}", 1e3 * *lo) : fmt::format("{:.3f}-{:.3f}", 1e3 * *lo, 1e3 * *hi);
    const std::vector<double> t = came_free(s.first);
    std::vector<double> all = s.first;  // none by the compared frame: later, the largest
    for (double& f : all)
      if (f < 0) f = INFINITY;
    rows.push_back({fmt::format("{:g}", s.speed), std::to_string(n), report::count_of(k, n),
                    report::count_of(k_before, n), ends, k > 0 ? fmt::format("{} of {}", k - k_before, k) : "-",
                    t.empty() ? "-" : fmt::format("{:.3f}", 1e3 * t.front()), t.empty() ? "-" : middle_ms(t, "-"),
                    middle_ms(all, "after the compared frame"), median_interval_ms(all, "after the compared frame"),
                    s.left_out > 0 ? std::to_string(s.left_out) : "-"});
    // The count as a step curve: at each time it rises to the meshes by then.
    render::Curve c{fmt::format("{:g} m/s", s.speed), {0.0}, {0.0}};
    csv << fmt::format("{:g},{:.6f},{},0\n", s.speed, 0.0, n);
    int at = 0;
    for (const auto& [ti, count] : steps(s)) {
      c.x.push_back(1e3 * ti), c.y.push_back(static_cast<double>(at) / n);
      at = count;
      c.x.push_back(1e3 * ti), c.y.push_back(static_cast<double>(at) / n);
      csv << fmt::format("{:g},{:.6f},{},{}\n", s.speed, 1e3 * ti, n, at);
    }
    c.x.push_back(1e3 * *hi), c.y.push_back(static_cast<double>(at) / n);
    csv << fmt::format("{:g},{:.6f},{},{}\n", s.speed, 1e3 * *hi, n, at);
    if (!t.empty()) curves.push_back(std::move(c));
  }
  doc.para(fmt::format(
      "When the large pieces come free. The paper compares one moment. Per speed, the meshes whose sphere has "
      "shown two pieces of at least 10 % of the mass by the compared time, and by {:g} ms before it: where many "
      "came free in that last stretch, the count at the compared time hangs on the moment as much as on the speed, "
      "and runs taken further (`--set time.end=...`) tell how many follow. A mesh is counted from its first frame "
      "with two such pieces (they may break up further by the compared time, which the pattern's count reads). "
      "Each run is read up to its own compared frame, the frame nearest the compared time. The median over all "
      "meshes counts those without two such pieces as later than their compared frames; its interval is "
      "distribution-free (the order statistics whose ranks cover the median with at least 95 %, the coverage "
      "they guarantee given; it needs six meshes) and holds for these censored times as long as the meshes are "
      "read to about one time (the compared frames above). The count against the "
      "time is in `large_pieces_time.csv`{}.{}",
      1e3 * kLateWindow, curves.empty() ? "" : " and `images/large_pieces_time.png`",
      too_few.empty()
          ? ""
          : fmt::format(" Not read, fewer than two runs with a history: {} m/s.", fmt::join(too_few, ", "))));
  doc.table({"speed [m/s]", "meshes", "two pieces >= 10 % by the compared frame",
             fmt::format("by {:g} ms before it", 1e3 * kLateWindow), "compared frames [ms after contact]",
             fmt::format("came free in its last {:g} ms", 1e3 * kLateWindow), "the first [ms after contact]",
             "median of those that came free [ms]", "median over all meshes [ms]", "its 95 % interval [ms]",
             "runs left out (failed, or no history)"},
            rows);
  if (curves.empty()) return;
  render::plot_curves(curves, "time after the first contact [ms]", "share of meshes with two pieces >= 10 %",
                      "when the large pieces come free", (fs::path(dir) / kLargePiecesTimePng).string());
  doc.figure("when the large pieces come free", kLargePiecesTimePng);
}

}  // namespace dspdem::sphere
