#include "app/report_command.hpp"

#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkIdList.h>
#include <vtkUnstructuredGrid.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include "app/render_command.hpp"
#include "app/run_command.hpp"
#include "core/error.hpp"
#include "core/log.hpp"
#include "core/timer.hpp"
#include "io/case_config.hpp"
#include "io/staging.hpp"
#include "post/brazilian.hpp"
#include "render/plot.hpp"
#include "render/series.hpp"

namespace dspdem {

namespace {
namespace fs = std::filesystem;

// The paper plots the stresses along the diameter at 33.0 kN of its 40.6 kN peak.
constexpr Real kProfileFraction = 33.0 / 40.6;

struct Column {
  std::vector<std::string> names;
  std::vector<std::vector<double>> cols;
  const std::vector<double>& operator[](const std::string& n) const {
    for (std::size_t i = 0; i < names.size(); ++i)
      if (names[i] == n) return cols[i];
    fail("series.csv has no column '{}'", n);
  }
};

std::string read_summary(const std::string& run_dir) {
  std::ifstream f(fs::path(run_dir) / "summary.json");
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

// A number from summary.json (flat keys only).
double summary_number(const std::string& run_dir, const std::string& key) {
  const std::regex re("\"" + key + "\": ([-0-9.eE+]+)");
  std::smatch m;
  const std::string s = read_summary(run_dir);
  if (!std::regex_search(s, m, re)) fail("'{}/summary.json' has no number '{}'", run_dir, key);
  return std::stod(m[1]);
}

std::vector<double> summary_list(const std::string& run_dir, const std::string& key) {
  const std::regex re("\"" + key + "\": \\[([^\\]]*)\\]");
  std::smatch m;
  const std::string s = read_summary(run_dir);
  std::vector<double> out;
  if (!std::regex_search(s, m, re)) return out;
  std::stringstream items(m[1].str());
  for (std::string v; std::getline(items, v, ',');) out.push_back(std::stod(v));
  return out;
}

struct DiscResult {
  std::string run_dir;
  Real D = 0, L = 0, ft = 0;
  Real P_peak = 0, t_peak = 0, split = 0, split_err = 0;
  Real P_profile = 0, t_profile = 0;
  Real l2_xx = 0, l2_yy = 0, centre_xx = 0, centre_yy = 0;
  Real face_xx = 0, mid_xx = 0;  ///< sigma_xx near the centre on the end faces / mid-plane, vs 2D
  Index profile_frame = -1, init_frame = -1, last_frame = -1;
  Real t_init = -1;
  Real balance_max = 0, largest_energy = 0;
  int fragments = 0;
  std::vector<double> mass_fractions;
  double wall_s = 0, dt = 0;
  long steps = 0;
};

// Loads, splitting strength, stress profile and ledger of one finished run.
DiscResult analyse(const CaseConfig& c, const std::string& run_dir, bool write_files) {
  DiscResult r;
  r.run_dir = run_dir;
  r.D = c.mesh_num.at("diameter"), r.L = c.mesh_num.at("thickness");
  for (std::size_t b = 0; b < c.bodies.size(); ++b)
    if (c.bodies[b].fracture != BodyConfig::Fracture::None)
      for (std::size_t m = 0; m < c.materials.size(); ++m)
        if (c.materials[m].name == c.bodies[b].material) r.ft = c.joint_materials[m].ft;
  DSPDEM_CHECK(c.walls.size() == 2, "{}: dspdem report expects the two plates as [[walls]] (found {})", c.path,
               c.walls.size());
  Column s;
  render::read_csv((fs::path(run_dir) / "series.csv").string(), s.names, s.cols);
  const auto& t = s["time"];
  const auto& f_top = s[c.walls[0].wall.name + "_fy"];
  const auto& f_bot = s[c.walls[1].wall.name + "_fy"];
  const Real closing_speed = c.walls[0].wall.velocity_target.norm() + c.walls[1].wall.velocity_target.norm();
  std::vector<double> P(t.size());
  for (std::size_t i = 0; i < t.size(); ++i) P[i] = 0.5 * (std::abs(f_top[i]) + std::abs(f_bot[i]));
  const std::size_t ip = static_cast<std::size_t>(std::max_element(P.begin(), P.end()) - P.begin());
  r.P_peak = P[ip], r.t_peak = t[ip];
  r.split = post::splitting_stress(r.P_peak, r.D, r.L);
  r.split_err = r.ft > 0 ? r.split / r.ft - 1 : 0;
  const auto& broken = s["broken_joints"];
  for (std::size_t i = 0; i < t.size(); ++i)
    if (broken[i] > 0) {
      r.t_init = t[i];
      break;
    }
  const auto& bal = s["balance_error"];
  r.balance_max = *std::max_element(bal.begin(), bal.end());
  for (const char* k : {"kinetic", "internal", "external_work", "joint_elastic", "fracture_I", "fracture_II"}) {
    const auto& col = s[k];
    for (double v : col) r.largest_energy = std::max(r.largest_energy, std::abs(v));
  }
  if (write_files) {
    std::ofstream f(fs::path(run_dir) / "load.csv");
    f << "time_ms,closure_mm,load_kN\n";
    for (std::size_t i = 0; i < t.size(); ++i)
      f << fmt::format("{:.6g},{:.6g},{:.6g}\n", 1e3 * t[i], 1e3 * closing_speed * t[i], 1e-3 * P[i]);
  }

  // Frame for the stress profile: the paper's 33/40.6 of the peak, taken before the first
  // broken joint (the analytic solution is elastic): when the peak comes late, the last
  // frame before cracking.
  const auto frames = render::read_series(run_dir);
  auto load_at = [&](double time) {
    std::size_t k = static_cast<std::size_t>(std::lower_bound(t.begin(), t.end(), time - 1e-15) - t.begin());
    return P[std::min(k, P.size() - 1)];
  };
  Real best = INFINITY;
  for (std::size_t i = 0; i < frames.size(); ++i) {
    if (frames[i].time > r.t_peak || (r.t_init >= 0 && frames[i].time >= r.t_init)) break;
    const Real d = std::abs(load_at(frames[i].time) - kProfileFraction * r.P_peak);
    if (d < best) best = d, r.profile_frame = static_cast<Index>(i);
  }
  r.last_frame = static_cast<Index>(frames.size()) - 1;
  for (std::size_t i = 0; i < frames.size() && r.t_init >= 0; ++i)
    if (frames[i].time >= r.t_init) {
      r.init_frame = static_cast<Index>(i);
      break;
    }
  DSPDEM_CHECK(r.profile_frame >= 0, "{}: no frame before the peak load; lower [output] frame_interval", run_dir);
  r.t_profile = frames[r.profile_frame].time;
  r.P_profile = load_at(r.t_profile);
  auto g = render::read_frame(frames[r.profile_frame].file);
  vtkDataArray* stress = g->GetCellData()->GetArray("stress");
  DSPDEM_CHECK(stress && stress->GetNumberOfComponents() == 6, "'{}' has no 6-component cell array 'stress'",
               frames[r.profile_frame].file);
  // Elements whose centroid lies within half an element size of the loaded diameter
  // (x = 0, every z), in 16 bins over the central 80 % of it. Each is compared with the
  // analytic field at its own centroid (an element at x = h/4 near a load point is in the
  // radial compression of that load, not on the axis), averaged over the same elements.
  const Real h = c.mesh_num.count("size") ? c.mesh_num.at("size") : 0.05 * r.D;
  const int nbins = 16;
  const Real y0 = -0.4 * r.D, dy = 0.8 * r.D / nbins;
  std::vector<double> sxx(nbins, 0), syy(nbins, 0), axx(nbins, 0), ayy(nbins, 0), ysum(nbins, 0), cnt(nbins, 0);
  double cxx = 0, cyy = 0, caxx = 0, cayy = 0, ccnt = 0;
  double fxx = 0, faxx = 0, mxx = 0, maxx = 0;  // end-face and mid-plane layers, |y| < h
  vtkNew<vtkIdList> ids;
  for (vtkIdType e = 0; e < g->GetNumberOfCells(); ++e) {
    g->GetCellPoints(e, ids);
    Vec3 cen = Vec3::Zero();
    for (vtkIdType k = 0; k < ids->GetNumberOfIds(); ++k) {
      double p[3];
      g->GetPoint(ids->GetId(k), p);
      cen += Vec3(p[0], p[1], p[2]);
    }
    cen /= static_cast<Real>(ids->GetNumberOfIds());
    if (std::abs(cen(0)) > 0.5 * h) continue;
    const double xx = stress->GetComponent(e, 0), yy = stress->GetComponent(e, 1);
    const auto a = post::point_load_stress(r.P_profile, r.D, r.L, cen(0), cen(1));
    if (std::abs(cen(1)) < 0.5 * h) cxx += xx, cyy += yy, caxx += a.xx, cayy += a.yy, ++ccnt;
    if (std::abs(cen(1)) < h && std::abs(cen(2)) > 0.5 * r.L - 0.5 * h) fxx += xx, faxx += a.xx;
    if (std::abs(cen(1)) < h && std::abs(cen(2)) < 0.5 * h) mxx += xx, maxx += a.xx;
    const int b = static_cast<int>(std::floor((cen(1) - y0) / dy));
    if (b < 0 || b >= nbins) continue;
    sxx[b] += xx, syy[b] += yy, axx[b] += a.xx, ayy[b] += a.yy, ysum[b] += cen(1), ++cnt[b];
  }
  std::vector<double> num_xx, num_yy, ref_xx, ref_yy, ys;
  for (int b = 0; b < nbins; ++b) {
    if (cnt[b] == 0) continue;
    ys.push_back(ysum[b] / cnt[b]);
    num_xx.push_back(sxx[b] / cnt[b]), num_yy.push_back(syy[b] / cnt[b]);
    ref_xx.push_back(axx[b] / cnt[b]), ref_yy.push_back(ayy[b] / cnt[b]);
  }
  r.l2_xx = post::relative_l2(num_xx, ref_xx), r.l2_yy = post::relative_l2(num_yy, ref_yy);
  if (ccnt > 0) r.centre_xx = cxx / caxx - 1, r.centre_yy = cyy / cayy - 1;
  if (faxx > 0) r.face_xx = fxx / faxx - 1;
  if (maxx > 0) r.mid_xx = mxx / maxx - 1;
  if (write_files) {
    std::ofstream fn(fs::path(run_dir) / "profile.csv"), fr(fs::path(run_dir) / "profile_analytic.csv");
    fn << "y_mm,sigma_xx_MPa,sigma_yy_MPa\n", fr << "y_mm,sigma_xx_MPa,sigma_yy_MPa\n";
    for (std::size_t i = 0; i < ys.size(); ++i) {
      fn << fmt::format("{:.6g},{:.6g},{:.6g}\n", 1e3 * ys[i], 1e-6 * num_xx[i], 1e-6 * num_yy[i]);
      fr << fmt::format("{:.6g},{:.6g},{:.6g}\n", 1e3 * ys[i], 1e-6 * ref_xx[i], 1e-6 * ref_yy[i]);
    }
  }
  r.fragments = static_cast<int>(summary_number(run_dir, "fragments"));
  const double total = summary_number(run_dir, "total_mass");
  for (double m : summary_list(run_dir, "largest_fragment_masses")) r.mass_fractions.push_back(m / total);
  r.wall_s = summary_number(run_dir, "wall_s");
  r.steps = static_cast<long>(summary_number(run_dir, "steps"));
  r.dt = summary_number(run_dir, "dt");
  return r;
}

struct Variant {
  std::string name, knob;
  CaseConfig c;
};

// The sweep: three mesh sizes at the reference settings, then each knob moved alone.
std::vector<Variant> study_variants(const CaseConfig& base) {
  std::vector<Variant> v;
  const Real h = base.mesh_num.at("size");
  for (Real f : {1.6, 1.25, 1.0}) {
    Variant x{fmt::format("size_{:.1f}mm", 1e3 * h * f), "mesh size", base};
    x.c.mesh_num["size"] = h * f;
    if (base.mesh_num.count("load_size")) x.c.mesh_num["load_size"] = base.mesh_num.at("load_size") * f;
    v.push_back(x);
  }
  {
    const Real p0 = base.joint_materials.empty() ? 100 : base.joint_materials.front().penalty;
    const Real p1 = p0 >= 100 ? 30 : 100;
    Variant x{fmt::format("penalty_{:.0f}", p1), fmt::format("joint penalty {:.0f} (reference {:.0f})", p1, p0), base};
    for (auto& jm : x.c.joint_materials) jm.penalty = p1;
    v.push_back(x);
  }
  {
    Variant x{"rate_x4", "plates 4x faster", base};
    for (auto& w : x.c.walls) w.wall.velocity_target *= 4;
    x.c.t_end /= 4, x.c.frame_interval /= 4, x.c.series_interval /= 4;
    v.push_back(x);
  }
  {
    const bool coro = !base.bodies.empty() && base.bodies.front().kinematics == Kinematics::Corotational;
    Variant x{coro ? "small_strain" : "corotational",
              coro ? "small-strain update (reference corotational)" : "corotational update (reference small strain)",
              base};
    for (auto& b : x.c.bodies) b.kinematics = coro ? Kinematics::SmallStrain : Kinematics::Corotational;
    v.push_back(x);
  }
  {
    // Joints only in a central band of 0.2 D: the rest of the disc is one continuum (fewer
    // joints and nodes, a larger stable step where the joints limited it).
    Variant x{"band_0.2D", "joints only in the band |x| < 0.1 D (reference: everywhere)", base};
    x.c.mesh_num["band_width"] = 0.2 * base.mesh_num.at("diameter");
    for (auto& b : x.c.bodies)
      if (b.fracture != BodyConfig::Fracture::None)
        b.fracture = BodyConfig::Fracture::Groups, b.fracture_groups = {"disc_band"};
    v.push_back(x);
  }
  {
    const bool split = base.mesh_num.count("split_plane") && base.mesh_num.at("split_plane") != 0;
    Variant x{split ? "unaligned" : "split_plane",
              split ? "mesh not aligned with the loaded diameter (reference: split_plane)"
                    : "loaded diametral plane in the mesh (reference: unaligned)",
              base};
    x.c.mesh_num["split_plane"] = split ? 0 : 1;
    v.push_back(x);
  }
  return v;
}

std::string pct(Real x) { return fmt::format("{:+.1f} %", 100 * x); }

}  // namespace

int report_command(const ReportArgs& a) {
  Timer total;
  const CaseConfig c = read_case(a.case_file, a.sets);
  DSPDEM_CHECK(c.mesh_generator == "brazilian_disc",
               "{}: dspdem report knows the Brazilian disc scene (mesh generator brazilian_disc); this case uses '{}'",
               c.path, c.mesh_generator.empty() ? c.mesh_file : c.mesh_generator);
  const std::string dir = a.out_dir.empty() ? (fs::path("results") / (c.name + "_report")).string() : a.out_dir;
  const std::string run_dir = a.from_run.empty() ? (fs::path(dir) / "run").string() : a.from_run;
  fs::create_directories(dir);
  if (a.from_run.empty()) {
    RunOptions ro;
    ro.out_dir = run_dir;
    run_case(c, ro);
  } else {
    DSPDEM_CHECK(fs::exists(fs::path(run_dir) / "summary.json"),
                 "--from-run {}: no summary.json there (not the output folder of a finished run)", run_dir);
  }
  const DiscResult r = analyse(c, run_dir, true);
  const fs::path img = fs::path(run_dir) / "images";
  if (!a.no_render) {
    RenderArgs ra;
    ra.run_dir = run_dir;
    ra.views = {"stress", "fragments"};
    render_command(ra);
  }
  fs::create_directories(img / "plots");
  auto plot = [&](const std::string& csv, const std::string& x, std::vector<std::string> y, const std::string& ref,
                  const std::string& title, const std::string& png) {
    render::PlotSpec s{x, std::move(y), ref, title};
    render::plot_csv((fs::path(run_dir) / csv).string(), s, (img / "plots" / png).string());
  };
  plot("load.csv", "time_ms", {"load_kN"}, "", "plate load [kN] against time [ms]", "load_time.png");
  plot("load.csv", "closure_mm", {"load_kN"}, "", "plate load [kN] against plate closure [mm]", "load_closure.png");
  plot("profile.csv", "y_mm", {"sigma_xx_MPa", "sigma_yy_MPa"}, (fs::path(run_dir) / "profile_analytic.csv").string(),
       fmt::format("stresses along the loaded diameter at {:.1f} kN [MPa]; dashed: analytic", 1e-3 * r.P_profile),
       "profile.png");
  plot("series.csv", "time", {"balance_error"}, "", "energy balance error (fraction of the largest term)",
       "balance_error.png");

  // Study.
  std::string study_md;
  if (a.study) {
    std::vector<std::pair<Variant, DiscResult>> rows;
    for (auto& v : study_variants(c)) {
      log::info("study: {} ({})", v.name, v.knob);
      RunOptions vo;
      vo.out_dir = (fs::path(dir) / "study" / v.name).string();
      run_case(v.c, vo);
      rows.emplace_back(v, analyse(v.c, vo.out_dir, false));
    }
    const std::string csv = (fs::path(dir) / "study" / "study.csv").string();
    {
      std::ofstream f(csv);
      f << "wall_s,split_error_pct,l2_xx_pct\n";
      for (const auto& [v, s] : rows)
        f << fmt::format("{:.4g},{:.4g},{:.4g}\n", s.wall_s, 100 * std::abs(s.split_err), 100 * s.l2_xx);
    }
    render::PlotSpec s{"wall_s", {"split_error_pct", "l2_xx_pct"}, "", "error [%] against wall time [s]"};
    render::plot_csv(csv, s, (img / "plots" / "study.png").string());
    study_md +=
        "| variant | knob | elements | wall time [s] | steps | dt [s] | 2P/(pi D L) [MPa] | vs f_t | L2 sigma_xx | "
        "L2 sigma_yy |\n|---|---|---|---|---|---|---|---|---|---|\n";
    for (const auto& [v, s] : rows)
      study_md += fmt::format("| {} | {} | {:.0f} | {:.1f} | {} | {:.3g} | {:.3f} | {} | {:.1f} % | {:.1f} % |\n",
                              v.name, v.knob, summary_number(s.run_dir, "elements"), s.wall_s, s.steps, s.dt,
                              1e-6 * s.split, pct(s.split_err), 100 * s.l2_xx, 100 * s.l2_yy);
  }

  // report.md
  const std::string rel = fs::relative(run_dir, dir).string();
  std::string md;
  md += fmt::format(
      "# Brazilian disc: report\n\nCase `{}` ({}), run in `run/`. Paper: section 2.2 of the seed "
      "(METHOD.md section 5); analytic reference: refdata/brazilian_analytic.md.\n\n",
      c.path, c.name);
  md += fmt::format(
      "Disc D = {:.1f} mm, L = {:.1f} mm, {:.0f} elements, {:.0f} joints; plates closing at {:.3g} m/s "
      "in all; input f_t = {:.2f} MPa. Run: {} steps of {:.3g} s, {:.1f} s wall time.\n\n",
      1e3 * r.D, 1e3 * r.L, summary_number(run_dir, "elements"), summary_number(run_dir, "joints"),
      c.walls[0].wall.velocity_target.norm() + c.walls[1].wall.velocity_target.norm(), 1e-6 * r.ft, r.steps, r.dt,
      r.wall_s);
  md += "## Load and splitting strength\n\n";
  md += fmt::format(
      "Peak plate load P = {:.2f} kN at t = {:.3f} ms. Splitting strength 2P/(pi D L) = {:.3f} MPa, {} "
      "against the input f_t = {:.2f} MPa (the paper: 40.6 kN, 2.54 MPa for 2.3 MPa, +10 %).\n\n",
      1e-3 * r.P_peak, 1e3 * r.t_peak, 1e-6 * r.split, pct(r.split_err), 1e-6 * r.ft);
  md +=
      "![load against time](run/images/plots/load_time.png)\n![load against closure](run/images/plots/"
      "load_closure.png)\n\n";
  md += "## Stresses along the loaded diameter\n\n";
  md += fmt::format(
      "At P = {:.2f} kN ({:.0f} % of the peak; the paper uses 33.0 of 40.6 kN = 81 %; never after the first broken "
      "joint), frame {} (t = {:.3f} ms). "
      "Elements within half an element size of x = 0, averaged in 16 bins over the central 80 % of the diameter, "
      "against the point-load solution (paper eqs. 24-25 on the axis; each element is compared with the full "
      "two-load field at its own centroid, averaged in the same bins). Relative L2 error: sigma_xx {:.1f} %, sigma_yy "
      "{:.1f} %. "
      "At the centre: sigma_xx {}, sigma_yy {}. The disc is 3D and the reference is plane stress: through the "
      "thickness at the centre (|y| < h), sigma_xx is {} on the end faces (outer half-element layer) and {} on "
      "the mid-plane against the 2D value, so cracking starts on the faces below the nominal 2P/(pi D L) = f_t."
      "\n\n![profile](run/images/plots/profile.png)\n\n",
      1e-3 * r.P_profile, 100 * r.P_profile / r.P_peak, r.profile_frame, 1e3 * r.t_profile, 100 * r.l2_xx,
      100 * r.l2_yy, pct(r.centre_xx), pct(r.centre_yy), pct(r.face_xx), pct(r.mid_xx));
  md += "## Fracture\n\n";
  std::string fr;
  for (std::size_t i = 0; i < std::min<std::size_t>(4, r.mass_fractions.size()); ++i)
    fr += fmt::format("{}{:.3f}", i ? ", " : "", r.mass_fractions[i]);
  md += fmt::format("{} fragments; largest mass fractions {}. First broken joint at t = {:.3f} ms (frame {}).\n\n",
                    r.fragments, fr, 1e3 * r.t_init, r.init_frame);
  if (!a.no_render) {
    for (const char* view : {"fragments", "stress"})
      md += fmt::format(
          "{}: start, crack initiation, failure\n\n![](run/images/{}/frame_0000.png)\n![](run/images/{}/"
          "frame_{:04d}.png)\n![](run/images/{}/frame_{:04d}.png)\n\nAnimation: `run/images/{}.ogv`.\n\n",
          view, view, view, std::max<Index>(0, r.init_frame), view, r.last_frame, view);
  }
  md += "## Energy ledger\n\n";
  md += fmt::format(
      "Largest balance error over the run {:.2e} of the largest energy term ({:.4g} J).\n\n"
      "![energy](run/images/plots/energy.png)\n![balance](run/images/plots/balance_error.png)\n\n",
      r.balance_max, r.largest_energy);
  if (a.study) {
    md += "## Speed against error\n\n" + study_md + "\n![error against wall time](run/images/plots/study.png)\n\n";
  }
  // Links point at the run folder, wherever it is (--from-run).
  for (const std::string from : {"](run/", "`run/"}) {
    const std::string to = from.substr(0, from.size() - 4) + rel + "/";
    for (std::size_t p = md.find(from); p != std::string::npos; p = md.find(from, p + to.size()))
      md.replace(p, from.size(), to);
  }
  write_file_atomic((fs::path(dir) / "report.md").string(), md);
  log::info("report: {}/report.md ({:.1f} s)", dir, total.seconds());
  return 0;
}

}  // namespace dspdem
