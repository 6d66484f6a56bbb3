#include "report/fragment_history.hpp"

#include <algorithm>

#include "core/error.hpp"
#include "report/run_data.hpp"

namespace dspdem::report {

int FragmentFrame::count_at_least(double m) const {
  return static_cast<int>(std::count_if(largest.begin(), largest.end(), [&](const Piece& p) { return p.mass >= m; }));
}

std::vector<FragmentFrame> fragment_history(const std::string& fragments_csv) {
  const Series s(fragments_csv);
  const auto &frame = s["frame"], &time = s["time"], &count = s["count"], &rank = s["rank"], &mass = s["mass"],
             &elements = s["elements"], &x = s["x"], &y = s["y"], &z = s["z"];
  std::vector<FragmentFrame> out;
  for (std::size_t i = 0; i < s.rows(); ++i) {
    const int f = static_cast<int>(frame[i]);
    if (out.empty() || out.back().frame != f) {
      // Frames come in order, each with its rows by rank (1 the largest). Two files joined
      // or rows moved by hand would mix frames, and a piece would be read into the wrong one.
      DSPDEM_CHECK(out.empty() || (f > out.back().frame && time[i] >= out.back().time),
                   "'{}', data row {}: frame {} at t = {:g} s after frame {} at t = {:g} s (frames must come in order)",
                   fragments_csv, i + 1, f, time[i], out.back().frame, out.back().time);
      FragmentFrame ff;
      ff.frame = f, ff.time = time[i], ff.count = static_cast<long>(count[i]);
      out.push_back(ff);
    }
    FragmentFrame& ff = out.back();
    DSPDEM_CHECK(static_cast<std::size_t>(rank[i]) == ff.largest.size() + 1 && time[i] == ff.time &&
                     static_cast<long>(count[i]) == ff.count,
                 "'{}', data row {}: frame {} lists rank {} (t = {:g} s, {} fragments) after {} piece(s) (t = {:g} s, "
                 "{} fragments)",
                 fragments_csv, i + 1, f, rank[i], time[i], count[i], ff.largest.size(), ff.time, ff.count);
    ff.largest.push_back({mass[i], static_cast<int>(elements[i]), x[i], y[i], z[i]});
  }
  return out;
}

}  // namespace dspdem::report
