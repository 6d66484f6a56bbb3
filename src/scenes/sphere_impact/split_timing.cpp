#include "scenes/sphere_impact/split_timing.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <limits>

#include "render/plot.hpp"
#include "report/proportion.hpp"

namespace dspdem::sphere {

namespace {
namespace fs = std::filesystem;
// Frame times are written to about 1e-12 s; a time read from one run is "by" the same time read
// from another within this.
constexpr double kSameTime = 1e-12;
}  // namespace

int SplitTiming::by_end(double before) const {
  int n = 0;
  for (std::size_t i = 0; i < first.size(); ++i) n += first[i] >= 0 && first[i] <= end[i] - before + kSameTime;
  return n;
}

std::vector<double> SplitTiming::times() const {
  std::vector<double> t;
  for (double f : first)
    if (f >= 0) t.push_back(f);
  std::sort(t.begin(), t.end());
  return t;
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
    s.end.push_back(run.result->history.back().after_contact);
  }
  return s;
}

void split_timing_section(report::Document& doc, const std::vector<double>& speeds,
                          const std::vector<std::vector<RealisationRun>>& by_speed, const std::string& dir) {
  std::vector<SplitTiming> per_speed;
  for (std::size_t si = 0; si < speeds.size(); ++si) per_speed.push_back(split_timing(speeds[si], by_speed[si]));
  std::erase_if(per_speed, [](const SplitTiming& s) { return s.meshes() < 2; });
  if (per_speed.empty()) return;

  doc.para(fmt::format(
      "When the large pieces come free. The paper compares one moment. Per speed, the meshes whose sphere has "
      "shown two pieces of at least 10 % of the mass by the compared time, and by {:g} ms before it (four of the "
      "case's frames): where many came free in that last stretch, the count at the compared time hangs on the "
      "moment as much as on the speed, and runs taken further (`--set time.end=...`) tell how many follow. A mesh "
      "is counted from its first frame with two such pieces (they may break up further by the compared time, "
      "which the pattern's count reads). Each run is read up to its own compared frame, the frame nearest the "
      "compared time; the curve is in `large_pieces_time.csv` and `images/large_pieces_time.png`.",
      1e3 * kLateWindow));
  std::vector<std::vector<std::string>> rows;
  std::vector<render::Curve> curves;
  std::ofstream csv(fs::path(dir) / "large_pieces_time.csv");
  csv << "speed,after_contact_ms,meshes,with_two_large\n";
  for (const SplitTiming& s : per_speed) {
    const int n = s.meshes(), k = s.by_end(), k_before = s.by_end(kLateWindow);
    const auto [lo, hi] = std::minmax_element(s.end.begin(), s.end.end());
    const std::string ends =
        *hi - *lo < 5e-7 ? fmt::format("{:.3f}", 1e3 * *lo) : fmt::format("{:.3f}-{:.3f}", 1e3 * *lo, 1e3 * *hi);
    const std::vector<double> t = s.times();
    std::string first_median = "-";
    if (!t.empty()) {
      const std::size_t m = t.size() / 2;
      const double median = t.size() % 2 ? t[m] : 0.5 * (t[m - 1] + t[m]);
      first_median = fmt::format("{:.3f}, {:.3f}", 1e3 * t.front(), 1e3 * median);
    }
    rows.push_back({fmt::format("{:g}", s.speed), std::to_string(n), report::count_of(k, n),
                    report::count_of(k_before, n), ends, k > 0 ? fmt::format("{} of {}", k - k_before, k) : "-",
                    first_median, s.left_out > 0 ? std::to_string(s.left_out) : "-"});
    // The count as a step curve: at each mesh's time it rises by one.
    render::Curve c{fmt::format("{:g} m/s", s.speed), {0.0}, {0.0}};
    csv << fmt::format("{:g},0,{},0\n", s.speed, n);
    int at = 0;
    for (double ti : t) {
      c.x.push_back(1e3 * ti), c.y.push_back(static_cast<double>(at) / n);
      ++at;
      c.x.push_back(1e3 * ti), c.y.push_back(static_cast<double>(at) / n);
      csv << fmt::format("{:g},{:.6f},{},{}\n", s.speed, 1e3 * ti, n, at);
    }
    c.x.push_back(1e3 * *hi), c.y.push_back(static_cast<double>(at) / n);
    csv << fmt::format("{:g},{:.6f},{},{}\n", s.speed, 1e3 * *hi, n, at);
    if (!t.empty()) curves.push_back(std::move(c));
  }
  doc.table({"speed [m/s]", "meshes", "two pieces >= 10 % by the compared frame",
             fmt::format("by {:g} ms before it", 1e3 * kLateWindow), "compared frames [ms after contact]",
             fmt::format("came free in its last {:g} ms", 1e3 * kLateWindow),
             "the first, the median of those [ms after contact]", "runs left out (failed, or no history)"},
            rows);
  if (curves.empty()) return;
  render::plot_curves(curves, "time after the first contact [ms]", "share of meshes with two pieces >= 10 %",
                      "when the large pieces come free", (fs::path(dir) / "images" / "large_pieces_time.png").string());
  doc.figure("when the large pieces come free", "images/large_pieces_time.png");
}

}  // namespace dspdem::sphere
