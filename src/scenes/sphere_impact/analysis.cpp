#include "scenes/sphere_impact/analysis.hpp"

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
}  // namespace

SphereImpactResult analyse_sphere_run(const CaseConfig& c, const std::string& run_dir, double after_contact,
                                      const std::string& files_dir) {
  DSPDEM_CHECK(c.mesh_generator == "sphere_plate", "{}: the sphere impact scene needs the sphere_plate generator",
               c.path);
  DSPDEM_CHECK(!c.initial.empty(), "{}: the sphere impact scene needs the sphere's [[initial]] velocity", c.path);
  SphereImpactResult r;
  r.run_dir = run_dir, r.files_dir = files_dir;
  r.speed = c.initial.front().velocity.norm();
  r.diameter = mesh_param(c, "diameter");
  const report::RunData run = report::RunData::open(run_dir);
  const report::Series& s = run.series;
  for (const char* col : {"plate_fy", "sphere_momentum"})
    DSPDEM_CHECK(s.has(col),
                 "{}: the sphere impact scene needs series column '{}' (a [[walls]] plane named plate and a "
                 "momentum monitor sphere_momentum over the sphere, as in cases/sphere_impact.toml)",
                 run_dir, col);
  const RunSummary& sum = run.summary;
  r.mass = sum.total_mass;
  const auto& t = s["time"];
  const std::size_t n = t.size();
  const auto &fy = s["plate_fy"], &p = s["sphere_momentum"], &broken = s["broken_joints"], &area = s["crack_area"];
  for (std::size_t i = 0; i < n && r.t_contact < 0; ++i)
    if (fy[i] != 0.0) r.t_contact = t[i];
  DSPDEM_CHECK(r.t_contact >= 0, "{}: the sphere never touched the plate (run to t = {:.4g} s)", run_dir, t[n - 1]);
  // The frame nearest the compared time after contact (frames are coarser than series rows).
  const double want = r.t_contact + after_contact;
  DSPDEM_CHECK(
      run.frames.back().time >= want - 0.5 * c.frame_interval,
      "{}: the run ends at t = {:.4g} s, before the compared time {:.4g} s after the first contact at {:.4g} s",
      run_dir, run.frames.back().time, after_contact, r.t_contact);
  r.frame = 0;
  for (std::size_t i = 1; i < run.frames.size(); ++i)
    if (std::abs(run.frames[i].time - want) < std::abs(run.frames[static_cast<std::size_t>(r.frame)].time - want))
      r.frame = static_cast<Index>(i);
  r.t_compare = run.frames[static_cast<std::size_t>(r.frame)].time;
  std::size_t k = 0;  // the series row at (or just after) the compared frame
  while (k + 1 < n && t[k] < r.t_compare - kSameTime) ++k;
  for (std::size_t i = 0; i <= k; ++i) {
    if (std::abs(fy[i]) > r.plate_force_peak) r.plate_force_peak = std::abs(fy[i]), r.t_plate_force_peak = t[i];
    if (r.t_first_broken < 0 && broken[i] > 0) r.t_first_broken = t[i];
  }
  // Velocity of the centre of mass; the sphere falls in -y, so + is the rebound.
  r.rebound_vy = p[k] / r.mass;
  r.restitution = r.speed > 0 ? r.rebound_vy / r.speed : 0.0;
  r.broken_joints = static_cast<long>(broken[k]);
  r.crack_area = area[k];
  r.joints = sum.joints;
  const auto& bal = s["balance_error"];
  r.balance_max = *std::max_element(bal.begin(), bal.end());
  auto at_k = [&](const char* key) { return s.has(key) ? s[key][k] : 0.0; };
  r.kinetic_start = s["kinetic"][0];
  r.kinetic_end = at_k("kinetic");
  r.elastic_end = at_k("internal") + at_k("joint_elastic") + at_k("contact_elastic");
  r.fracture = at_k("fracture_I") + at_k("fracture_II");
  r.friction = at_k("friction");
  r.damping = at_k("damping") + at_k("contact_damping");
  if (s.has("born_unseen_energy")) r.born_unseen_energy = s["born_unseen_energy"][k];
  if (s.has("born_wall_energy")) r.born_wall_energy = s["born_wall_energy"][k];

  std::vector<double> density;
  for (const auto& m : c.materials) density.push_back(m.density);
  r.fragments = report::fragment_stats(run.frames[static_cast<std::size_t>(r.frame)].file, density);
  r.pieces_1pct = r.fragments.count_at_least(0.01);
  r.pieces_10pct = r.fragments.count_at_least(SphereImpactResult::large_piece_fraction);
  r.second_fraction = r.fragments.count() > 1 ? r.fragments.masses[1] / r.fragments.total_mass : 0.0;
  r.through_crack = SphereImpactResult::cut_through(r.fragments.largest_fraction(), r.second_fraction);

  // Up to the compared frame only: each run goes on past it by its own allowance for the gap
  // (over its speed), so later frames would cover a different window at each speed.
  if (const fs::path fcsv = fs::path(run_dir) / "fragments.csv"; fs::exists(fcsv)) {
    const double large = SphereImpactResult::large_piece_fraction * r.mass;
    for (const auto& f : report::fragment_history(fcsv.string())) {
      if (f.time < r.t_contact || f.frame > r.frame) continue;
      SphereImpactResult::PiecesAt h{
          f.frame, f.time - r.t_contact, f.mass(0) / r.mass, f.mass(1) / r.mass, f.count_at_least(large), f.count};
      r.history.push_back(h);
    }
  }

  // How far up the cracks reach, frame by frame. Joints frames are written with the frames
  // (same count, same times), the same joints in each, so the first gives every joint's place
  // at the start. A run without them, or with a set that does not match its frames, keeps -1.
  const auto& jf = run.joint_frames;
  bool paired = !jf.empty() && jf.size() == run.frames.size() && fs::exists(jf.front().file);
  for (std::size_t f = 0; paired && f < jf.size(); ++f)
    paired = std::abs(jf[f].time - run.frames[f].time) <= 1e-9 * std::max(1.0, std::abs(run.frames[f].time));
  if (paired) {
    const std::vector<report::CrackPiece> where = report::broken_joints(jf.front().file, 0);
    const Vec3 bottom(0.0, -0.5 * r.diameter, 0.0), up = Vec3::UnitY();  // the generator's sphere is centred at 0
    std::vector<double> edges;
    for (double e : SphereImpactResult::height_bands) edges.push_back(e * r.diameter);
    auto reach_at = [&](Index f, double& reach, double& top, std::vector<long>& bands) {
      const std::vector<int> states = report::joint_states(jf[static_cast<std::size_t>(f)].file);
      const report::CrackReach cr = report::crack_reach(where, states, bottom, up, SphereImpactResult::reach_fraction);
      reach = cr.at_quantile / r.diameter, top = cr.furthest / r.diameter;
      bands = report::count_by_band(where, states, bottom, up, edges);
    };
    reach_at(r.frame, r.crack_reach, r.crack_top, r.broken_by_height);
    r.joints_by_height = report::count_by_band(where, std::vector<int>(where.size(), 0), bottom, up, edges, 0);
    std::vector<long> bands;
    for (auto& h : r.history)  // fragments.csv numbers the frames as run.pvd does
      if (h.frame >= 0 && static_cast<std::size_t>(h.frame) < jf.size()) {
        reach_at(h.frame, h.crack_reach, h.crack_top, bands);
        h.broken_contact = bands.front(), h.broken_upper = bands.back();
      }
  }

  if (!files_dir.empty()) {
    fs::create_directories(files_dir);
    std::ofstream ph(fs::path(files_dir) / "pieces_time.csv");
    DSPDEM_CHECK(ph.good(), "cannot write '{}/pieces_time.csv'", files_dir);
    ph << "frame,time_ms,after_contact_ms,fragments,largest,second,large_pieces,crack_reach,crack_top,broken_contact,"
          "broken_upper_half\n";
    for (const auto& h : r.history)
      ph << fmt::format("{},{:.6g},{:.6g},{},{:.6g},{:.6g},{},{:.4f},{:.4f},{},{}\n", h.frame,
                        1e3 * (h.after_contact + r.t_contact), 1e3 * h.after_contact, h.fragments, h.largest, h.second,
                        h.large_pieces, h.crack_reach, h.crack_top, h.broken_contact, h.broken_upper);
    std::ofstream f(fs::path(files_dir) / "sphere_series.csv");
    DSPDEM_CHECK(f.good(), "cannot write '{}/sphere_series.csv'", files_dir);
    f << "time_ms,broken_joints,crack_area_cm2,plate_force_kN,vy_centre,kinetic,elastic,fracture,friction,damping\n";
    auto at = [&](const char* k, std::size_t i) { return s.has(k) ? s[k][i] : 0.0; };
    for (std::size_t i = 0; i < n; ++i)
      f << fmt::format("{:.6g},{},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g}\n", 1e3 * t[i],
                       static_cast<long>(broken[i]), 1e4 * area[i], 1e-3 * std::abs(fy[i]), p[i] / r.mass,
                       at("kinetic", i), at("internal", i) + at("joint_elastic", i) + at("contact_elastic", i),
                       at("fracture_I", i) + at("fracture_II", i), at("friction", i),
                       at("damping", i) + at("contact_damping", i));
    report::write_mass_distribution_csv((fs::path(files_dir) / "fragment_masses.csv").string(), r.fragments);
  }
  r.wall_s = sum.wall_s, r.steps = sum.steps, r.dt = sum.dt, r.elements = sum.elements;
  return r;
}

}  // namespace dspdem
