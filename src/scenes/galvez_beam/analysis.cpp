#include "scenes/galvez_beam/analysis.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "core/error.hpp"
#include "report/crack_sampling.hpp"
#include "report/run_data.hpp"

namespace dspdem {

namespace {
namespace fs = std::filesystem;

struct Slab {
  double zlo, zhi;
};
bool in_slab(const Vec3& p, const void* ctx) {
  const auto* s = static_cast<const Slab*>(ctx);
  return p(2) >= s->zlo && p(2) <= s->zhi;
}
}  // namespace

bool outer_line_held(const CaseConfig& c) {
  for (const auto& b : c.boundaries)
    if (b.group == "load_outer" && b.dof[1] &&
        (b.type == BoundaryConfig::Type::Fixed || (b.type == BoundaryConfig::Type::Velocity && b.value(1) == 0)))
      return true;
  return false;
}

bool outer_line_driven(const CaseConfig& c) {
  for (const auto& b : c.boundaries)
    if (b.group == "load_outer" && b.dof[1] && b.type != BoundaryConfig::Type::Fixed && b.value(1) != 0) return true;
  return false;
}

GalvezResult analyse_galvez_run(const CaseConfig& c, const std::string& run_dir, const std::string& files_dir) {
  DSPDEM_CHECK(c.mesh_generator == "galvez_beam", "{}: the Galvez beam scene needs the galvez_beam generator", c.path);
  GalvezResult r;
  r.run_dir = run_dir;
  r.D = mesh_param(c, "depth"), r.B = mesh_param(c, "thickness"), r.notch = mesh_param(c, "notch_depth");
  r.load_x = mesh_param(c, "load_inner_x"), r.outer_x = mesh_param(c, "load_outer_x");
  r.outer_held = outer_line_held(c), r.outer_driven = outer_line_driven(c);
  const report::RunData run = report::RunData::open(run_dir);
  const report::Series& s = run.series;
  const auto& t = s["time"];
  const auto& load = s["load"];
  const auto& cmod = s["cmod"];
  const auto& defl = s["deflection"];
  const auto& ke = s["kinetic"];
  const auto& ie = s["internal"];
  std::vector<double> P(t.size());
  for (std::size_t i = 0; i < t.size(); ++i) P[i] = std::abs(load[i]);
  const std::size_t ip = static_cast<std::size_t>(std::max_element(P.begin(), P.end()) - P.begin());
  r.P_peak = P[ip], r.t_peak = t[ip], r.cmod_peak = cmod[ip], r.defl_peak = -defl[ip];
  // Quasi-static: kinetic against internal energy over the second half of the loading, up
  // to the peak (while the actuator ramps up the beam rings, and the load is all inertia).
  for (std::size_t i = 0; i <= ip; ++i)
    if (P[i] > 0.5 * r.P_peak && ie[i] > 0) r.ke_ratio_max = std::max(r.ke_ratio_max, ke[i] / ie[i]);
  r.ke_ratio_peak = ie[ip] > 0 ? ke[ip] / ie[ip] : 0;
  const auto& bal = s["balance_error"];
  r.balance_max = *std::max_element(bal.begin(), bal.end());
  for (const char* k : {"kinetic", "internal", "external_work", "joint_elastic", "fracture_I", "fracture_II"})
    for (double v : s[k]) r.largest_energy = std::max(r.largest_energy, std::abs(v));
  if (!files_dir.empty()) {
    std::ofstream f(fs::path(files_dir) / "load.csv");
    f << "time_ms,cmod_mm,deflection_mm,load_kN\n";
    for (std::size_t i = 0; i < t.size(); ++i)
      f << fmt::format("{:.6g},{:.6g},{:.6g},{:.6g}\n", 1e3 * t[i], 1e3 * cmod[i], -1e3 * defl[i], 1e-3 * P[i]);
  }

  // The crack: where it starts (the first joints frame with broken joints) and its path at
  // the end, on the mid-plane and on the two faces, in slices of the ligament's height.
  r.last_frame = static_cast<Index>(run.frames.size()) - 1;
  for (std::size_t i = 0; i < run.joint_frames.size(); ++i) {
    const auto first = report::broken_joints(run.joint_frames[i].file, 1);
    if (first.empty()) continue;
    double a = 0;
    Vec3 m = Vec3::Zero();
    for (const auto& p : first) a += p.area, m += p.area * p.centroid;
    m /= a;
    r.first_crack_frame = static_cast<Index>(i), r.start_x = m(0), r.start_y = m(1);
    break;
  }
  if (!run.joint_frames.empty()) {
    // The crack of a test is what can be seen: here the damaged joints (softening or
    // broken), weighted by their width. Broken ones alone are only the part of the crack
    // that carries nothing; in this beam the load has fallen to a fifth while most of the
    // ligament still softens. By area alone, a band of barely softened joints beside the
    // crack pulls the path into it: held at its second top line, the beam softens joints
    // over x = -18..+43 mm under its top face while the open crack reaches it at +58 mm,
    // and the area-weighted path ended at +21 mm.
    const auto pieces = report::broken_joints(run.joint_frames.back().file, 1);
    for (const auto& p : pieces) r.crack_area += p.area;
    const int bins = 10;
    const Slab mid{-r.B / 6, r.B / 6}, front{r.B / 3, r.B / 2 + 1e-9}, back{-r.B / 2 - 1e-9, -r.B / 3};
    const auto w = report::PathWeight::AreaWidth;
    r.path_mid = report::trace_path(pieces, 1, 0, r.notch, r.D, bins, in_slab, &mid, w);
    r.path_front = report::trace_path(pieces, 1, 0, r.notch, r.D, bins, in_slab, &front, w);
    r.path_back = report::trace_path(pieces, 1, 0, r.notch, r.D, bins, in_slab, &back, w);
    if (!r.path_mid.empty()) r.top_y = r.path_mid.back().first, r.top_x = r.path_mid.back().second;
  }
  if (!files_dir.empty()) {
    std::ofstream f(fs::path(files_dir) / "crack_path.csv");
    f << "plane,y_mm,x_mm\n";
    for (const auto& [name, path] :
         {std::pair{"mid", &r.path_mid}, std::pair{"front", &r.path_front}, std::pair{"back", &r.path_back}})
      for (const auto& [y, x] : *path) f << fmt::format("{},{:.6g},{:.6g}\n", name, 1e3 * y, 1e3 * x);
    std::ofstream m(fs::path(files_dir) / "crack_mid.csv");  // numeric, for the plot
    m << "x_mm,y_mm\n";
    for (const auto& [y, x] : r.path_mid) m << fmt::format("{:.6g},{:.6g}\n", 1e3 * x, 1e3 * y);
  }
  const RunSummary& sum = run.summary;
  r.fragments = static_cast<int>(sum.fragments);
  for (double m : sum.largest_fragment_masses) r.mass_fractions.push_back(m / sum.total_mass);
  r.wall_s = sum.wall_s, r.steps = sum.steps, r.dt = sum.dt, r.dt_start = sum.dt_start, r.elements = sum.elements,
  r.joints = sum.joints;
  return r;
}

}  // namespace dspdem
