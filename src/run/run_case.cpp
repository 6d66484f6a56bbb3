#include "run/run_case.hpp"

#include <omp.h>
#include <unistd.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <functional>
#include <optional>

#include "core/error.hpp"
#include "core/log.hpp"
#include "core/timer.hpp"
#include "fem/stable_dt.hpp"
#include "io/model_builder.hpp"
#include "io/run_summary.hpp"
#include "io/staging.hpp"
#include "io/vtu_writer.hpp"
#include "joint/fragments.hpp"
#include "joint/joint_compliance.hpp"
#include "mesh/locality.hpp"
#include "run/case_mesh.hpp"
#include "time/extrinsic.hpp"
#include "time/integrator.hpp"
#include "time/stop_rule.hpp"

namespace dspdem {

namespace {
namespace fs = std::filesystem;
volatile std::sig_atomic_t g_interrupted = 0;
extern "C" void on_signal(int) { g_interrupted = 1; }

std::string format_duration(double s) {
  if (!std::isfinite(s)) return "?";
  if (s < 120) return fmt::format("{:.0f}s", s);
  if (s < 7200) return fmt::format("{:.0f}m{:02.0f}s", std::floor(s / 60), std::fmod(s, 60));
  return fmt::format("{:.0f}h{:02.0f}m", std::floor(s / 3600), std::fmod(s / 60, 60));
}

class Series {
 public:
  Series(const std::string& path, const Model& m) : f_(path) {
    DSPDEM_CHECK(f_.good(), "cannot write '{}'", path);
    f_ << "time,step,kinetic,internal,external_work,damping,joint_elastic,fracture_I,fracture_II,broken_joints,"
          "crack_area";
    if (m.contact.enabled()) f_ << ",contact_elastic,friction,contact_damping,contacts";
    f_ << ",balance_error";  // monitors follow this column (dspdem render plots each)
    for (const auto& w : m.contact.walls()) {
      f_ << ',' << w.name << "_fx," << w.name << "_fy," << w.name << "_fz";
      if (w.free)  // a free wall's motion: its centre and velocity
        for (const char* q : {"_x", "_y", "_z", "_vx", "_vy", "_vz"}) f_ << ',' << w.name << q;
    }
    for (const auto& ms : m.monitors) f_ << ',' << ms.cfg.name;
    f_ << '\n';
  }
  void row(const Integrator& it, const Model& m) {
    const Energy e = it.energy();
    f_ << fmt::format("{:.10g},{},{:.10g},{:.10g},{:.10g},{:.10g},{:.10g},{:.10g},{:.10g},{},{:.10g}", it.time(),
                      it.steps(), e.kinetic, e.internal, e.external_work, e.damping, e.joint_elastic, e.fracture_I,
                      e.fracture_II, e.broken_joints, e.crack_area);
    if (m.contact.enabled())
      f_ << fmt::format(",{:.10g},{:.10g},{:.10g},{}", e.contact_elastic, e.friction, e.contact_damping,
                        m.contact.totals().contacts);
    f_ << fmt::format(",{:.4g}", e.balance_error());
    for (const auto& w : m.contact.walls()) {
      f_ << fmt::format(",{:.10g},{:.10g},{:.10g}", w.force(0), w.force(1), w.force(2));
      if (w.free)
        f_ << fmt::format(",{:.10g},{:.10g},{:.10g},{:.10g},{:.10g},{:.10g}", w.centre(0), w.centre(1), w.centre(2),
                          w.velocity(0), w.velocity(1), w.velocity(2));
    }
    for (const auto& ms : m.monitors) f_ << fmt::format(",{:.10g}", it.monitor(ms));
    f_ << '\n';
    f_.flush();
  }

