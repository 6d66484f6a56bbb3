#include "scenes/murray_beam/analysis.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "core/error.hpp"
#include "report/crack_sampling.hpp"
#include "report/fragment_history.hpp"
#include "report/run_data.hpp"

namespace dspdem {

namespace {
namespace fs = std::filesystem;

struct PlaneCrack {
  double x = 0, area = 0, y = 0;  // area-weighted mean x and y of its broken joints
  double y_lo = 1e300, y_hi = -1e300;
};

// Broken joints facing along x (|n_x| > 0.9), grouped into planes: sorted by x, a new plane
// wherever the gap to the previous joint exceeds `gap` (a quarter element: the joints of one
// crack share a mesh plane, and move together when its faces part).
std::vector<PlaneCrack> crack_planes(const std::vector<report::CrackPiece>& pieces, double gap) {
  std::vector<const report::CrackPiece*> v;
  for (const auto& p : pieces)
    if (std::abs(p.normal(0)) > 0.9) v.push_back(&p);
  std::sort(v.begin(), v.end(), [](auto* a, auto* b) { return a->centroid(0) < b->centroid(0); });
  std::vector<PlaneCrack> out;
  double last = -1e300;
  for (const auto* p : v) {
    if (p->centroid(0) - last > gap) out.emplace_back();
    last = p->centroid(0);
    PlaneCrack& c = out.back();
    c.area += p->area, c.x += p->area * p->centroid(0), c.y += p->area * p->centroid(1);
    c.y_lo = std::min(c.y_lo, p->centroid(1)), c.y_hi = std::max(c.y_hi, p->centroid(1));
  }
  for (auto& c : out) c.x /= c.area, c.y /= c.area;
  return out;
}
}  // namespace

MurrayResult analyse_murray_run(const CaseConfig& c, const std::string& run_dir, const std::string& files_dir) {
  DSPDEM_CHECK(c.mesh_generator == "murray_beam", "{}: the impact beam scene needs the murray_beam generator", c.path);
  MurrayResult r;
  r.run_dir = run_dir;
  r.L = mesh_param(c, "length"), r.H = mesh_param(c, "depth"), r.W = mesh_param(c, "width");
  r.span = mesh_param(c, "span"), r.gap = mesh_param(c, "impactor_spacing");
  const double hx = r.L / mesh_param(c, "nx");
  const report::RunData run = report::RunData::open(run_dir);
  const report::Series& s = run.series;
  for (const char* col : {"impactor_left_vy", "impactor_right_vy", "support_left_fy", "support_right_fy",
                          "midspan_deflection", "max_deflection"})
    DSPDEM_CHECK(s.has(col),
                 "{}: the impact beam scene needs series column '{}' (free cylinder walls impactor_left/right, "
                 "walls support_left/right, monitors midspan_deflection and max_deflection, as in "
                 "cases/murray_beam.toml)",
                 run_dir, col);
  const auto& t = s["time"];
  const std::size_t n = t.size();
  const auto &vl = s["impactor_left_vy"], &vr = s["impactor_right_vy"];
  const auto &fl = s["impactor_left_fy"], &fr = s["impactor_right_fy"];
  const auto &sl = s["support_left_fy"], &sr = s["support_right_fy"];
  const auto &mid = s["midspan_deflection"], &mx = s["max_deflection"];
  for (std::size_t i = 0; i < n; ++i) {
    if (mx[i] > r.max_deflection) r.max_deflection = mx[i], r.t_max_deflection = t[i];
    r.impact_force_peak = std::max({r.impact_force_peak, std::abs(fl[i]), std::abs(fr[i])});
    r.support_force_peak = std::max({r.support_force_peak, std::abs(sl[i]), std::abs(sr[i])});
  }
  r.midspan_at_end = -mid[n - 1];
  r.v_impactor_end = 0.5 * (vl[n - 1] + vr[n - 1]);
  const auto& bal = s["balance_error"];
  r.balance_max = *std::max_element(bal.begin(), bal.end());
  for (const char* k : {"kinetic", "internal", "external_work", "joint_elastic", "fracture_I", "contact_elastic"})
    for (double v : s[k]) r.largest_energy = std::max(r.largest_energy, std::abs(v));
  r.fracture_energy = s["fracture_I"][n - 1];
  if (s.has("beam_momentum")) {
    double m_l = 0, m_r = 0;
    for (const auto& w : c.walls)
      if (w.wall.name == "impactor_left")
        m_l = w.wall.mass;
      else if (w.wall.name == "impactor_right")
        m_r = w.wall.mass;
    const auto& pb = s["beam_momentum"];
    auto p = [&](std::size_t i) { return pb[i] + m_l * vl[i] + m_r * vr[i]; };
    r.momentum_error = 0;
    double J = 0;  // impulse of the supports on the beam: minus the force on them, trapezoidal
    for (std::size_t i = 1; i < n; ++i) {
      J -= 0.5 * (t[i] - t[i - 1]) * (sl[i] + sr[i] + sl[i - 1] + sr[i - 1]);
      r.momentum_error = std::max(r.momentum_error, std::abs(p(i) - p(0) - J) / std::abs(p(0)));
    }
    r.support_impulse = J;
  }
  r.kinetic_start = s["kinetic"][0], r.kinetic_end = s["kinetic"][n - 1];
  if (!files_dir.empty()) {
    std::ofstream f(fs::path(files_dir) / "murray_series.csv");
    f << "time_ms,midspan_deflection_mm,max_deflection_mm,impactor_left_vy,impactor_right_vy,impactor_left_kN,"
         "impactor_right_kN,support_left_kN,support_right_kN\n";
    for (std::size_t i = 0; i < n; ++i)
      f << fmt::format("{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g}\n", 1e3 * t[i], -1e3 * mid[i],
                       1e3 * mx[i], vl[i], vr[i], 1e-3 * std::abs(fl[i]), 1e-3 * std::abs(fr[i]),
                       1e-3 * std::abs(sl[i]), 1e-3 * std::abs(sr[i]));
  }

  // Fragments over time (fragments.csv: per frame the count and the 20 largest pieces).
  const RunSummary& sum = run.summary;
  r.total_mass = sum.total_mass;
  r.fragments = static_cast<int>(sum.fragments);
  const auto history = report::fragment_history((fs::path(run_dir) / "fragments.csv").string());
  const double main_mass = MurrayResult::main_piece_fraction * r.total_mass;
  for (const auto& f : history)
    if (r.t_main5 < 0 && f.count_at_least(main_mass) >= 5) r.t_main5 = f.time;
  if (!history.empty())
    for (const auto& p : history.back().largest)
      if (p.mass >= main_mass) r.pieces.push_back({p.mass, p.mass / r.total_mass, p.x, p.y});
  r.main_pieces = static_cast<int>(r.pieces.size());
  if (!files_dir.empty()) {
    std::ofstream f(fs::path(files_dir) / "fragments_time.csv");
    f << "time_ms,fragments,main_pieces\n";
    for (const auto& fh : history)
      f << fmt::format("{:.6g},{},{}\n", 1e3 * fh.time, fh.count, fh.count_at_least(main_mass));
  }

  // Cracks: planes of broken joints across the beam, followed from frame to frame. A joint
  // is placed where it was in the first frame (the cells are the same joints in every
  // frame), so that a plane keeps its x while the pieces on either side move away.
  const double section = r.H * r.W;
  const auto ref = run.joint_frames.empty() ? std::vector<report::CrackPiece>{}
                                            : report::broken_joints(run.joint_frames.front().file, 0);
  for (std::size_t i = 0; i < run.joint_frames.size(); ++i) {
    const double ti = run.joint_frames[i].time;
    const auto state = report::joint_states(run.joint_frames[i].file);
    DSPDEM_CHECK(state.size() == ref.size(), "'{}' has {} joints, the first joints frame {}", run.joint_frames[i].file,
                 state.size(), ref.size());
    std::vector<report::CrackPiece> broken;
    for (std::size_t j = 0; j < state.size(); ++j)
      if (state[j] >= 2) broken.push_back(ref[j]);
    const auto planes = crack_planes(broken, 0.25 * hx);
    for (const auto& p : planes) {
      auto it = std::find_if(r.cracks.begin(), r.cracks.end(),
                             [&](const BeamCrack& k) { return std::abs(k.x - p.x) < 0.5 * hx; });
      if (it == r.cracks.end()) {
        r.cracks.push_back({p.x, ti, p.y, p.y_lo, p.y_hi, -1, 0});
        it = r.cracks.end() - 1;
      }
      it->final_fraction = p.area / section;
      if (it->t_through < 0 && p.area >= MurrayResult::through_fraction * section) it->t_through = ti;
    }
  }
  std::stable_sort(r.cracks.begin(), r.cracks.end(), [](const BeamCrack& a, const BeamCrack& b) {
    return a.t_first < b.t_first || (a.t_first == b.t_first && a.x < b.x);
  });
  if (!files_dir.empty()) {
    std::ofstream f(fs::path(files_dir) / "cracks.csv");
    f << "x_mm,first_ms,y_first_mm,y_lo_mm,y_hi_mm,through_ms,final_fraction\n";
    for (const auto& k : r.cracks)
      f << fmt::format("{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.4f}\n", 1e3 * k.x, 1e3 * k.t_first,
                       1e3 * k.y_first, 1e3 * k.y_lo, 1e3 * k.y_hi, k.t_through < 0 ? -1.0 : 1e3 * k.t_through,
                       k.final_fraction);
  }
  r.last_frame = static_cast<Index>(run.frames.size()) - 1;
  auto frame_at = [&](double t) -> Index {  // the first frame at or after t
    for (std::size_t i = 0; i < run.frames.size(); ++i)
      if (run.frames[i].time >= t - 1e-12) return static_cast<Index>(i);
    return -1;
  };
  if (!r.cracks.empty()) r.first_crack_frame = frame_at(r.cracks.front().t_first);
  if (r.t_main5 >= 0) r.main5_frame = frame_at(r.t_main5);
  r.wall_s = sum.wall_s, r.steps = sum.steps, r.dt = sum.dt, r.dt_start = sum.dt_start, r.elements = sum.elements,
  r.joints = sum.joints;
  return r;
}

}  // namespace dspdem
