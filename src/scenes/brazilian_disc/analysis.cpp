#include "scenes/brazilian_disc/analysis.hpp"

#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkIdList.h>
#include <vtkUnstructuredGrid.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "core/error.hpp"
#include "render/plot.hpp"
#include "render/series.hpp"
#include "report/crack_sampling.hpp"
#include "report/field_sampling.hpp"
#include "report/run_data.hpp"
#include "scenes/brazilian_disc/point_load.hpp"

namespace dspdem {

namespace {
namespace fs = std::filesystem;

}  // namespace

namespace {
fs::path joints_frame(const std::string& run_dir, Index frame) {
  return fs::path(run_dir) / "frames" / fmt::format("joints_{:04d}.vtu", frame);
}

// Broken joints (state 2) of the joints frame at the split: area-weighted mean |x| of their
// centroids (how wide the broken band is), the share of their area within D/4 of a plate
// (|y| > D/4), and the crack traced along y in element-sized slices (where the band runs:
// its mean and largest distance from x = 0). A band of crushed facets centred on the
// diameter has a large mean |x| but a path near x = 0; an inclined crack has both large.
void crack_path(const std::string& run_dir, Real h, DiscResult& r, Index frame) {
  const fs::path jf = joints_frame(run_dir, frame);
  if (frame < 0 || !fs::exists(jf)) return;
  double area = 0, ax = 0, near = 0;
  const auto pieces = report::broken_joints(jf.string());
  for (const auto& p : pieces) {
    area += p.area, ax += p.area * std::abs(p.centroid(0));
    if (std::abs(p.centroid(1)) > 0.25 * r.D) near += p.area;
  }
  r.crack_area = area;
  if (area > 0) r.crack_mean_x = ax / area, r.crack_near_plates = near / area;
  const int bins = std::max(4, static_cast<int>(std::lround(r.D / h)));
  const auto path = report::trace_path(pieces, 1, 0, -0.5 * r.D, 0.5 * r.D, bins);
  if (path.empty()) return;
  double sum = 0, worst = 0;
  for (const auto& [y, x] : path) sum += std::abs(x), worst = std::max(worst, std::abs(x));
  r.crack_path_mean_x = sum / static_cast<double>(path.size()), r.crack_path_max_x = worst;
  r.crack_path_slices = static_cast<int>(path.size()), r.crack_path_bins = bins;
}

// The damaged zone (softening or broken joints) at the first frame at or after the peak:
// area-weighted mean |x| of its centroids.
void damage_at_peak(const std::string& run_dir, DiscResult& r, Index frame) {
  const fs::path jf = joints_frame(run_dir, frame);
  if (frame < 0 || !fs::exists(jf)) return;
  double area = 0, ax = 0;
  for (const auto& p : report::broken_joints(jf.string(), 1)) area += p.area, ax += p.area * std::abs(p.centroid(0));
  if (area > 0) r.peak_damage_mean_x = ax / area, r.peak_frame = frame;
}
}  // namespace

DiscResult analyse_disc_run(const CaseConfig& c, const std::string& run_dir, const std::string& files_dir,
                            Real profile_load) {
  DiscResult r;
  r.run_dir = run_dir;
  r.D = c.mesh_num.at("diameter"), r.L = c.mesh_num.at("thickness");
  for (std::size_t b = 0; b < c.bodies.size(); ++b)
    if (c.bodies[b].fracture != BodyConfig::Fracture::None)
      for (std::size_t m = 0; m < c.materials.size(); ++m)
        if (c.materials[m].name == c.bodies[b].material) r.ft = c.joint_materials[m].ft;
  DSPDEM_CHECK(c.walls.size() == 2, "{}: dspdem report expects the two plates as [[walls]] (found {})", c.path,
               c.walls.size());
  const report::RunData run = report::RunData::open(run_dir);
  const report::Series& s = run.series;
  const auto& t = s["time"];
  const auto& f_top = s[c.walls[0].wall.name + "_fy"];
  const auto& f_bot = s[c.walls[1].wall.name + "_fy"];
  const Real closing_speed = c.walls[0].wall.velocity_target.norm() + c.walls[1].wall.velocity_target.norm();
  std::vector<double> P(t.size());
  for (std::size_t i = 0; i < t.size(); ++i) P[i] = 0.5 * (std::abs(f_top[i]) + std::abs(f_bot[i]));
  const std::size_t ip = static_cast<std::size_t>(std::max_element(P.begin(), P.end()) - P.begin());
  r.P_peak = P[ip], r.t_peak = t[ip];
  r.split = disc::splitting_stress(r.P_peak, r.D, r.L);
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
  if (!files_dir.empty()) {
    std::ofstream f(fs::path(files_dir) / "load.csv");
    f << "time_ms,closure_mm,load_kN\n";
    for (std::size_t i = 0; i < t.size(); ++i)
      f << fmt::format("{:.6g},{:.6g},{:.6g}\n", 1e3 * t[i], 1e3 * closing_speed * t[i], 1e-3 * P[i]);
  }

  // Frame for the stress profile: the paper's 33/40.6 of the peak, taken before the first
  // broken joint (the analytic solution is elastic): when the peak comes late, the last
  // frame before cracking.
  const auto& frames = run.frames;
  auto load_at = [&](double time) { return report::value_at(t, P, time); };
  const Real target = profile_load > 0 ? profile_load : kProfileFraction * r.P_peak;
  Real best = INFINITY;
  for (std::size_t i = 0; i < frames.size(); ++i) {
    if (frames[i].time > r.t_peak || (r.t_init >= 0 && frames[i].time >= r.t_init)) break;
    const Real d = std::abs(load_at(frames[i].time) - target);
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
  // (x = 0, every z), in 16 bins over the central 80 % of it. Each element's constant
  // stress is compared with the mean of the analytic field over that element (near a load
  // point an element at x = h/4 is in the radial compression of that load, not on the
  // axis, and the field curves across it), averaged over the same elements. The centroid
  // value of the field is kept as a second reference, to show what the sampling does.
  const Real h = c.mesh_num.count("size") ? c.mesh_num.at("size") : 0.05 * r.D;
  const int nbins = 16;
  const Real y0 = -0.4 * r.D, dy = 0.8 * r.D / nbins;
  std::vector<double> sxx(nbins, 0), syy(nbins, 0), axx(nbins, 0), ayy(nbins, 0), ysum(nbins, 0), cnt(nbins, 0);
  double cxx = 0, cyy = 0, caxx = 0, cayy = 0, ccnt = 0;
  double fxx = 0, faxx = 0, mxx = 0, maxx = 0;  // end-face and mid-plane layers, |y| < h
  std::vector<double> cxx_ref(nbins, 0);        // the field at the centroids, binned the same way
  vtkNew<vtkIdList> ids;
  for (vtkIdType e = 0; e < g->GetNumberOfCells(); ++e) {
    g->GetCellPoints(e, ids);
    const vtkIdType nv = ids->GetNumberOfIds();
    Vec3 cen = Vec3::Zero(), v[4];
    for (vtkIdType k = 0; k < nv; ++k) {
      double p[3];
      g->GetPoint(ids->GetId(k), p);
      cen += Vec3(p[0], p[1], p[2]);
      if (k < 4) v[k] = Vec3(p[0], p[1], p[2]);
    }
    cen /= static_cast<Real>(nv);
    if (std::abs(cen(0)) > 0.5 * h) continue;
    const double xx = stress->GetComponent(e, 0), yy = stress->GetComponent(e, 1);
    const auto at_centroid = disc::point_load_stress(r.P_profile, r.D, r.L, cen(0), cen(1));
    // Tetrahedra get the element mean; other cells (not made by the disc generator) the
    // centroid value.
    const auto a = nv == 4 ? disc::tet_mean_point_load_stress(r.P_profile, r.D, r.L, v) : at_centroid;
    if (std::abs(cen(1)) < 0.5 * h) cxx += xx, cyy += yy, caxx += a.xx, cayy += a.yy, ++ccnt;
    if (std::abs(cen(1)) < h && std::abs(cen(2)) > 0.5 * r.L - 0.5 * h) fxx += xx, faxx += a.xx;
    if (std::abs(cen(1)) < h && std::abs(cen(2)) < 0.5 * h) mxx += xx, maxx += a.xx;
    const int b = static_cast<int>(std::floor((cen(1) - y0) / dy));
    if (b < 0 || b >= nbins) continue;
    sxx[b] += xx, syy[b] += yy, axx[b] += a.xx, ayy[b] += a.yy, ysum[b] += cen(1), ++cnt[b];
    cxx_ref[b] += at_centroid.xx;
  }
  std::vector<double> num_xx, num_yy, ref_xx, ref_yy, cen_xx, ys;
  for (int b = 0; b < nbins; ++b) {
    if (cnt[b] == 0) continue;
    ys.push_back(ysum[b] / cnt[b]);
    num_xx.push_back(sxx[b] / cnt[b]), num_yy.push_back(syy[b] / cnt[b]);
    ref_xx.push_back(axx[b] / cnt[b]), ref_yy.push_back(ayy[b] / cnt[b]);
    cen_xx.push_back(cxx_ref[b] / cnt[b]);
  }
  r.l2_xx = report::relative_l2(num_xx, ref_xx), r.l2_yy = report::relative_l2(num_yy, ref_yy);
  r.l2_xx_centroid = report::relative_l2(num_xx, cen_xx);
  if (ccnt > 0 && caxx != 0 && cayy != 0) r.centre_xx = cxx / caxx - 1, r.centre_yy = cyy / cayy - 1;
  if (faxx > 0) r.face_xx = fxx / faxx - 1;
  if (maxx > 0) r.mid_xx = mxx / maxx - 1;
  if (!files_dir.empty()) {
    std::ofstream fn(fs::path(files_dir) / "profile.csv"), fr(fs::path(files_dir) / "profile_analytic.csv");
    fn << "y_mm,sigma_xx_MPa,sigma_yy_MPa\n", fr << "y_mm,sigma_xx_MPa,sigma_yy_MPa\n";
    for (std::size_t i = 0; i < ys.size(); ++i) {
      fn << fmt::format("{:.6g},{:.6g},{:.6g}\n", 1e3 * ys[i], 1e-6 * num_xx[i], 1e-6 * num_yy[i]);
      fr << fmt::format("{:.6g},{:.6g},{:.6g}\n", 1e3 * ys[i], 1e-6 * ref_xx[i], 1e-6 * ref_yy[i]);
    }
  }
  // The split: the first frame after the peak whose load is below half of it (after that
  // the plates go on crushing the halves' edges, which is not the splitting crack).
  r.split_frame = r.last_frame;
  for (std::size_t i = 0; i < frames.size(); ++i)
    if (frames[i].time > r.t_peak && load_at(frames[i].time) < 0.5 * r.P_peak) {
      r.split_frame = static_cast<Index>(i);
      break;
    }
  crack_path(run_dir, c.mesh_num.at("size"), r, r.split_frame);
  for (std::size_t i = 0; i < frames.size(); ++i)
    if (frames[i].time >= r.t_peak) {
      damage_at_peak(run_dir, r, static_cast<Index>(i));
      break;
    }
  const RunSummary& sum = run.summary;
  r.fragments = static_cast<int>(sum.fragments);
  for (double m : sum.largest_fragment_masses) r.mass_fractions.push_back(m / sum.total_mass);
  r.wall_s = sum.wall_s;
  r.steps = sum.steps;
  r.dt = sum.dt, r.dt_start = sum.dt_start;
  r.elements = sum.elements;
  r.joints = sum.joints;
  return r;
}

std::string pct(Real x) { return fmt::format("{:+.1f} %", 100 * x); }

}  // namespace dspdem