 private:
  std::ofstream f_;
};
/// The series.csv column named by [time] stop_series: a wall force or a monitor.
std::function<Real()> series_column(const CaseConfig& c, const Model& m, const Integrator& it) {
  const std::string& name = c.stop_series;
  // The kinetic energy: a heap or a rubble pile that has come to rest.
  if (name == "kinetic") return [&it]() { return it.energy().kinetic; };
  for (const auto& w : m.contact.walls())
    for (int k = 0; k < 3; ++k)
      if (name == w.name + "_f" + "xyz"[k]) return [&w, k]() { return w.force(k); };
  for (const auto& ms : m.monitors)
    if (name == ms.cfg.name) return [&it, &ms]() { return it.monitor(ms); };
  std::string known = " kinetic";
  for (const auto& w : m.contact.walls()) known += fmt::format(" {0}_fx {0}_fy {0}_fz", w.name);
  for (const auto& ms : m.monitors) known += " " + ms.cfg.name;
  fail(
      "{}: [time] stop_series = \"{}\" is not the kinetic energy, a wall force or a monitor column of series.csv "
      "(known:{})",
      c.path, name, known);
}
}  // namespace

int run_case(const CaseConfig& c, const RunOptions& opt) {
  Timer wall;
  log::info("dspdem run: case '{}' ({})", c.name, c.path);
  Mesh mesh = load_case_mesh(c);
  // Elements and nodes in a spatial order before anything numbers them (joints, contact,
  // output): the step's kernels then read neighbours from neighbouring memory. Here, not in
  // build_model, so that a model built from a structured test mesh keeps its numbering.
  order_for_locality(mesh);
  Model model = build_model(c, std::move(mesh));
  const FemModel& fem = model.fem;
  log::info("  mesh {}: {} nodes, {} elements, {} body(ies)", c.mesh_generator.empty() ? c.mesh_file : c.mesh_generator,
            fem.n_nodes, fem.n_elements, model.body_names.size());

  if (model.joints.size() > 0)
    log::info("  joints: {} ({} triangles, {} quadrilaterals) on fracturable bodies; nodes {} -> {}",
              model.joint_report.joints, model.joint_report.tri, model.joint_report.quad,
              model.joint_report.nodes_before, model.joint_report.nodes_after);
  Real joint_compliance = 0;
  if (model.joints.size() > 0) {
    std::vector<Real> elem_E(fem.n_elements), elem_vol(fem.n_elements, 0.0);
    for (Index e = 0; e < fem.n_elements; ++e) elem_E[e] = model.materials[fem.elem_material[e]].E;
    for (const auto& b : fem.blocks)
      for (Index e = 0; e < b.size(); ++e) elem_vol[b.elem[e]] = b.vol[e];
    joint_compliance = joint::added_compliance(model.joints, elem_E, elem_vol);
    log::info(
        "  intact joints add about {:.2f} % to the compliance of the jointed bodies (penalty springs in series; "
        "joint_penalty trades this against the step)",
        100 * joint_compliance);
  }
  if (model.joint_report.split_without_joint > 0)
    log::warn(
        "{} node(s) were split into unconnected copies with no joint between them (elements meeting only at an "
        "edge or a vertex, or across a tet/hex interface): the pieces there are not tied together",
        model.joint_report.split_without_joint);
  const StableStep crit = stable_step(model);
  if (crit.element < 0 && !(c.dt > 0))
    fail("{}: nothing limits the time step (only rigid bodies, and no contact): set [time] dt", c.path);
  const std::size_t lim_tag = crit.element >= 0 ? fem.elem_tag[crit.element] : 0;
  Real dt = c.dt > 0 ? c.dt : c.safety * crit.dt;
  log::info("  critical step {:.4g} s, limited by {} {} (body '{}'); using dt = {:.4g} s{}", crit.dt,
            crit.limiter == "joint"     ? "a joint of element"
            : crit.limiter == "contact" ? "the contact springs of element"
                                        : "element",
            lim_tag, crit.element >= 0 ? model.body_names[fem.elem_body[crit.element]] : "-", dt,
            c.dt > 0 ? " (fixed)" : fmt::format(" ({} x critical)", c.safety));
  if (model.contact.enabled())
    log::info("  contact: on, {} wall(s); candidates: elements with a free face, refreshed as joints fail",
              model.contact.walls().size());
  if (c.dt > crit.dt) {
    if (!c.allow_unstable)
      fail(
          "{}: [time] dt = {:.4g} s exceeds the critical step {:.4g} s (limited by element {}); lower dt, remove it "
          "for automatic, or set time.allow_unstable = true to study the instability",
          c.path, c.dt, crit.dt, lim_tag);
    log::warn(
        "[time] dt = {:.4g} s is {:.2f} x the critical step {:.4g} s (element {}): expect the run to be stopped "
        "by the stability checks",
        c.dt, c.dt / crit.dt, crit.dt, lim_tag);
  }
  long n_steps = static_cast<long>(std::ceil(c.t_end / dt - 1e-9));
  if (c.max_steps > 0) n_steps = std::min(n_steps, c.max_steps);

  Staging stage(opt.out_dir);
  const std::string frames_dir = (fs::path(stage.path()) / "frames").string();
  fs::create_directories(frames_dir);
  write_file_atomic((fs::path(stage.path()) / "case.resolved.toml").string(), c.resolved_toml);
  Series series((fs::path(stage.path()) / "series.csv").string(), model);
  std::vector<std::pair<double, std::string>> frames;
  const std::string pvd = (fs::path(stage.path()) / "run.pvd").string();

  Integrator it(model, dt);
  std::optional<ExtrinsicInsertion> extrinsic;
  if (!model.joints.closed.empty()) {
    extrinsic.emplace(c.insertion_interval);
    log::info(
        "  extrinsic insertion: {} joint(s) closed until their faces reach the strength, checked every {} step(s)",
        std::count(model.joints.closed.begin(), model.joints.closed.end(), 1), c.insertion_interval);
  }
  std::vector<Real> stress;
  std::vector<Real> elem_mass(fem.n_elements, 0.0);
  for (const auto& b : fem.blocks)
    for (Index e = 0; e < b.size(); ++e)
      elem_mass[b.elem[e]] = b.vol[e] * model.materials[fem.elem_material[b.elem[e]]].density;
  joint::Fragments frag = joint::find_fragments(model.mesh, model.joints, elem_mass);
  // fragments.csv: per frame the count and the largest pieces (mass, size, where), so that
  // any scene's report can follow the break-up without reading the frames back.
  std::ofstream frag_csv(fs::path(stage.path()) / "fragments.csv");
  DSPDEM_CHECK(frag_csv.good(), "cannot write '{}'", (fs::path(stage.path()) / "fragments.csv").string());
  frag_csv << "frame,time,count,rank,id,mass,elements,x,y,z\n";  // id: the frames' fragment field
  constexpr std::size_t kFragmentRows = 20;
  std::vector<std::pair<double, std::string>> joint_frames;
  const std::string joints_pvd = (fs::path(stage.path()) / "joints.pvd").string();
  auto write_frame = [&]() {
    it.stresses(stress);
    FrameData fd;
    fd.mesh = &model.mesh;
    fd.x = it.x().data();
    fd.x0 = fem.x0.data();
    fd.v = it.v().data();
    fd.stress = stress.data();
    fd.body = fem.elem_body.data();
    frag = joint::find_fragments(model.mesh, model.joints, elem_mass);
    fd.fragment = frag.id.data();
    {
      const auto info = joint::describe_fragments(model.mesh, frag, it.x().data(), elem_mass);
      for (std::size_t k = 0; k < std::min(kFragmentRows, info.size()); ++k)
        frag_csv << fmt::format("{},{:.10g},{},{},{},{:.10g},{},{:.8g},{:.8g},{:.8g}\n", frames.size(), it.time(),
                                frag.count, k + 1, info[k].id, info[k].mass, info[k].elements, info[k].centroid(0),
                                info[k].centroid(1), info[k].centroid(2));
      frag_csv.flush();
    }
    fd.material = fem.elem_material.data();
    fd.fields = c.fields;
    fd.compress = c.compress;
    const std::string name = fmt::format("frame_{:04d}.vtu", frames.size());
    write_vtu((fs::path(frames_dir) / name).string(), fd);
    frames.emplace_back(it.time(), "frames/" + name);
    write_pvd(pvd, frames);
    if (model.joints.size() > 0) {
      const std::string jname = fmt::format("joints_{:04d}.vtu", joint_frames.size());
      write_joints_vtu((fs::path(frames_dir) / jname).string(), model.joints, it.x().data(), c.compress);
      joint_frames.emplace_back(it.time(), "frames/" + jname);
      write_pvd(joints_pvd, joint_frames);
    }
  };

  auto write_summary = [&](const std::string& dir, const std::string& status, const std::string& message) {
    const Energy e = it.energy();
    RunSummary s;
    s.case_name = c.name, s.case_file = c.path, s.status = status, s.message = message;
    s.steps = it.steps(), s.dt = dt, s.dt_critical = crit.dt, s.dt_limiter = crit.limiter;
    s.dt_limiting_element = static_cast<long>(lim_tag);
    s.t_end = it.time(), s.wall_s = wall.seconds(), s.threads = omp_get_max_threads();
    s.nodes = fem.n_nodes, s.elements = fem.n_elements, s.frames = static_cast<long>(frames.size());
    s.joints = model.joints.size(), s.joint_added_compliance = joint_compliance;
    s.broken_joints = e.broken_joints, s.crack_area = e.crack_area;
    s.fragments = frag.count;
    for (Real mm : frag.mass) s.total_mass += mm;
    for (std::size_t i = 0; i < std::min<std::size_t>(10, frag.mass.size()); ++i)
      s.largest_fragment_masses.push_back(frag.mass[i]);
    s.element_steps_per_s = s.wall_s > 0 ? static_cast<double>(it.steps()) * fem.n_elements / s.wall_s : 0.0;
    s.energy = {e.kinetic,    e.internal,    e.external_work,   e.damping,  e.initial,         e.joint_elastic,
                e.fracture_I, e.fracture_II, e.contact_elastic, e.friction, e.contact_damping, e.balance_error()};
    write_run_summary((fs::path(dir) / "summary.json").string(), s);
  };

  g_interrupted = 0;
  auto old_int = std::signal(SIGINT, on_signal);
  auto old_term = std::signal(SIGTERM, on_signal);
  struct Restore {
    decltype(old_int) a, b;
    ~Restore() { std::signal(SIGINT, a), std::signal(SIGTERM, b); }
  } restore{old_int, old_term};

  const bool tty_progress = opt.progress;
  std::function<Real()> stop_value;
  if (!c.stop_series.empty()) stop_value = series_column(c, model, it);
  PeakDropStop stop_rule(c.stop_fraction, c.stop_min_peak);
  std::string stop_message;
  Real stop_at = -1;
  try {
    write_frame();
    series.row(it, model);
    Real next_frame = c.frame_interval, next_series = c.series_interval;
    Timer loop;
    double last_report = 0;
    for (long s = 0; s < n_steps; ++s) {
      it.step();
      if (extrinsic) extrinsic->check(model, it);
      bool last = s + 1 == n_steps;
      const Real t = it.time();
      if (t >= next_series - 1e-12 * c.t_end || last) {
        it.check_energy(c.energy_blowup_factor);
        if (stop_value && stop_at < 0 && stop_rule.update(stop_value())) {
          stop_at = t + c.stop_delay;
          stop_message = fmt::format("|{}| fell below {} of its peak {:.6g} at t = {:.6g} s; stopped at ",
                                     c.stop_series, c.stop_fraction, stop_rule.peak(), t);
        }
        if (stop_at >= 0 && t >= stop_at - 1e-12 * c.t_end && !last) {
          last = true;  // this row and a last frame, then stop
          stop_message += fmt::format("t = {:.6g} s", t);
          log::info("  {}", stop_message);
        }
        series.row(it, model);
        while (next_series <= t + 1e-12 * c.t_end) next_series += c.series_interval;
      }
      if (t >= next_frame - 1e-12 * c.t_end || last) {
        write_frame();
        while (next_frame <= t + 1e-12 * c.t_end) next_frame += c.frame_interval;
      }
      if (g_interrupted)
        throw Interrupted(fmt::format("interrupted at step {}, t = {:.6g} s", it.steps(), t), it.steps(), t);
      if (last) break;
      if (tty_progress && loop.seconds() - last_report > 0.5) {
        last_report = loop.seconds();
        const double rate = static_cast<double>(s + 1) / last_report;
        fmt::print(stderr, "\r  step {}/{}  t = {:.4g} s  {:.0f} steps/s  ETA {}   ", s + 1, n_steps, t, rate,
                   format_duration(static_cast<double>(n_steps - s - 1) / rate));
      }
    }
    if (tty_progress) fmt::print(stderr, "\n");
  } catch (const NumericalError& e) {
    if (tty_progress) fmt::print(stderr, "\n");
    write_summary(stage.path(), "failed", e.what());
    write_pvd(pvd, frames);
    const std::string kept = stage.keep_failed();
    throw NumericalError(fmt::format("{}\n  partial results (frames up to the failure) kept in {}", e.what(), kept),
                         e.step, e.time);
  }
  if (extrinsic) log::info("  extrinsic insertion: {} joint(s) opened", extrinsic->opened());
  write_summary(stage.path(), "completed", stop_message);
  stage.commit();
  const Energy e = it.energy();
  log::info("  {} steps to t = {:.6g} s in {:.2f} s ({:.3g} element-steps/s, {} threads); energy balance error {:.2e}",
            it.steps(), it.time(), wall.seconds(), static_cast<double>(it.steps()) * fem.n_elements / wall.seconds(),
            omp_get_max_threads(), e.balance_error());
  log::info("  results in {}/ (run.pvd, {} frames, series.csv, summary.json)", opt.out_dir, frames.size());
  return 0;
}

}  // namespace dspdem
