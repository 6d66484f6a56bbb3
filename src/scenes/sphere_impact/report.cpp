#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <thread>

#include "core/archive.hpp"
#include "core/error.hpp"
#include "core/file.hpp"
#include "core/log.hpp"
#include "core/timer.hpp"
#include "io/run_place.hpp"
#include "io/run_summary.hpp"
#include "render/plot.hpp"
#include "report/document.hpp"
#include "report/earlier_reports.hpp"
#include "report/files_aside.hpp"
#include "report/outdated_report.hpp"
#include "report/report_dirs.hpp"
#include "report/resume.hpp"
#include "report/run_data.hpp"
#include "run/checkpoint.hpp"
#include "run/montage.hpp"
#include "run/process_pool.hpp"
#include "run/render_run.hpp"
#include "scenes/sphere_impact/analysis.hpp"
#include "scenes/sphere_impact/draws.hpp"
#include "scenes/sphere_impact/pattern.hpp"
#include "scenes/sphere_impact/pattern_over_time.hpp"
#include "scenes/sphere_impact/realisations.hpp"
#include "scenes/sphere_impact/scene.hpp"
#include "scenes/sphere_impact/split_precursors.hpp"
#include "scenes/sphere_impact/split_timing.hpp"

namespace dspdem {

namespace {
namespace fs = std::filesystem;
using report::Earlier;
using report::earlier_run;

// The sweep; the paper shows 5, 7.5 and 20 m/s.
const std::vector<double> kDefaultSpeeds = {2.5, 5.0, 7.5, 10.0, 20.0, 30.0, 50.0};

std::string speed_name(double v) { return fmt::format("v{:g}", v); }

// The case's [time] end is the compared time after the first contact (the paper's 0.75 ms).
// The sphere's lowest node lies above the plate by at most the gap between the plate and
// the true sphere plus the sag of a facet of the element size h, h^2 / (8 R); each speed
// runs that distance over v longer (with 0.1 mm to spare).
double max_gap(const CaseConfig& c) {
  const double D = mesh_param(c, "diameter"), h = mesh_param(c, "size");
  double gap = 0;
  for (const auto& w : c.walls)
    if (w.wall.name == "plate") gap = std::max(0.0, w.wall.normal0.dot(Vec3(0, -0.5 * D, 0) - w.wall.centre));
  return gap + h * h / (4 * D) + 1e-4;
}

std::vector<std::string> speed_overrides(const CaseConfig& c, double v) {
  // Along the case's own direction of approach, at speed v.
  const Vec3 d = c.initial.front().velocity.normalized();
  return {override_of("initial.0.velocity", Vec3(v * d)), override_of("time.end", c.t_end + max_gap(c) / v)};
}

struct Planned {
  std::string name, knob, dir;
  std::vector<std::string> sets;  // on top of the case's own overrides
  double speed = 0;
  int orientation = 0;  // its mesh's mesh.sphere_plate.orientation
  int draw = 0;         // 0, or the draw of --draws (sphere_impact/draws.hpp)
};

// Each planned run is read in-process first (a bad override fails here, with its message,
// before any process starts), then run as its own `dspdem -t 1 run` process.
std::vector<std::string> run_planned(const CaseConfig& c, const std::vector<Planned>& plan, int jobs,
                                     const report::RunPolicy& runs) {
  std::vector<Job> list;
  std::vector<std::size_t> listed;  // plan index of each job
  int kept = 0, continued = 0;
  for (std::size_t i = 0; i < plan.size(); ++i) {
    const Planned& p = plan[i];
    const CaseConfig v = reread_with(c, p.sets);
    const report::EarlierRun e = runs.resume ? earlier_run(p.dir, v.resolved_toml) : report::EarlierRun{};
    if (e.state == Earlier::Finished) {
      ++kept;
      log::info("sphere impact: {}: kept the finished run in {}", p.name, p.dir);
      continue;
    }
    Job j;
    j.log = report::run_log(p.dir);
    if (e.state == Earlier::Interrupted) {
      ++continued;
      // The checkpoint judged, by its file: a search of the folder by the child could find
      // another, should a killed run's staging folder appear in between.
      log::info("sphere impact: {}: continued from its checkpoint {}", p.name, e.checkpoint);
      j.args = {"-q", "-t", "1", "run", "--restart", e.checkpoint, "--out", p.dir, "--no-progress"};
      j.args.insert(j.args.end(), {"--checkpoint-wall", fmt::format("{}", runs.checkpoint_wall)});
      // After the interrupted part's messages, which say where it stopped.
      j.append_log = true;
      std::ofstream(j.log, std::ios::app) << "\n--- dspdem report --resume: continued from its checkpoint ---\n\n";
    } else {
      // Not resumed: the sweep starts this speed again, over any interrupted run of it.
      j.args = {"-q", "-t", "1", "run", c.path, "--no-progress", "--discard-interrupted", "--out", p.dir};
      j.args.insert(j.args.end(), {"--checkpoint-wall", fmt::format("{}", runs.checkpoint_wall)});
      for (const auto& s : c.overrides) j.args.insert(j.args.end(), {"--set", s});
      for (const auto& s : p.sets) j.args.insert(j.args.end(), {"--set", s});
    }
    list.push_back(j);
    listed.push_back(i);
  }
  if (runs.resume)
    log::info("sphere impact: --resume: {} run(s) kept, {} continued, {} started", kept, continued,
              list.size() - static_cast<std::size_t>(continued));
  if (!list.empty()) log::info("sphere impact: {} run(s), {} at a time, logs beside their folders", list.size(), jobs);
  // A finished run that a job replaces marks the earlier report in the folder outdated: the
  // runs change one by one, the report.md only at the end. Told by the files, whatever the
  // job's exit status (a run stopped after its commit has replaced the earlier one).
  std::vector<report::RunReplacement> earlier;
  earlier.reserve(list.size());
  for (std::size_t k = 0; k < list.size(); ++k) earlier.emplace_back(plan[listed[k]].dir);
  // Stopped by a signal, Interrupted goes up to report_command, which says how to go on.
  const std::vector<int> status = run_processes(list, jobs, [&](std::size_t k, int) {
    if (earlier[k].replaced()) report::mark_report_outdated(runs.report_dir, earlier[k].dir());
  });
  std::vector<std::string> err(plan.size());
  for (std::size_t k = 0; k < list.size(); ++k)
    if (status[k] != 0) {
      const std::size_t i = listed[k];
      err[i] = fmt::format("exit status {} (see {})", status[k], list[k].log);
      log::warn("sphere impact: run {} failed: {}", plan[i].name, err[i]);
    }
  return err;
}

std::string pct(double f) { return fmt::format("{:.1f}", 100 * f); }

std::vector<std::string> sweep_row(const SphereImpactResult& r) {
  const auto& f = r.fragments;
  return {fmt::format("{:g}", r.speed),
          fmt::format("{:.0f}", r.kinetic_start),
          r.t_first_broken < 0 ? "-" : fmt::format("{:.3f}", 1e3 * (r.t_first_broken - r.t_contact)),
          fmt::format("{} ({:.1f} %)", r.broken_joints, r.joints ? 100.0 * r.broken_joints / r.joints : 0.0),
          fmt::format("{:.0f}", 1e4 * r.crack_area),
          r.crack_reach < 0 ? "-" : fmt::format("{:.2f} / {:.2f}", r.crack_reach, r.crack_top),
          std::to_string(f.count()),
          std::to_string(f.single_element()),
          std::to_string(r.pieces_1pct),
          std::to_string(r.pieces_10pct),
          fmt::format("{:.3f}", f.largest_fraction()),
          fmt::format("{:.3f}", r.second_fraction),
          r.through_crack ? "yes" : "no",
          fmt::format("{:.0f}", 1e-3 * r.plate_force_peak),
          fmt::format("{:+.2f}", r.rebound_vy),
          fmt::format("{:.1e}", r.balance_max),
          fmt::format("{:.0f}", r.wall_s)};
}

std::vector<std::string> energy_row(const SphereImpactResult& r) {
  const double e0 = r.kinetic_start > 0 ? r.kinetic_start : 1.0;
  return {fmt::format("{:g}", r.speed), fmt::format("{:.1f}", r.kinetic_start),
          pct(r.kinetic_end / e0),      pct(r.elastic_end / e0),
          pct(r.fracture / e0),         pct(r.friction / e0),
          pct(r.damping / e0),          fmt::format("{:.2f}", r.fracture)};
}

// Where a sequence is not monotonic: the speeds at which it turns.
std::string monotonic(const std::vector<SphereImpactResult>& rs, double (*key)(const SphereImpactResult&), int sign) {
  std::string breaks;
  for (std::size_t i = 1; i < rs.size(); ++i)
    if (sign * (key(rs[i]) - key(rs[i - 1])) < 0)
      breaks += fmt::format("{}{:g} -> {:g} m/s", breaks.empty() ? "" : ", ", rs[i - 1].speed, rs[i].speed);
  return breaks;
}

// When the sphere came apart, not only whether it had by the compared time: near the
// splitting speed one mesh's large pieces come free just before the compared time and
// another's just after it (src/scenes/sphere_impact/REFERENCE.md).
std::string split_times(const std::vector<SphereImpactResult>& sweep, double frame_interval) {
  std::vector<std::string> split, whole, unknown;
  for (const auto& r : sweep)
    if (r.history.empty())
      unknown.push_back(fmt::format("{:g}", r.speed));
    else if (r.t_two_large() >= 0)
      split.push_back(fmt::format("{} ms at {:g} m/s", sphere::two_large_ms(r, ""), r.speed));
    else
      whole.push_back(fmt::format("{:g}", r.speed));
  auto list = [](const std::vector<std::string>& v) {
    std::string out;
    for (std::size_t i = 0; i < v.size(); ++i) out += (i == 0 ? "" : i + 1 == v.size() ? " and " : ", ") + v[i];
    return out;
  };
  std::string s = fmt::format(
      "The largest piece frame by frame up to the compared time (frames every {:.3g} ms, so a time below is that of "
      "the first frame to show it; per speed in `speeds/v<speed>/pieces_time.csv`). ",
      1e3 * frame_interval);
  // A run older than fragments.csv has no history: that is not "no split".
  const std::string none =
      unknown.empty() ? "" : fmt::format(" No history at {} m/s (a run without fragments.csv).", list(unknown));
  if (split.empty())
    return s +
           (whole.empty() ? "" : "No speed has two pieces of at least 10 % of the mass each by the compared time.") +
           none;
  s += fmt::format(
      "First frame with two pieces of at least 10 % of the mass each, after the first contact: {} (they may have "
      "broken up further by the compared time: the table above has the count then)",
      list(split));
  if (!whole.empty()) s += fmt::format("; at {} m/s there is none by the compared time", list(whole));
  return s + "." + none;
}

// The report's own files beside report.md (not its runs' places). Set aside once the runs are
// analysed (report/files_aside.hpp): dropped when this report is written, put back if it stops
// first, so that a report that stops leaves the earlier report's files as they were, beside
// the earlier report.md it also leaves. Those that only some reports write (with
// --realisations, --draws, runs past the paper's moment, a render) would otherwise also stay
// beside a new report.md that no longer names them, and read as its own. Each section names
// its own files beside the code that writes them; this report's are below.
constexpr const char* kFragmentMassesCsv = "fragment_masses.csv";
constexpr const char* kFragmentMassesPng = "images/fragment_masses.png";
constexpr const char* kCrackAreaPng = "images/crack_area.png";
constexpr const char* kPlateForcePng = "images/plate_force.png";
constexpr const char* kLargestPiecePng = "images/largest_piece.png";
constexpr const char* kCrackReachPng = "images/crack_reach.png";              // runs with a history
constexpr const char* kMontageFragmentsPng = "images/montage_fragments.png";  // a render
constexpr const char* kMontageCracksPng = "images/montage_cracks.png";
const std::vector<std::string> kReportFiles = {kFragmentMassesCsv,
                                               kFragmentMassesPng,
                                               kCrackAreaPng,
                                               kPlateForcePng,
                                               kLargestPiecePng,
                                               kCrackReachPng,
                                               kMontageFragmentsPng,
                                               kMontageCracksPng,
                                               sphere::kOrientationsCsv,
                                               sphere::kBreakagePng,
                                               sphere::kDrawsCsv,
                                               sphere::kLargePiecesTimeCsv,
                                               sphere::kLargePiecesTimePng,
                                               sphere::kSplitPrecursorsCsv,
                                               sphere::kPatternOverTimeCsv,
                                               sphere::kPatternOverTimeRunsCsv};

}  // namespace

int sphere_impact_report(const CaseConfig& c, const report::ReportArgs& a) {
  Timer total;
  const std::string dir = report::report_folder(c, a);
  fs::create_directories(dir);
  std::vector<double> speeds = a.speeds.empty() ? kDefaultSpeeds : a.speeds;
  std::sort(speeds.begin(), speeds.end());
  speeds.erase(std::unique(speeds.begin(), speeds.end()), speeds.end());
  const int jobs = a.jobs > 0 ? a.jobs : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  // --from-run: earlier reports' folders, whose speeds/ and orientations/ runs are analysed
  // again (each found in the first folder that has it); the plan's folders are this report's
  // until then.
  std::vector<std::string> sweep_roots;
  for (const auto& r : a.from_runs) {
    // "a/" and "a" alike; "." and "./" stay "." (their normal form's parent is empty).
    const std::string root = (fs::path(r) / "").lexically_normal().parent_path().string();
    sweep_roots.push_back(root.empty() ? "." : root);
  }

  // The case's own orientation: the sweep's and the study's mesh; realisations turn it further.
  const int k0 = static_cast<int>(mesh_param(c, "orientation"));
  std::vector<Planned> plan;
  for (double v : speeds)
    plan.push_back({speed_name(v), fmt::format("{:g} m/s", v), (fs::path(dir) / "speeds" / speed_name(v)).string(),
                    speed_overrides(c, v), v, k0});
  const std::size_t n_sweep = plan.size();
  // The study: at 7.5 and 20 m/s (--study-speeds), each knob moved alone from the case.
  const std::vector<double> study_speeds = a.study_speeds.empty() ? std::vector<double>{7.5, 20.0} : a.study_speeds;
  if (a.study) {
    const double n_paper = 4539;  // [S] tetrahedra in the sphere
    std::vector<std::string> pen, law, quad, ss;
    bool nodal = false;  // the case's quadrature (of its first joint material); the row tries the other
    for (std::size_t i = 0; i < c.materials.size(); ++i)
      if (c.joint_materials[i].given) {
        const auto& m = c.materials[i].name;
        pen.push_back(
            override_of("materials." + m + ".joint_penalty", c.joint_materials[i].penalty >= 100 ? 30.0 : 100.0));
        law.push_back(override_of("materials." + m + ".joint_law", std::string("coupled")));
        if (quad.empty()) nodal = c.joint_materials[i].nodal_quadrature;
        quad.push_back(override_of("materials." + m + ".joint_quadrature", std::string(nodal ? "gauss" : "nodal")));
      }
    for (std::size_t i = 0; i < c.bodies.size(); ++i)
      ss.push_back(override_of(fmt::format("bodies.{}.kinematics", i), std::string("small_strain")));
    // The case's elements, three times finer where the sphere meets the plate than the case
    // has them there: the Hertz contact's radius (10 mm at 7.5 m/s) is under one of the
    // paper-sized elements (16.8 mm).
    const double case_contact = mesh_param(c, "contact_size");
    const double at_contact = (case_contact > 0 ? case_contact : mesh_param(c, "size")) / 3;
    for (double v : study_speeds) {
      const std::vector<std::string> vo = speed_overrides(c, v);
      auto add = [&](const std::string& name, const std::string& knob, std::vector<std::string> sets) {
        sets.insert(sets.begin(), vo.begin(), vo.end());
        plan.push_back({fmt::format("{}_{}", speed_name(v), name), knob,
                        (fs::path(dir) / "study" / fmt::format("{}_{}", speed_name(v), name)).string(), sets, v, k0});
      };
      add("mesh_x2", "2x the paper's elements", {override_of("mesh.sphere_plate.target_elements", 2 * n_paper)});
      add("mesh_x4", "4x the paper's elements", {override_of("mesh.sphere_plate.target_elements", 4 * n_paper)});
      add("mesh_contact", fmt::format("elements 3x finer at the contact ({:.1f} mm)", 1e3 * at_contact),
          {override_of("mesh.sphere_plate.contact_size", at_contact)});
      add("penalty", "joint penalty 100 <-> 30", pen);
      add("coupled_law", "joint_law = coupled (same strengths)", law);
      add(nodal ? "gauss_joints" : "nodal_joints",
          nodal ? "Gauss joint quadrature (reference nodal)" : "nodal joint quadrature (reference Gauss)", quad);
      add("small_strain", "small-strain kinematics (reference: co-rotational)", ss);
    }
  }
  const std::size_t n_study = plan.size() - n_sweep;
  // Realisations (--realisations N): each speed again with the sphere's mesh turned N - 1
  // other ways, orientations k0 + 1 ... k0 + N - 1 after the case's own k0.
  const std::size_t first_realisation = plan.size();
  for (double v : speeds)
    for (int r = 1; r < a.realisations; ++r) {
      std::vector<std::string> sets = speed_overrides(c, v);
      sets.push_back(override_of("mesh.sphere_plate.orientation", k0 + r));
      const std::string name = fmt::format("{}_o{}", speed_name(v), k0 + r);
      plan.push_back({name, fmt::format("orientation {}", k0 + r), (fs::path(dir) / "orientations" / name).string(),
                      sets, v, k0 + r});
    }
  // Draws (--draws N): each run of the sweep and of the turned meshes N - 1 times more on its
  // own mesh, the impact speed nudged; the study's runs are not drawn again.
  const std::size_t first_draw = plan.size();
  for (std::size_t i = 0; i < first_draw; ++i) {
    if (i >= n_sweep && i < first_realisation) continue;
    const double v = plan[i].speed;
    const int o = plan[i].orientation;
    for (int d = 1; d < a.draws; ++d) {
      std::vector<std::string> sets = speed_overrides(c, sphere::draw_speed(v, d));
      if (o != k0) sets.push_back(override_of("mesh.sphere_plate.orientation", o));
      const std::string name = fmt::format("{}_o{}_d{}", speed_name(v), o, d);
      plan.push_back({name, fmt::format("orientation {}, draw {}", o, d), (fs::path(dir) / "draws" / name).string(),
                      sets, v, o, d});
    }
  }
  std::vector<std::string> errors(plan.size());
  // Each run's place in this report's folder: its files derived here and its images go there
  // also when the run itself is an earlier report's, whose folder is only read.
  std::vector<std::string> own_dir(plan.size());
  for (std::size_t i = 0; i < plan.size(); ++i) own_dir[i] = plan[i].dir;
  // --from-run: where each run of the sweep was found, by plan index (the study's: none).
  std::vector<report::EarlierReportRun> earlier(a.from_runs.empty() ? 0 : plan.size());
  if (a.from_runs.empty()) {
    // Runs to be made there: a run empties such a place itself, but only once its set-up has
    // succeeded; a row failing before must not show another run's files either.
    // What an earlier report derived there from another run goes now: its report is outdated.
    for (const Planned& p : plan) {
      const report::RunReplacement earlier_place(p.dir);
      clear_derived_place(p.dir);
      if (earlier_place.replaced()) report::mark_report_outdated(a.runs.report_dir, p.dir);
    }
    errors = run_planned(c, plan, jobs, a.runs);
  } else {
    for (std::size_t i = 0; i < plan.size(); ++i) {
      if (i >= n_sweep && i < n_sweep + n_study) continue;
      const std::string rel = fs::path(plan[i].dir).lexically_relative(dir).string();
      earlier[i] = report::find_earlier_report_run(sweep_roots, rel, reread_with(c, plan[i].sets).resolved_toml);
      const report::EarlierReportRun& e = earlier[i];
      if (!e.dir.empty()) {
        // What is derived from the run goes to its place here: checked now, changed only
        // once every run is found.
        check_derived_place(own_dir[i], e.dir);
        plan[i].dir = e.dir;
        continue;
      }
      // A run an earlier report ran and lost is a failed row, as it was in that report: with
      // the reason its summary gives when it failed or was stopped, else its log's. One none
      // ran means they had other speeds or fewer --realisations.
      if (!e.error.empty() || !e.lost_log.empty()) {
        errors[i] = e.error.empty() ? fmt::format("no finished run (see {})", e.lost_log)
                                    : e.error + (e.lost_log.empty() ? "" : fmt::format(" (see {})", e.lost_log));
        continue;
      }
      fail(
          "--from-run {}: none has run {} (the speeds/, orientations/ and draws/ folders of earlier reports of this "
          "sweep{})",
          fmt::join(sweep_roots, ", "), rel,
          i >= first_draw          ? ", with as many --realisations and --draws"
          : i >= first_realisation ? ", with as many --realisations"
                                   : "");
    }
    // Every run found and none refused: only now is anything of this folder changed.
    for (std::size_t i = 0; i < plan.size(); ++i)
      if (!earlier[i].dir.empty())
        take_derived_place(own_dir[i], earlier[i].dir);
      else if (!errors[i].empty())
        clear_derived_place(own_dir[i]);  // a failed row: nothing of another run beside it
    if (a.study) {
      const auto first = plan.begin() + static_cast<long>(n_sweep);
      const auto e = run_planned(c, std::vector<Planned>(first, first + static_cast<long>(n_study)), jobs,
                                 report::RunPolicy{false, a.runs.checkpoint_wall, a.runs.report_dir});
      std::copy(e.begin(), e.end(), errors.begin() + static_cast<long>(n_sweep));
    }
  }
  std::vector<SphereImpactResult> res(plan.size());
  for (std::size_t i = 0; i < plan.size(); ++i) {
    if (!errors[i].empty()) continue;
    try {
      res[i] = analyse_sphere_run(reread_with(c, plan[i].sets), plan[i].dir, c.t_end, own_dir[i]);
    } catch (const std::exception& e) {
      errors[i] = e.what();
    }
  }
  std::vector<SphereImpactResult> sweep;
  std::vector<std::string> sweep_failed;
  for (std::size_t i = 0; i < speeds.size(); ++i) {
    if (errors[i].empty())
      sweep.push_back(res[i]);
    else
      sweep_failed.push_back(fmt::format("{:g} m/s: {}", speeds[i], errors[i]));
  }
  DSPDEM_CHECK(!sweep.empty(), "sphere impact: every run of the sweep failed: {}", sweep_failed.front());
  report::FilesAside earlier_files(dir, kReportFiles);

  // Plots over all speeds: cumulative mass distribution, broken joints and plate force.
  const fs::path img = fs::path(dir) / "images";
  fs::create_directories(img);
  std::vector<render::Curve> dist, cracks, force, largest_curves, reach_curves;
  std::ofstream all(fs::path(dir) / kFragmentMassesCsv);
  all << "speed,mass_kg,cumulative\n";
  for (const auto& r : sweep) {
    render::Curve d{fmt::format("{:g} m/s", r.speed), {}, {}};
    double below = 0;  // drawn as steps: the fraction jumps at each fragment's mass
    for (const auto& [m, f] : report::cumulative_mass_distribution(r.fragments)) {
      d.x.insert(d.x.end(), {m, m}), d.y.insert(d.y.end(), {below, f});
      below = f;
      all << fmt::format("{:g},{:.8g},{:.8g}\n", r.speed, m, f);
    }
    dist.push_back(d);
    const report::Series s((fs::path(r.files_dir) / "sphere_series.csv").string());
    cracks.push_back({d.name, s["time_ms"], s["crack_area_cm2"]});
    force.push_back({d.name, s["time_ms"], s["plate_force_kN"]});
    render::Curve l{d.name, {}, {}};
    for (const auto& h : r.history) l.x.push_back(1e3 * h.after_contact), l.y.push_back(h.largest);
    largest_curves.push_back(l);
    render::Curve rc{d.name, {}, {}};
    for (const auto& h : r.history)
      if (h.crack_reach >= 0) rc.x.push_back(1e3 * h.after_contact), rc.y.push_back(h.crack_reach);
    if (!rc.x.empty()) reach_curves.push_back(rc);
  }
  all.close();
  render::plot_curves(dist, "fragment mass [kg]", "mass fraction in fragments of at most this mass",
                      "cumulative fragment mass distribution at the compared time",
                      (fs::path(dir) / kFragmentMassesPng).string(), true);
  render::plot_curves(cracks, "time [ms]", "broken joints' area [cm^2]", "crack area against time",
                      (fs::path(dir) / kCrackAreaPng).string());
  render::plot_curves(force, "time [ms]", "|f_y| on the plate [kN]", "contact force on the plate against time",
                      (fs::path(dir) / kPlateForcePng).string());
  render::plot_curves(largest_curves, "time after the first contact [ms]", "largest piece / sphere mass",
                      "largest piece against time, up to the compared time",
                      (fs::path(dir) / kLargestPiecePng).string());
  if (!reach_curves.empty())
    render::plot_curves(
        reach_curves, "time after the first contact [ms]",
        fmt::format("height below which {:.0f} % of the crack area lies [D]", 100 * SphereImpactResult::reach_fraction),
        "how far up the cracks reach, up to the compared time", (fs::path(dir) / kCrackReachPng).string());
  std::vector<std::string> labels, runs;
  for (const auto& r : sweep) labels.push_back(fmt::format("{:g} m/s", r.speed)), runs.push_back(r.run_dir);
  const double t_cmp = c.t_end;
  // A case run to another time (`--set time.end=...`) must not read as the paper's moment.
  const std::string as_paper = std::abs(t_cmp - sphere::kPaperTime) < 1e-9
                                   ? std::string("as in the paper's Fig. 22")
                                   : fmt::format("the paper's Fig. 22: {:g} ms", 1e3 * sphere::kPaperTime);
  if (!a.no_render) {
    MontageArgs m;
    m.run_dirs = runs, m.labels = labels;
    for (const auto& r : sweep) m.times.push_back(r.t_compare);  // each run's compared frame
    m.rows = {"fragments:z", "fragments"};
    m.camera = "front";
    m.width = 480, m.height = 400;
    m.out = (fs::path(dir) / kMontageFragmentsPng).string();
    write_montage(m);
    m.rows = {"cracks"};
    m.out = (fs::path(dir) / kMontageCracksPng).string();
    write_montage(m);
    // Each speed's own frames and animations, all with one stress range so that the speeds
    // compare colour for colour.
    std::vector<std::string> dirs;
    for (const auto& r : sweep) dirs.push_back(r.run_dir);
    const bool stress = std::find(c.render.views.begin(), c.render.views.end(), "stress") != c.render.views.end();
    const std::string range = stress ? common_range(dirs, c.render.field, c.render) : std::string();
    for (const auto& r : sweep) {
      RenderArgs ra;
      ra.run_dir = r.run_dir, ra.out_dir = r.files_dir;
      ra.range = range;
      // Every speed's run has the case's name: the frames say which speed they show.
      ra.label = fmt::format("{:g} m/s", r.speed);
      render_command(ra);
    }
  }

  // Where the sweep's own runs are, for the text: this report's speeds/, or with --from-run
  // the earlier reports' that hold them.
  const std::string speeds_folders = report::earlier_report_folders(earlier, 0, n_sweep, "speeds", dir);
  report::Document doc(dir, dir);
  doc.title("Sphere impact (paper section 2.5): report");
  doc.para(fmt::format(
      "Case `{}` ({}): a sphere of diameter {:.0f} mm ({:.2f} kg, {} tetrahedra, {} joints) strikes a rigid plate; "
      "one run per speed, each a separate process in its own folder under {} with its case.resolved.toml. "
      "Compared {:.3g} ms after the first contact ({}). Reference data and sources: "
      "src/scenes/sphere_impact/REFERENCE.md in dspdem.",
      c.path, c.name, 1e3 * sweep.front().diameter, sweep.front().mass, sweep.front().elements, sweep.front().joints,
      speeds_folders, 1e3 * t_cmp, as_paper));
  doc.para(
      "The paper's pattern: no crack through the sphere at 2.5 and 5 m/s, a few large pieces at 7.5 m/s, a crushed "
      "base with many small pieces at 20 m/s and more. Here a crack is *through* when a second piece holds at least "
      "1 % of the mass (smaller pieces are material crushed off at the contact), *large pieces* hold at least 10 %, "
      "and single-element fragments are the crushed material the mesh cannot resolve further.");
  if (!earlier.empty())
    doc.para(fmt::format(
        "Runs analysed again from earlier reports (`--from-run`){}: {}. What this report derives from each run "
        "(`pieces_time.csv`, `sphere_series.csv`, `fragment_masses.csv`{}) is written here at the run's place "
        "(`speeds/`, `orientations/`, `draws/`); the earlier reports' folders are only read.",
        a.study ? ", the study's run here" : ", none run here", report::earlier_report_sources(earlier, dir),
        a.no_render ? "" : ", the sweep's images"));
  if (!sweep_failed.empty()) {
    std::string f;
    for (const auto& e : sweep_failed) f += "\n- " + e;
    doc.para("Runs that failed:" + f);
  }
  doc.section("Fragments and cracks by speed");
  std::vector<std::vector<std::string>> rows;
  for (const auto& r : sweep) rows.push_back(sweep_row(r));
  doc.table(
      {"speed [m/s]", "impact energy [J]", "first broken joint after the contact [ms]", "broken joints",
       "crack area [cm^2]", "cracks reach / top [D]", "fragments", "of one element", "pieces >= 1 %", "pieces >= 10 %",
       "largest", "second", "through crack", "plate force peak [kN]", "rebound v_y [m/s]", "balance max", "wall [s]"},
      rows);
  // Where the joints broke: the crushing under the contact against the cracks that must
  // reach the upper half to split the sphere (REFERENCE.md, session 96: the two move apart).
  if (std::any_of(sweep.begin(), sweep.end(),
                  [](const SphereImpactResult& r) { return !r.broken_by_height.empty(); })) {
    const auto& hb = SphereImpactResult::height_bands;
    std::vector<std::string> head = {"speed [m/s]", "broken joints"};
    for (std::size_t b = 0; b + 1 < hb.size(); ++b) head.push_back(fmt::format("{:g}-{:g} D", hb[b], hb[b + 1]));
    std::vector<std::vector<std::string>> reg;
    for (const auto& r : sweep) {
      std::vector<std::string> row = {fmt::format("{:g}", r.speed), std::to_string(r.broken_joints)};
      for (std::size_t b = 0; b + 1 < hb.size(); ++b)
        row.push_back(
            r.broken_by_height.empty()
                ? "-"
                : fmt::format("{} of {} ({:.0f} %)", r.broken_by_height[b], r.joints_by_height[b],
                              r.joints_by_height[b] > 0 ? 100.0 * r.broken_by_height[b] / r.joints_by_height[b] : 0.0));
      reg.push_back(row);
    }
    doc.para(fmt::format(
        "Where the joints broke by the compared time: broken joints against all joints in bands of height over the "
        "diameter above the lowest point, each joint where it was at the start (a joint outside the sphere's height, a "
        "meshed plate's, is in none); the lowest band is the contact ({:.0f} mm on this sphere), the last the upper "
        "half. The lowest and the last band over time: `broken_contact` and "
        "`broken_upper_half` in `speeds/v<speed>/pieces_time.csv`.",
        1e3 * hb[1] * sweep.front().diameter));
    doc.table(head, reg);
  }
  // A ledger lost by more than 1 % means energy was made or lost by the numerics (a contact
  // born deep created 208 J in one sphere run that completed): say so beside the numbers.
  // The turned meshes' runs too: their numbers feed the pattern's counts, and a friction-2.0
  // sweep lost 8.5 % on one of them while the speeds/ runs closed.
  std::vector<std::string> lost;
  for (const auto& r : sweep)
    if (r.balance_max > 0.01) lost.push_back(fmt::format("{:g} m/s ({:.2g})", r.speed, r.balance_max));
  for (std::size_t i = first_realisation; i < plan.size(); ++i)
    if (errors[i].empty() && res[i].balance_max > 0.01)
      lost.push_back(fmt::format("{:g} m/s, orientation {}{} ({:.2g})", plan[i].speed, plan[i].orientation,
                                 plan[i].draw > 0 ? fmt::format(", draw {}", plan[i].draw) : "", res[i].balance_max));
  if (!lost.empty())
    doc.para(fmt::format(
        "**Energy balance lost** (more than 1 % of the largest term) at {}: energy was made or lost by the numerics, "
        "so that run's fragments are not to be trusted; `series.csv` (`balance_error`) shows when.",
        fmt::join(lost, ", ")));
  // Overlaps between elements that no contact computed are forgiven, which the balance does
  // not see, so their energy is named against the impact's (with the plate's: those push).
  std::vector<std::string> unseen, unknown;
  bool large = false;
  for (const auto& r : sweep) {
    if (std::isnan(r.born_unseen_energy)) {
      unknown.push_back(fmt::format("{:g}", r.speed));
      continue;
    }
    const double e = r.born_unseen_energy + r.born_wall_energy;
    if (e <= 0) continue;
    large = large || r.born_unseen_energy > 0.01 * r.kinetic_start;
    unseen.push_back(fmt::format(
        "{:g} m/s {:.3g} J ({:.3g} % of the impact energy{})", r.speed, e, 100 * e / r.kinetic_start,
        r.born_wall_energy > 0 ? fmt::format("; {:.3g} J with the plate", r.born_wall_energy) : std::string()));
  }
  if (unknown.size() < sweep.size()) {
    std::string p =
        "Contacts first found already overlapping where no contact had been computed (an element reached through an "
        "edge or a vertex before a joint of it failed; `born_unseen_energy` and `born_wall_energy` in `series.csv`)";
    if (unseen.empty())
      p += ": none by the compared time";
    else
      p += fmt::format(
          ", the spring energy of those overlaps by the compared time: {}. Between elements such an overlap is "
          "forgiven, not resolved: the two stay that far into each other until they part, and the balance does not "
          "see it (the plate pushes with its overlap, which the balance does see). Its energy is what it would have "
          "made had it pushed{}",
          fmt::join(unseen, ", "),
          large ? "; **more than 1 % of the impact energy**: that run's pieces met where its contacts did not look"
                : "");
    if (!unknown.empty())
      p += fmt::format(" (not recorded at {} m/s: runs older than that record)", fmt::join(unknown, ", "));
    doc.para(p + ".");
  }
  std::vector<std::vector<std::string>> pat;
  for (const auto& r : sweep)
    pat.push_back({fmt::format("{:g}", r.speed), sphere::expected_pattern(r.speed),
                   fmt::format("{} fragments, {} >= 10 %, largest {:.2f}, {} of one element{}", r.fragments.count(),
                               r.pieces_10pct, r.fragments.largest_fraction(), r.fragments.single_element(),
                               r.through_crack ? ", through crack" : ", no through crack"),
                   sphere::pattern_met(r) ? "yes" : "no"});
  doc.subsection("Against the paper's description");
  doc.table({"speed [m/s]", "paper", "dspdem", "matches"}, pat);
  {
    const std::string nb = monotonic(
        sweep, [](const SphereImpactResult& r) { return double(r.fragments.count()); }, 1);
    const std::string lb = monotonic(
        sweep, [](const SphereImpactResult& r) { return r.fragments.largest_fraction(); }, -1);
    doc.para(fmt::format("Fragment count with speed: {}. Largest-fragment fraction with speed: {}.",
                         nb.empty() ? "never falls" : "falls between " + nb,
                         lb.empty() ? "never rises" : "rises between " + lb));
  }
  // The runs at speeds[si], by plan index: the sweep's own (the case's mesh, k0) first, then
  // those of plan[first_realisation, end) at that speed (the turned meshes, then the draws).
  auto at_speed = [&](std::size_t si, std::size_t end) {
    std::vector<std::size_t> ix{si};
    for (std::size_t i = first_realisation; i < end; ++i)
      if (std::abs(plan[i].speed - speeds[si]) < 1e-9) ix.push_back(i);
    return ix;
  };
  auto result_of = [&](std::size_t i) { return errors[i].empty() ? &res[i] : nullptr; };
  // Over the realisations: per speed and per mesh (realisations.hpp).
  sphere::EverySpeed every;
  if (a.realisations > 1) {
    std::vector<std::vector<sphere::RealisationRun>> by_speed(speeds.size());
    for (std::size_t si = 0; si < speeds.size(); ++si)
      for (std::size_t i : at_speed(si, first_draw))
        by_speed[si].push_back({plan[i].orientation, result_of(i), errors[i]});
    every = sphere::realisation_tables(
        doc, speeds, by_speed,
        {k0, a.realisations, dir, speeds_folders,
         report::earlier_report_folders(earlier, first_realisation, first_draw, "orientations", dir)});
  }
  if (a.draws > 1) {
    std::vector<std::vector<sphere::DrawRun>> by_speed(speeds.size());
    for (std::size_t si = 0; si < speeds.size(); ++si)
      for (std::size_t i : at_speed(si, plan.size()))
        by_speed[si].push_back({plan[i].orientation, plan[i].draw, result_of(i), errors[i]});
    sphere::draw_tables(doc, speeds, by_speed, a.draws, dir,
                        report::earlier_report_folders(earlier, first_draw, plan.size(), "draws", dir));
  }
  if (!a.no_render) {
    doc.subsection("All speeds at the compared time");
    doc.para("Fragments (a colour per piece), cut on the mid-plane z = 0 (top row) and from outside (bottom row):");
    doc.figure("fragments montage", kMontageFragmentsPng);
    doc.para("Broken joints (red) over the translucent sphere:");
    doc.figure("cracks montage", kMontageCracksPng);
  }
  doc.section("Fragment size distribution");
  doc.para("Per speed in `speeds/v<speed>/fragment_masses.csv`; all speeds in `fragment_masses.csv`.");
  doc.figure("cumulative fragment mass distribution", kFragmentMassesPng);
  doc.section("Cracks, pieces and contact force over time");
  doc.figures({{"crack area", kCrackAreaPng}, {"plate force", kPlateForcePng}});
  doc.para(split_times(sweep, c.frame_interval));
  doc.figure("largest piece against time", kLargestPiecePng);
  if (!reach_curves.empty()) {
    doc.para(fmt::format(
        "How far up the cracks reach: the height above the sphere's lowest point below which {:.0f} % of the broken "
        "joints' area lies, over the diameter, each joint where it was at the start (so a piece flying off does not "
        "move its crack). It rises as broken joints spread up through the sphere, whether or not they have cut a "
        "piece free yet. The table's second figure is the highest broken joint (its centroid). Per speed in "
        "`speeds/v<speed>/pieces_time.csv`.",
        100 * SphereImpactResult::reach_fraction));
    doc.figure("crack reach against time", kCrackReachPng);
  }
  doc.section("Where the impact energy went");
  std::vector<std::vector<std::string>> en;
  for (const auto& r : sweep) en.push_back(energy_row(r));
  doc.para(
      "At the compared frame (the one the pieces above are counted in, nearest the compared time after the first "
      "contact), as a percentage of the impact energy:");
  doc.table({"speed [m/s]", "impact energy [J]", "kinetic [%]", "elastic [%]", "fracture [%]", "friction [%]",
             "damping [%]", "fracture [J]"},
            en);
  if (a.study) {
    doc.section("Speed against error");
    std::vector<std::vector<std::string>> st;
    auto row = [&](const std::string& name, const std::string& knob, const SphereImpactResult& r) {
      return std::vector<std::string>{name,
                                      knob,
                                      std::to_string(r.elements),
                                      fmt::format("{:.0f}", r.wall_s),
                                      std::to_string(r.steps),
                                      std::to_string(r.fragments.count()),
                                      std::to_string(r.pieces_10pct),
                                      fmt::format("{:.3f}", r.fragments.largest_fraction()),
                                      fmt::format("{:.1f}", r.joints ? 100.0 * r.broken_joints / r.joints : 0.0),
                                      fmt::format("{:.2f}", r.fracture),
                                      fmt::format("{:.1e}", r.balance_max)};
    };
    for (double v : study_speeds) {
      for (const auto& r : sweep)
        if (std::abs(r.speed - v) < 1e-9) st.push_back(row(speed_name(v) + "_reference", "the case", r));
      for (std::size_t i = n_sweep; i < n_sweep + n_study; ++i) {
        if (std::abs(plan[i].speed - v) > 1e-9) continue;
        if (errors[i].empty())
          st.push_back(row(plan[i].name, plan[i].knob, res[i]));
        else {
          std::vector<std::string> failed(11);
          failed[0] = plan[i].name, failed[1] = plan[i].knob, failed[2] = "failed: " + errors[i];
          st.push_back(failed);
        }
      }
    }
    doc.table({"run", "knob", "elements", "wall [s]", "steps", "fragments", "pieces >= 10 %", "largest",
               "joints broken [%]", "fracture [J]", "balance max"},
              st);
  }
  // The headline for the figures site: the paper's pattern speed by speed.
  report::Headline& h = doc.headline();
  h.scene = "sphere_impact", h.title = "Sphere impact (paper 2.5)";
  h.summary = fmt::format(
      "A rock sphere {:.0f} mm across ({} tetrahedra, {} joints) strikes a rigid plate at {} speed{}; the pieces are "
      "compared {:.3g} ms after the first contact ({}).",
      1e3 * sweep.front().diameter, sweep.front().elements, sweep.front().joints, sweep.size(),
      sweep.size() == 1 ? "" : "s", 1e3 * t_cmp, as_paper);
  for (const auto& r : sweep)
    h.rows.push_back(
        {fmt::format("pieces at {:g} m/s", r.speed), sphere::expected_pattern(r.speed),
         fmt::format("{} fragments, {} of at least 10 %, largest {:.2f}{}", r.fragments.count(), r.pieces_10pct,
                     r.fragments.largest_fraction(), r.through_crack ? ", through crack" : ", no through crack"),
         report::agrees(sphere::pattern_met(r)),
         "SphereImpact.SweepFollowsThePapersPatternAndMatchesTheStoredMontage"});
  if (!every.count.empty())
    h.rows.push_back({every.speeds.size() == 1
                          ? fmt::format("meshes with the paper's pattern at {:g} m/s", every.speeds.front())
                          : std::string("meshes with the paper's pattern at every speed run that the paper describes"),
                      "the pattern (one mesh)", every.count, report::agrees(every.most),
                      "Cli.ReportRealisationsRunEachSpeedAgainOnTurnedMeshes"});
  {
    double worst = 0;
    for (const auto& r : sweep) worst = std::max(worst, r.balance_max);
    for (std::size_t i = first_realisation; i < plan.size(); ++i)
      if (errors[i].empty()) worst = std::max(worst, res[i].balance_max);
    h.rows.push_back(report::balance_row(
        worst, "SphereImpact.SweepFollowsThePapersPatternAndMatchesTheStoredMontage",
        fmt::format("energy balance, largest error over the speeds{}{}", a.realisations > 1 ? " and orientations" : "",
                    a.draws > 1 ? " and draws" : "")));
  }
  if (!a.no_render) {
    doc.thumbnail("fragments, every speed", kMontageFragmentsPng);
    doc.thumbnail("cracks, every speed", kMontageCracksPng);
    // The animation of the speed nearest the paper's 7.5 m/s.
    const SphereImpactResult* near = &sweep.front();
    for (const auto& r : sweep)
      if (std::abs(r.speed - 7.5) < std::abs(near->speed - 7.5)) near = &r;
    const std::string rel = fs::relative(near->files_dir, dir).string();
    doc.section(fmt::format("The run at {:g} m/s", near->speed));
    doc.animation(fmt::format("fragments at {:g} m/s", near->speed), rel + "/images/fragments",
                  rel + "/images/fragments/frame_0000.png");
  }
  doc.thumbnail("fragment mass distribution", kFragmentMassesPng);
  h.wall_s = total.seconds();
  doc.write();
  earlier_files.drop();
  log::info("report: {}/report.md ({:.1f} s)", dir, total.seconds());
  return 0;
}

}  // namespace dspdem
