#include "run/run_case.hpp"

#include <omp.h>
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <optional>
#include <regex>
#include <string_view>

#include "core/error.hpp"
#include "core/file.hpp"
#include "core/folder_lock.hpp"
#include "core/log.hpp"
#include "core/signals.hpp"
#include "core/timer.hpp"
#include "fem/stable_dt.hpp"
#include "io/model_builder.hpp"
#include "io/run_place.hpp"
#include "io/run_summary.hpp"
#include "io/staging.hpp"
#include "io/vtu_writer.hpp"
#include "joint/fragments.hpp"
#include "joint/joint_compliance.hpp"
#include "mesh/locality.hpp"
#include "par/mpi_world.hpp"
#if DSPDEM_HAVE_MPI
#include "par/fragments.hpp"
#include "par/halo.hpp"
#include "par/partition.hpp"
#include "par/subdomain.hpp"
#endif
#include "run/case_mesh.hpp"
#include "run/checkpoint.hpp"
#include "run/estimate.hpp"
#include "run/output_schedule.hpp"
#include "run/series_units.hpp"
#include "time/balance_watch.hpp"
#include "time/extrinsic.hpp"
#include "time/integrator.hpp"
#include "time/stop_rule.hpp"

namespace dspdem {

namespace {
namespace fs = std::filesystem;
volatile std::sig_atomic_t g_interrupted = 0, g_setting_up = 0;
// The set-up's stop message, whole (one write: a report's parallel jobs share its stderr);
// a lock-free atomic, so the handler may read it.
// Without a hint (a lone run's), the message itself; set_setup_stop_hint puts a hint before its
// newline.
constexpr std::string_view kSetupStopped =
    "dspdem: stopped by a signal during the set-up (meshing, the model): nothing written\n";
std::atomic<const char*> g_setup_message{kSetupStopped.data()};
static_assert(std::atomic<const char*>::is_always_lock_free);
// The first signal asks for a stop at the end of the step (checkpoint, outputs closed); a
// second one exits at once. Every output file is written to a temporary name and renamed,
// so what is on disk then is whole: the last checkpoint, frames and collections so far. A
// hang-up is not a second signal: a closing terminal's job gets one from the kernel and one
// from its shell, and must still write its checkpoint.
// During the set-up (meshing, the model; until the staging folder is made) there is nothing
// to keep, and gmsh cannot be asked to stop: any of the three exits at once. Waiting for the
// first step instead kept a run meshing for minutes after a scheduler's or CI's SIGTERM.
extern "C" void on_signal(int sig) {
  if (g_setting_up) {
    const char* msg = g_setup_message.load();
    const ssize_t n = write(STDERR_FILENO, msg, std::strlen(msg));
    (void)n;
    _exit(kExitInterrupted);
  }
  if (g_interrupted && sig != SIGHUP) _exit(kExitInterrupted);
  g_interrupted = 1;
}

}  // namespace

void set_setup_stop_hint(const std::string& hint) {
  // Kept to the end of the process (reachable from here, never freed): the handler may hold
  // the pointer of the one a later call replaces.
  static auto* const kept = new std::vector<std::unique_ptr<const std::string>>;
  kept->push_back(std::make_unique<const std::string>(
      fmt::format("{}{}\n", kSetupStopped.substr(0, kSetupStopped.size() - 1), hint)));
  g_setup_message.store(kept->back()->c_str());
}

namespace {

/// Where the time loop is, besides the model: output schedule, the files' lengths, the stop
/// rule. Saved in checkpoints with the model's state.
struct LoopState {
  std::vector<std::pair<double, std::string>> frames, joint_frames;
  Real next_frame = 0, next_series = 0, next_checkpoint = 0;
  Real stop_at = -1;
  long n_steps = 0;  ///< the step the run ends at, unless a stop rule ends it first
  std::string stop_message;
  std::uint64_t series_bytes = 0, fragments_bytes = 0;
  /// CRC-32s of those bytes: a restart takes its series from the folder only if they are the
  /// ones its run wrote (a checkpoint copied into another run's folder spliced two runs' rows).
  std::uint32_t series_crc = 0, fragments_crc = 0;
  double wall_before = 0;  ///< wall time of the run before its last restart [s]
  template <class Ar>
  void persist(Ar& ar) {
    ar(frames, joint_frames, next_frame, next_series, next_checkpoint, stop_at, n_steps, stop_message, series_bytes,
       fragments_bytes, series_crc, fragments_crc, wall_before);
  }
};

// Whether the file at `path` ends as VTK's XML files do, with </VTKFile> (and blanks).
bool ends_as_vtk_file(const std::string& path) {
  std::ifstream f(path, std::ios::binary | std::ios::ate);
  const std::streamoff size = f.tellg();
  if (!f || size <= 0) return false;
  const std::streamoff tail = std::min<std::streamoff>(size, 64);
  std::string end(static_cast<std::size_t>(tail), '\0');
  f.seekg(size - tail);
  f.read(end.data(), tail);
  if (!f) return false;
  end.erase(end.find_last_not_of(" \t\r\n") + 1);
  constexpr std::string_view kEnd = "</VTKFile>";
  return end.size() >= kEnd.size() && end.compare(end.size() - kEnd.size(), kEnd.size(), kEnd) == 0;
}

// A restart's outputs so far: the frames up to the checkpoint (hard links: frames never
// change once written, and a link costs no space), series.csv and fragments.csv cut back to
// their length then, the collections written again. The source folder is left as it is, so
// a restart that fails can be tried again.
void restore_outputs(const fs::path& from, const fs::path& to, const LoopState& ls) {
  fs::create_directories(to / "frames");
  auto link = [&](const std::string& rel) {
    std::error_code ec;
    fs::create_hard_link(from / rel, to / rel, ec);
    if (ec) fs::copy_file(from / rel, to / rel, fs::copy_options::overwrite_existing);
  };
  // A frame's files: itself, and a distributed frame's (.pvtu) pieces, as it lists them
  // (<Piece Source="...">, beside it): listed from the folder instead, a piece gone was not
  // missed (a review's).
  auto frame_files = [&](const std::string& rel) {
    std::vector<std::string> files{rel};
    if (fs::path(rel).extension() == ".pvtu" && fs::exists(from / rel)) {
      const std::string text = read_file((from / rel).string(), "frame");
      static const std::regex piece(R"re(<Piece\s+Source\s*=\s*"([^"]+)")re");
      for (auto it = std::sregex_iterator(text.begin(), text.end(), piece); it != std::sregex_iterator(); ++it)
        files.push_back((fs::path(rel).parent_path() / (*it)[1].str()).string());
      DSPDEM_CHECK(files.size() > 1, "restart: frame '{}' of the checkpoint's run lists no pieces",
                   (from / rel).string());
    }
    return files;
  };
  // The checkpoint's run's files, checked before anything is linked or copied: its series as
  // far as it had written them (their CRC-32s) and every frame it lists.
  auto check = [&](const char* name, std::uint64_t bytes, std::uint32_t crc) {
    DSPDEM_CHECK(fs::exists(from / name) && fs::file_size(from / name) >= bytes,
                 "restart: '{}' is shorter than when the checkpoint was written ({} bytes)", (from / name).string(),
                 bytes);
    DSPDEM_CHECK(file_crc((from / name).string(), bytes).crc == crc,
                 "restart: '{}' is not the file the checkpoint's run wrote (its first {} bytes differ): the folder "
                 "holds another run's outputs; restart from a checkpoint in the folder of the run that wrote it",
                 (from / name).string(), bytes);
  };
  check("series.csv", ls.series_bytes, ls.series_crc);
  check("fragments.csv", ls.fragments_bytes, ls.fragments_crc);
  std::vector<std::string> frames;
  for (const auto* list : {&ls.frames, &ls.joint_frames})
    for (const auto& [t, rel] : *list)
      for (const std::string& f : frame_files(rel)) {
        DSPDEM_CHECK(fs::path(f).lexically_normal().parent_path() == "frames",
                     "restart: frame '{}' of the checkpoint's run names a piece outside frames/: '{}'",
                     (from / rel).string(), f);
        DSPDEM_CHECK(fs::exists(from / f), "restart: frame '{}' of the checkpoint's run is missing",
                     (from / f).string());
        // Whole to its last line (VTK's XML files end with </VTKFile>): a frame cut short passed
        // into the restarted run's results, and failed only when drawn (a probe's).
        DSPDEM_CHECK(ends_as_vtk_file((from / f).string()),
                     "restart: frame '{}' of the checkpoint's run is cut short or damaged (it does not end with "
                     "</VTKFile>)",
                     (from / f).string());
        frames.push_back(f);
      }
  for (const std::string& f : frames) link(f);
  auto cut = [&](const char* name, std::uint64_t bytes) {
    fs::copy_file(from / name, to / name, fs::copy_options::overwrite_existing);
    fs::resize_file(to / name, bytes);
  };
  cut("series.csv", ls.series_bytes);
  cut("fragments.csv", ls.fragments_bytes);
  write_pvd((to / "run.pvd").string(), ls.frames);
  if (!ls.joint_frames.empty()) write_pvd((to / "joints.pvd").string(), ls.joint_frames);
}

class Series {
 public:
  /// append: a restart's series, cut back to the checkpoint (its header is there).
  Series(const std::string& path, const Model& m, bool append)
      : f_(path, append ? std::ios::app | std::ios::binary : std::ios::out | std::ios::binary) {
    DSPDEM_CHECK(f_.good(), "cannot write '{}'", path);
    if (append) return;
    // The columns and their units: run/series_units (the plots' axes read the units there).
    std::string head;
    auto add = [&head](const auto& cols, const std::string& prefix) {
      for (const SeriesColumn& col : cols) head += (head.empty() ? "" : ",") + prefix + std::string(col.name);
    };
    add(kSeriesColumns, "");
    if (m.contact.enabled()) add(kSeriesContactColumns, "");
    add(kSeriesLastColumns, "");  // monitors follow balance_error (dspdem render plots each)
    for (const auto& w : m.contact.walls()) {
      add(kWallForceColumns, w.name);
      if (w.free) add(kFreeWallColumns, w.name);  // a free wall's motion: its centre and velocity
    }
    f_ << head;
    for (const auto& ms : m.monitors) f_ << ',' << ms.cfg.name;
    f_ << '\n';
  }
  void row(const Integrator& it, const Model& m) {
    const Energy e = it.energy();
    f_ << fmt::format("{:.10g},{},{:.10g},{:.10g},{:.10g},{:.10g},{:.10g},{:.10g},{:.10g},{},{:.10g}", it.time(),
                      it.steps(), e.kinetic, e.internal, e.external_work, e.damping, e.joint_elastic, e.fracture_I,
                      e.fracture_II, e.broken_joints, e.crack_area);
    if (m.contact.enabled()) {
      const contact::ContactTotals ct = m.contact.totals();
      f_ << fmt::format(",{:.10g},{:.10g},{:.10g},{},{:.10g},{:.10g},{:.10g}", e.contact_elastic, e.friction,
                        e.contact_damping, ct.contacts, ct.born.split.energy, ct.born.unseen.energy,
                        ct.born.wall.energy);
    }
    f_ << fmt::format(",{:.10g},{:.4g}", e.kick, e.balance_error());
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
  /// What is on disk (flushed first): a checkpoint records it and its CRC-32.
  std::uint64_t bytes() {
    f_.flush();
    return static_cast<std::uint64_t>(f_.tellp());
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
  // From the start: a signal during the set-up (meshing can take minutes) ends the process
  // at once (on_signal), before anything is written.
  g_interrupted = 0;
  g_setting_up = 1;
  ScopedSignals signals({SIGINT, SIGTERM, SIGHUP}, on_signal);
  log::info("dspdem run: case '{}' ({})", c.name, c.path);
  // A run made inside another's side folder went with it, results and all: a restart given
  // --out DIR/interrupted_run ended "completed" in a folder its own end removed (a probe's).
  if (const std::string side = side_folder_on_path(opt.out_dir); !side.empty())
    fail(
        "run: --out {} lies in {}, a folder a run keeps its staged, stopped or failed outputs in, which its restart, "
        "end or next run replaces whole; give --out the run's own folder ({}) or another",
        opt.out_dir, side, std::filesystem::path(side).parent_path().string());
  check_monitor_columns(c);
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
  for (std::size_t b = 0; b < model.zone_joints.size(); ++b) {
    const BodyConfig& bc = c.bodies[b];
    if (bc.zone_material.empty()) continue;
    if (model.zone_joints[b] > 0)
      log::info("  joint zone of body '{}': {} joint(s) take the joint parameters of material '{}'", bc.name,
                model.zone_joints[b], bc.zone_material);
    else  // no two of the zone's fracturable elements share a face: the zone changes nothing
      log::warn(
          "[[bodies]] '{}': no joint lies inside its zone (zone_groups, zone box), so none takes the joint "
          "parameters of material '{}'; a zone needs two of its fracturable elements (fracture = \"all\" or in "
          "fracture_groups) sharing a face",
          bc.name, bc.zone_material);
  }
  // The elements' own critical steps are kept: with extrinsic insertion and the step left to
  // dspdem, closed joints have no spring yet, so the step starts from the elements and the
  // contact and is recomputed each time joints open (in the loop below; it only falls). A
  // fixed [time] dt never changes, so it is checked against every joint open.
  std::vector<Real> per_element;
  element_stable_step(fem, model.materials, &per_element);
  const StableStep crit_all_open = stable_step(model, per_element);
  const bool adaptive_dt = !model.joints.closed.empty() && !(c.dt > 0);
  StableStep crit = crit_all_open;
  if (adaptive_dt) {
    const joint::Ties ties = joint::build_ties(model.joints, fem.n_nodes);
    crit = stable_step(model, per_element, &ties);
  }
  if (crit.element < 0 && !(c.dt > 0)) {
    // A deformable element whose own step came out zero or not a number (a density, an E or a
    // damping far out of range) limits nothing either: named, not said to be rigid (a probe's).
    for (Index e = 0; e < fem.n_elements; ++e)
      if (!(per_element[static_cast<std::size_t>(e)] > 0)) {
        const Material& m = model.materials[fem.elem_material[e]];
        fail(
            "{}: element {} has a critical step of {:g} s, which no step can meet: its material '{}' (density {:g} "
            "kg/m^3, E {:g} Pa, damping_beta {:g} s) holds a value far out of range",
            c.path, fem.elem_tag[e], per_element[static_cast<std::size_t>(e)], m.name, m.density, m.E, m.beta);
      }
    fail("{}: nothing limits the time step (only rigid bodies, and no contact): set [time] dt", c.path);
  }
  auto limiter_text = [&](const StableStep& s) {
    return fmt::format("{} {} (body '{}')",
                       s.limiter == "joint"     ? "a joint of element"
                       : s.limiter == "contact" ? "the contact springs of element"
                                                : "element",
                       s.element >= 0 ? fem.elem_tag[s.element] : 0,
                       s.element >= 0 ? model.body_names[fem.elem_body[s.element]] : "-");
  };
  Real dt = c.dt > 0 ? c.dt : c.safety * crit.dt;
  log::info("  critical step {:.4g} s, limited by {}; using dt = {:.4g} s{}", crit.dt, limiter_text(crit), dt,
            c.dt > 0 ? " (fixed)" : fmt::format(" ({} x critical)", c.safety));
  if (adaptive_dt)
    log::info("  the step falls as joints open (extrinsic insertion); with every joint open it would be {:.4g} s",
              c.safety * crit_all_open.dt);
  if (model.contact.enabled())
    log::info("  contact: on, {} wall(s); candidates: elements with a free face, refreshed as joints fail",
              model.contact.walls().size());
  if (c.dt > crit.dt) {
    if (!c.allow_unstable)
      fail(
          "{}: [time] dt = {:.4g} s exceeds the critical step {:.4g} s (limited by {}); lower dt, remove it "
          "for automatic, or set time.allow_unstable = true to study the instability",
          c.path, c.dt, crit.dt, limiter_text(crit));
    log::warn(
        "[time] dt = {:.4g} s is {:.2f} x the critical step {:.4g} s (limited by {}): expect the run to be "
        "stopped by the stability checks",
        c.dt, c.dt / crit.dt, crit.dt, limiter_text(crit));
  }
  // Steps from step s0 at time t0 to [time] end at step h (or max_steps): the loop's end,
  // worked out again when the step changes.
  // At the start (s0 = 0), a run whose end lies more than kMostSteps steps away is refused
  // unless max_steps bounds it: such a count comes from a mistyped end, step or material
  // (E = 1e300 gave a step of 1e-150 s), and past 2^63 it turned negative and the run
  // "completed" in 0 steps; and a run whose end is nearer than one step takes that one step
  // (below 1e-9 of a step it took none). Worked out again when the step falls, the count is as
  // it always was (the step within 1e-9 of a step of the end is the last), only clamped.
  constexpr double kMostSteps = 1e10;
  auto last_step = [&](long s0, Real t0, Real h) {
    const double q = (c.t_end - t0) / h;
    if (s0 == 0 && !(q <= kMostSteps) && c.max_steps <= 0)
      fail(
          "{}: [time] end = {:.6g} s from t = {:.6g} s at a step of {:.4g} s ({}) is {:.3g} steps, more than "
          "{:.0e}: check the end, the step and the materials that set it (E, density, damping_beta), or bound the run "
          "by [time] "
          "max_steps",
          c.path, c.t_end, t0, h, c.dt > 0 && h == c.dt ? "[time] dt" : "limited by " + limiter_text(crit), q,
          kMostSteps);
    const long rest = static_cast<long>(std::ceil(std::min(q, kMostSteps) - 1e-9));
    const long n = s0 + (s0 == 0 && q > 0 ? std::max(1L, rest) : std::max(0L, rest));
    return c.max_steps > 0 ? std::min(n, c.max_steps) : n;
  };
  if (c.t_end < dt)
    log::warn("[time] end = {:.4g} s is shorter than one step ({:.4g} s): the run takes that one step", c.t_end, dt);

  // After a step with extrinsic insertion: the check, and when joints opened the step lowered
  // to what the tied state allows (their springs act from the next step, at their points'
  // masses). The tied state is the every-joint-open model held to equal copies: its step is
  // never below that one's, though the estimate at the state can be (joint/joint_dt.hpp).
  // Returns whether the step changed.
  auto insert_joints = [&](ExtrinsicInsertion& ext, Integrator& i) {
    if (ext.check(model, i) == 0 || !adaptive_dt) return false;
    StableStep now = stable_step(model, per_element, &i.ties());
    if (now.dt < crit_all_open.dt) now = crit_all_open;
    if (!(c.safety * now.dt < i.dt())) return false;
    crit = now;
    i.set_dt(c.safety * crit.dt);
    return true;
  };
  auto make_extrinsic = [&]() {
    std::optional<ExtrinsicInsertion> ext;
    if (!model.joints.closed.empty())
      ext.emplace(c.insertion_interval, c.insertion_stress,
                  c.insertion_cut_front ? InsertionFront::Cut : InsertionFront::Tied);
    return ext;
  };

  if (opt.estimate) {
    // A step count capped by [time] max_steps is the run's, whatever the step would do after.
    const long n = last_step(0, 0.0, dt);
    const bool stops = !c.stop_series.empty(), capped = c.max_steps > 0 && n == c.max_steps;
    // The steps as the run takes them, frames aside: with its extrinsic checks (about a sixth
    // of the step's time on the disc's extrinsic row, session 106) and its series rows (the
    // energy check and a row, written nowhere, on the run's schedule: its row at t = 0, before
    // its loop, is not checked).
    std::optional<ExtrinsicInsertion> ext = make_extrinsic();
    Series rows("/dev/null", model, false);
    Real next_series = c.series_interval, dt_now = dt, t_now = 0;
    long steps_now = 0;
    estimate_run(
        c, model, dt, n, stops, adaptive_dt && !capped,
        [&](const Integrator& i) {
          if (stops) series_column(c, model, i);
        },
        [&](Integrator& i) {
          if (ext && insert_joints(*ext, i)) dt_now = i.dt();
          t_now = i.time(), steps_now = i.steps();
          if (i.time() >= next_series - 1e-12 * c.t_end) {
            i.check_energy(c.energy_blowup_factor);
            rows.row(i, model);
            next_series = next_output_time(next_series, i.time(), c.series_interval, 1e-12 * c.t_end);
          }
        });
    // The steps still to go at the step reached: the run's count from there on, as its loop
    // works it out again at each fall (the step may fall further: at least that many; the run
    // may also stop on a load drop: about).
    if (ext && ext->opened() > 0) {
      fmt::print("extrinsic insertion opened {} joint(s) during those steps", ext->opened());
      if (dt_now < dt)
        fmt::print("; the step fell from {:.6g} s to {:.6g} s, at which the run takes {} {} steps", dt, dt_now,
                   stops ? "about" : "at least", last_step(steps_now, t_now, dt_now));
      fmt::print("\n");
    }
    return 0;
  }

  // A distributed run (mpirun -n N): the whole model was built on every process, as above,
  // and each keeps its share (par/subdomain.hpp); the step is the whole model's.
  const int n_ranks = par::size(), my_rank = par::rank();
  const bool distributed = n_ranks > 1;
  const Index whole_nodes = fem.n_nodes, whole_elements = fem.n_elements, whole_joints = model.joints.size();
  std::vector<std::pair<std::string, long>> monitor_joints;  // the whole model's, for summary.json
  for (const MonitorSet& ms : model.monitors)
    if (ms.cfg.counts_joints())
      monitor_joints.emplace_back(ms.cfg.name, std::count(ms.joint_in.begin(), ms.joint_in.end(), 1));
  Distribution* dist = nullptr;  // a distributed run's exchange and reductions
#if DSPDEM_HAVE_MPI
  std::unique_ptr<par::MpiHalo> halo;
#endif
  if (distributed) {
#if DSPDEM_HAVE_MPI
    auto refuse = [&](bool bad, const char* what) {
      if (bad)
        fail("{}: {} is not yet supported in a distributed run (mpirun -n {}); run it on one process", c.path, what,
             n_ranks);
    };
    refuse(!model.rigid.empty(), "a rigid body");
    refuse(!model.joints.closed.empty(), "extrinsic joint insertion");
    const std::vector<int> part = par::partition_elements(model, n_ranks);
    par::Subdomain sd = par::make_subdomain(model, part, my_rank);
    halo = std::make_unique<par::MpiHalo>(sd);  // before the share moves out of sd
    dist = halo.get();
    model = std::move(sd.local);
    if (model.contact.enabled()) model.contact.set_exchange(halo.get());
    const std::vector<long> own = par::all_gather(model.owned_nodes);
    const std::vector<long> ghosts = par::all_gather(halo->ghosts());
    const std::vector<long> elems =
        par::all_gather(static_cast<long>(std::count(model.elem_owned.begin(), model.elem_owned.end(), 1)));
    const std::vector<long> msgs = par::all_gather(halo->messages_per_exchange());
    log::info(
        "  distributed over {} processes (METIS): own elements {}, own nodes {}, ghost nodes {}, messages "
        "sent per step {}",
        n_ranks, fmt::join(elems, "/"), fmt::join(own, "/"), fmt::join(ghosts, "/"), fmt::join(msgs, "/"));
#endif
  }

  // From here a signal stops the run at the end of a step, with a checkpoint: the staging
  // folder is made whole (and cleared by a later run if this one is killed) or not at all.
  g_setting_up = 0;
  // A folder a report or a render filled from another run (io/run_place.hpp): its images and
  // tables would sit beside this run's results as if they were its own. Emptied once the set-up
  // has succeeded, so a run refused in its set-up leaves it as it was.
  if (my_rank == 0) {
    // A render drawing the run this one is to replace would go on reading its frames as they
    // are replaced, and the images it leaves would mix both runs.
    DSPDEM_CHECK(!FolderLock::held(opt.out_dir, render_lock_file),
                 "{}: a render is drawing into this folder now; wait for it to end, or give --out another folder",
                 opt.out_dir);
    check_run_frames(opt.out_dir);  // before anything is emptied: a refusal changes nothing
    clear_derived_place(opt.out_dir);
  }
  // Process 0 makes the staging folder and commits it; the others write their pieces into it.
  Staging stage(opt.out_dir, par::broadcast(static_cast<long>(getpid())), my_rank == 0);
  par::barrier();  // the folder made before anyone writes into it
  const fs::path sdir(stage.path());
  // Restarting from a killed run's staging folder of this very name: it was moved aside.
  std::string restart_file = opt.restart_file;
  if (const long aside = par::broadcast(stage.moved_aside());
      aside > 0 && !restart_file.empty() &&
      fs::weakly_canonical(fs::path(restart_file).parent_path()) == fs::weakly_canonical(sdir))
    restart_file = (fs::path(stage.path() + "." + std::to_string(aside)) / fs::path(restart_file).filename()).string();
  const std::string frames_dir = (sdir / "frames").string();
  fs::create_directories(frames_dir);
  const std::string pvd = (sdir / "run.pvd").string();
  const std::string joints_pvd = (sdir / "joints.pvd").string();
  const std::string ckpt = checkpoint_piece((sdir / "checkpoint.bin").string(), my_rank);  // this process's

  Integrator it(model, dt, dist);
  it.watch_flag(&g_interrupted);
  std::optional<ExtrinsicInsertion> extrinsic = make_extrinsic();
  if (extrinsic) {
    log::info(
        "  extrinsic insertion: {} joint(s) closed until their faces reach the strength (traction from the {} "
        "stress), checked every {} step(s)",
        std::count(model.joints.closed.begin(), model.joints.closed.end(), 1),
        c.insertion_stress == joint::FaceStress::Mean ? "two elements' mean" : "more stressed element's",
        c.insertion_interval);
  }
  std::vector<Real> stress;
  std::vector<Real> elem_mass(fem.n_elements, 0.0);
  for (const auto& b : fem.blocks)
    for (Index e = 0; e < b.size(); ++e)
      elem_mass[b.elem[e]] = b.vol[e] * model.materials[fem.elem_material[b.elem[e]]].density;
  // Distributed: found per frame by a union-find over the processes (par/fragments.hpp).
  joint::Fragments frag;
  if (!distributed) frag = joint::find_fragments(model.mesh, model.joints, elem_mass);
  PeakDropStop stop_rule(c.stop_fraction, c.stop_min_peak);
  BalanceWatch balance_watch(c.energy_balance_warn);
  LoopState ls;
  ls.next_frame = c.frame_interval, ls.next_series = c.series_interval, ls.next_checkpoint = opt.checkpoint_every;
  ls.n_steps = last_step(0, 0.0, dt);

  std::string case_file = c.path;  // as the run was started (a restart reads it by its absolute path)
  CheckpointHeader head;
  head.build = checkpoint_build_id();
  head.executable = executable_id();
  head.case_path = fs::absolute(c.path).lexically_normal().string();
  head.sets = opt.sets, head.resolved_toml = c.resolved_toml;
  head.nodes = whole_nodes, head.elements = whole_elements, head.joints = whole_joints;
  head.dt = dt, head.checkpoint_every = opt.checkpoint_every, head.checkpoint_wall = opt.checkpoint_wall;
  head.processes = n_ranks, head.rank = my_rank;
  // The same list saves and loads (core/archive.hpp).
  auto persist = [&](StateArchive& ar) {
    ar.section("loop");
    ar(ls, stop_rule);
    it.persist(ar);
    ar.section("insertion");
    ar(crit.dt, crit.element, crit.limiter);  // the critical step that set the step in use
    Index opened = extrinsic ? extrinsic->opened() : 0;
    if (extrinsic)
      ar(*extrinsic);
    else
      ar(opened);
  };
  if (!restart_file.empty()) {
    StateArchive body;
    const std::string mine = checkpoint_piece(restart_file, my_rank);
    DSPDEM_CHECK(my_rank == 0 || fs::exists(mine), "restart: no '{}' beside '{}' for process {} of {}", mine,
                 restart_file, my_rank, n_ranks);
    const CheckpointHeader h = read_checkpoint(mine, body);
    DSPDEM_CHECK(h.processes == n_ranks && h.rank == my_rank,
                 "restart: checkpoint '{}' is process {}'s of a run on {} process(es); restart it on as many ({})",
                 mine, h.rank, h.processes,
                 h.processes > 1 ? fmt::format("mpirun -n {} dspdem run --restart ...", h.processes)
                                 : std::string("without mpirun"));
    // Every process's file of the same step (a crash between two processes' writes would
    // leave them apart).
    const std::vector<long> steps = par::all_gather(h.steps);
    DSPDEM_CHECK(std::all_of(steps.begin(), steps.end(), [&](long n) { return n == steps[0]; }),
                 "restart: the processes' checkpoint files in {} are of different steps ({}): the run was stopped "
                 "while they were written; no restart from these",
                 fs::path(restart_file).parent_path().string(), fmt::join(steps, "/"));
    DSPDEM_CHECK(same_case(h.resolved_toml, c.resolved_toml),
                 "restart: checkpoint '{}' was written for case {} as it was then; it has changed since ({}): run it "
                 "again, or restore the case",
                 restart_file, h.case_path, first_difference(h.resolved_toml, c.resolved_toml));
    // The same case, but read now by the absolute path the checkpoint keeps: the record keeps
    // the path the run was started with.
    head.resolved_toml = h.resolved_toml;
    if (const std::string o = case_origin(h.resolved_toml); !o.empty()) case_file = o;
    DSPDEM_CHECK(h.nodes == whole_nodes && h.elements == whole_elements && h.joints == whole_joints && h.dt == dt,
                 "restart: checkpoint '{}' is of a model with {} nodes, {} elements, {} joints and dt {:.17g}; the "
                 "case gives {}, {}, {} and {:.17g} (its mesh changed?)",
                 restart_file, h.nodes, h.elements, h.joints, h.dt, whole_nodes, whole_elements, whole_joints, dt);
    persist(body);
    DSPDEM_CHECK(body.remaining() == 0, "checkpoint '{}': {} bytes left after the state (corrupt file)", restart_file,
                 body.remaining());
    if (my_rank == 0) restore_outputs(fs::path(restart_file).parent_path(), sdir, ls);
    par::barrier();  // the frames so far in place before anyone adds to them
    if (!distributed) frag = joint::find_fragments(model.mesh, model.joints, elem_mass);
#if DSPDEM_HAVE_MPI
    if (distributed) frag = par::find_fragments(model, *halo, elem_mass, it.x().data()).fr;  // for the summary
#endif
    log::info("  restarted from {} at step {}, t = {:.6g} s ({} frames so far)", restart_file, it.steps(), it.time(),
              ls.frames.size());
  }
  // Once the restart (if any) has said which text ran: the checkpoint's, which keeps the origin.
  if (my_rank == 0) write_file_atomic((sdir / "case.resolved.toml").string(), head.resolved_toml);
  // Every process computes each row (its reductions are collective); process 0 writes it.
  Series series(my_rank == 0 ? (sdir / "series.csv").string() : "/dev/null", model, !restart_file.empty());
  // fragments.csv: per frame the count and the largest pieces (mass, size, where), so that
  // any scene's report can follow the break-up without reading the frames back.
  std::ofstream frag_csv(my_rank == 0 ? sdir / "fragments.csv" : fs::path("/dev/null"),
                         restart_file.empty() ? std::ios::out | std::ios::binary : std::ios::app | std::ios::binary);
  DSPDEM_CHECK(frag_csv.good(), "cannot write '{}'", (sdir / "fragments.csv").string());
  if (restart_file.empty())
    frag_csv << "frame,time,count,rank,id,mass,elements,x,y,z\n";  // id: the frames' fragment field
  constexpr std::size_t kFragmentRows = 20;
  auto& frames = ls.frames;
  auto& joint_frames = ls.joint_frames;
  // The joints' mid-surface displacement where the frames have the nodes' (the renderer's magnify).
  const Real* const joints_x0 =
      std::find(c.fields.begin(), c.fields.end(), "displacement") != c.fields.end() ? fem.x0.data() : nullptr;
  auto write_frame = [&]() {
    // Distributed: the ghosts of the pieces' points at their owners' end-of-step velocities
    // (the step leaves them at mid-step: only own nodes take the last half kick).
    if (distributed) it.refresh_ghosts();
    it.stresses(stress);
    FrameData fd;
    fd.mesh = &model.mesh;
    fd.x = it.x().data();
    fd.x0 = fem.x0.data();
    fd.v = it.v().data();
    fd.stress = stress.data();
    fd.body = fem.elem_body.data();
    fd.element_tag = fem.elem_tag.data();
    std::vector<joint::FragmentInfo> info;
    if (distributed) {
      fd.cell_owned = model.elem_owned.data();
      fd.piece = my_rank, fd.pieces = n_ranks;
#if DSPDEM_HAVE_MPI
      par::DistributedFragments df = par::find_fragments(model, *halo, elem_mass, it.x().data());
      frag = std::move(df.fr);
      info = std::move(df.info);
#endif
    } else {
      frag = joint::find_fragments(model.mesh, model.joints, elem_mass);
      info = joint::describe_fragments(model.mesh, frag, it.x().data(), elem_mass);
    }
    fd.fragment = frag.id.data();
    {
      for (std::size_t k = 0; k < std::min(kFragmentRows, info.size()); ++k)
        frag_csv << fmt::format("{},{:.10g},{},{},{},{:.10g},{},{:.8g},{:.8g},{:.8g}\n", frames.size(), it.time(),
                                frag.count, k + 1, info[k].id, info[k].mass, info[k].elements, info[k].centroid(0),
                                info[k].centroid(1), info[k].centroid(2));
      frag_csv.flush();
    }
    fd.material = fem.elem_material.data();
    fd.fields = c.fields;
    fd.compress = c.compress;
    for (const auto& w : model.contact.walls())
      fd.wall_pose.insert(fd.wall_pose.end(),
                          {w.centre(0), w.centre(1), w.centre(2), w.q.w(), w.q.x(), w.q.y(), w.q.z()});
    const char* ext = distributed ? "pvtu" : "vtu";  // a distributed frame: its pieces, listed in a .pvtu
    const std::string name = fmt::format("frame_{:04d}.{}", frames.size(), ext);
    write_vtu((fs::path(frames_dir) / name).string(), fd);
    frames.emplace_back(it.time(), "frames/" + name);
    if (my_rank == 0) write_pvd(pvd, frames);
    if (whole_joints > 0) {
      const std::string jname = fmt::format("joints_{:04d}.{}", joint_frames.size(), ext);
      write_joints_vtu((fs::path(frames_dir) / jname).string(), model.joints, it.x().data(), joints_x0, c.compress,
                       model.joint_owned, my_rank, n_ranks);
      joint_frames.emplace_back(it.time(), "frames/" + jname);
      if (my_rank == 0) write_pvd(joints_pvd, joint_frames);
    }
  };
  // What the CRCs of series.csv and fragments.csv are known to cover: the restored prefix's
  // (restore_outputs checked it), then the last checkpoint's. Each checkpoint reads what the
  // files grew by since, not the whole of a long run's series; a read that came short (the
  // file not as long as written) is not carried on, and the next reads from the start.
  FileCrc series_known{ls.series_crc, ls.series_bytes}, fragments_known{ls.fragments_crc, ls.fragments_bytes};
  auto carried_crc = [](const fs::path& file, std::uint64_t bytes, FileCrc& known) {
    const FileCrc got = file_crc(file.string(), bytes, known);
    known = got.bytes == bytes ? got : FileCrc{};
    return got.crc;
  };
  auto write_ckpt = [&]() {
    ls.series_bytes = series.bytes();
    frag_csv.flush();
    ls.fragments_bytes = static_cast<std::uint64_t>(frag_csv.tellp());
    if (my_rank == 0) {
      ls.series_crc = carried_crc(sdir / "series.csv", ls.series_bytes, series_known);
      ls.fragments_crc = carried_crc(sdir / "fragments.csv", ls.fragments_bytes, fragments_known);
    }
    const double before = ls.wall_before;
    ls.wall_before += wall.seconds();
    StateArchive body;
    persist(body);
    ls.wall_before = before;
    head.steps = it.steps(), head.time = it.time();
    write_checkpoint(ckpt, head, body, !distributed);
    if (distributed) {
      par::barrier();  // every process's new file on disk before any replaces its old one
      move_checkpoint_into_place(ckpt);
    }
  };

  auto write_summary = [&](const std::string& dir, const std::string& status, const std::string& message) {
    const Energy e = it.energy();  // on every process: its sums are collective
    if (my_rank != 0) return;
    RunSummary s;
    s.case_name = c.name, s.case_file = case_file, s.status = status, s.message = message;
    s.build = executable_id();
    s.steps = it.steps(), s.dt = it.dt(), s.dt_start = dt, s.dt_critical = crit.dt, s.dt_limiter = crit.limiter;
    s.dt_limiting_element = static_cast<long>(crit.element >= 0 ? fem.elem_tag[crit.element] : 0);
    s.t_end = it.time(), s.wall_s = ls.wall_before + wall.seconds(), s.threads = omp_get_max_threads();
    s.processes = n_ranks;
    s.nodes = whole_nodes, s.elements = whole_elements, s.frames = static_cast<long>(frames.size());
    s.joints = whole_joints, s.joint_added_compliance = joint_compliance;
    s.broken_joints = e.broken_joints, s.crack_area = e.crack_area;
    s.monitor_joints = monitor_joints;
    s.fragments = frag.count;
    for (Real mm : frag.mass) s.total_mass += mm;
    for (std::size_t i = 0; i < std::min<std::size_t>(10, frag.mass.size()); ++i)
      s.largest_fragment_masses.push_back(frag.mass[i]);
    s.element_steps_per_s = s.wall_s > 0 ? static_cast<double>(it.steps()) * whole_elements / s.wall_s : 0.0;
    s.energy = {e.kinetic,         e.internal,   e.external_work,  e.damping,         e.initial,
                e.joint_elastic,   e.fracture_I, e.fracture_II,    e.contact_elastic, e.friction,
                e.contact_damping, e.kick,       e.balance_error()};
    if (model.contact.enabled()) {
      const contact::ContactTotals ct = model.contact.totals();
      auto born = [](const contact::BornOverlaps& b) {
        return BornOverlapSummary{static_cast<long>(b.pairs), b.energy, b.max_ratio};
      };
      s.born_split = born(ct.born.split), s.born_unseen = born(ct.born.unseen), s.born_wall = born(ct.born.wall);
    }
    write_run_summary((fs::path(dir) / "summary.json").string(), s);
  };

  // Again before the loop: the set-up's libraries (gmsh) may have put in their own.
  signals.install();
  const bool tty_progress = opt.progress;
  std::function<Real()> stop_value;
  if (!c.stop_series.empty()) stop_value = series_column(c, model, it);
  const long s0 = it.steps();  // 0, or where a restart begins
  try {
    if (restart_file.empty()) {
      write_frame();
      series.row(it, model);
    }
    Timer loop;
    double last_report = 0, next_wall_checkpoint = opt.checkpoint_wall;
    for (long s = s0; s < ls.n_steps; ++s) {
      it.step();
      if (extrinsic && insert_joints(*extrinsic, it)) ls.n_steps = last_step(s + 1, it.time(), it.dt());
      bool last = s + 1 == ls.n_steps;
      const Real t = it.time();
      if (t >= ls.next_series - 1e-12 * c.t_end || last) {
        const Energy e = it.check_energy(c.energy_blowup_factor);
        if (stop_value && ls.stop_at < 0) {
          const Real v = stop_value();
          if (stop_rule.update(v))
            ls.stop_message = fmt::format("|{}| fell below {} of its peak {:.6g} at t = {:.6g} s; stopped at ",
                                          c.stop_series, c.stop_fraction, stop_rule.peak(), t);
          else if (c.stop_reach > 0 && std::abs(v) >= c.stop_reach)
            ls.stop_message = fmt::format("|{}| reached {:.6g} ({:.6g}) at t = {:.6g} s; stopped at ", c.stop_series,
                                          c.stop_reach, v, t);
          if (!ls.stop_message.empty()) ls.stop_at = t + c.stop_delay;
        }
        if (ls.stop_at >= 0 && t >= ls.stop_at - 1e-12 * c.t_end && !last) {
          last = true;  // this row and a last frame, then stop
          ls.stop_message += fmt::format("t = {:.6g} s", t);
          log::info("  {}", ls.stop_message);
        }
        // After the stop rule, which may make this row the last.
        if (auto w = balance_watch.update(e, it.steps(), t, last)) log::warn("{}", *w);
        series.row(it, model);
        ls.next_series = next_output_time(ls.next_series, t, c.series_interval, 1e-12 * c.t_end);
      }
      if (t >= ls.next_frame - 1e-12 * c.t_end || last) {
        write_frame();
        ls.next_frame = next_output_time(ls.next_frame, t, c.frame_interval, 1e-12 * c.t_end);
      }
      if (last) break;
      if (it.steps() == opt.interrupt_at_step) g_interrupted = 1;
      // Distributed: a signal reaches the processes at different steps; all stop after the
      // step whose reduction first carried it (Integrator::watch_flag). g_interrupted stays
      // this process's own: its signal may still come, and must not count as a second one.
      const bool stop = distributed ? it.flag_anywhere() : g_interrupted != 0;
      if (stop) {
        write_ckpt();
        write_summary(stage.path(), "interrupted", fmt::format("interrupted at step {}, t = {:.6g} s", it.steps(), t));
        par::barrier();  // every process's file written before process 0 moves the folder
        const std::string kept = stage.keep_as(interrupted_folder);
        // mpirun ends the job as soon as one process exits non-zero: none leaves (nor loses
        // its signal handler, to a late signal) before process 0 has moved the folder.
        par::barrier();
        throw Interrupted(fmt::format("interrupted at step {}, t = {:.6g} s; outputs so far and a checkpoint in {}; "
                                      "continue with: dspdem run --restart {}",
                                      it.steps(), t, kept, opt.out_dir),
                          it.steps(), t);
      }
      if (opt.checkpoint_every > 0 && t >= ls.next_checkpoint - 1e-12 * c.t_end) {
        ls.next_checkpoint = next_output_time(ls.next_checkpoint, t, opt.checkpoint_every, 1e-12 * c.t_end);
        write_ckpt();
        next_wall_checkpoint = loop.seconds() + opt.checkpoint_wall;
      } else if (opt.checkpoint_wall > 0 && !distributed && loop.seconds() >= next_wall_checkpoint) {
        write_ckpt();  // reads the state only: the run's results are the same with or without
        next_wall_checkpoint = loop.seconds() + opt.checkpoint_wall;
      }
      if (tty_progress && loop.seconds() - last_report > 0.5) {
        last_report = loop.seconds();
        const double rate = static_cast<double>(s + 1 - s0) / last_report;
        fmt::print(stderr, "\r  step {}/{}  t = {:.4g} s  {:.0f} steps/s  ETA {}   ", s + 1, ls.n_steps, t, rate,
                   format_duration(static_cast<double>(ls.n_steps - s - 1) / rate));
      }
    }
    if (tty_progress) fmt::print(stderr, "\n");
  } catch (const Interrupted&) {
    if (tty_progress) fmt::print(stderr, "\n");
    throw;
  } catch (const NumericalError& e) {
    if (tty_progress) fmt::print(stderr, "\n");
    // Distributed: the failure may be this process's alone (its node, its element), so no
    // collective call and no folder moved; main ends every process. The frames written so far
    // stay in the staging folder.
    if (distributed)
      throw NumericalError(
          fmt::format("{} (process {} of {}; frames so far in {})", e.what(), my_rank, n_ranks, stage.path()), e.step,
          e.time);
    write_summary(stage.path(), "failed", e.what());
    write_pvd(pvd, frames);
    const std::string kept = stage.keep_failed();
    throw NumericalError(fmt::format("{}\n  partial results (frames up to the failure) kept in {}", e.what(), kept),
                         e.step, e.time);
  }
  if (extrinsic)
    log::info("  extrinsic insertion: {} joint(s) opened, {} of them to free a crack front{}", extrinsic->opened(),
              extrinsic->forced(),
              adaptive_dt ? fmt::format("; the step fell from {:.4g} s to {:.4g} s (critical {:.4g} s, limited by {})",
                                        dt, it.dt(), crit.dt, limiter_text(crit))
                          : std::string());
  if (distributed && model.contact.enabled()) {
    // How the contact work fell on the processes (the partition is the elements', made once).
    const contact::ContactSystem::ShareLoad l = model.contact.share_load();
    log::info(
        "  contact per process at the last rebuild: pairs evaluated {}, counted {}; elements lent {} ({} nodes); "
        "most elements lent at a rebuild {}",
        fmt::join(par::all_gather(l.evaluated), "/"), fmt::join(par::all_gather(l.counted), "/"),
        fmt::join(par::all_gather(l.lent_elements), "/"), fmt::join(par::all_gather(l.lent_nodes), "/"),
        fmt::join(par::all_gather(l.most_lent), "/"));
  }
  write_summary(stage.path(), "completed", ls.stop_message);
  const Energy e = it.energy();  // collective: before the other processes return
  fs::remove(ckpt);              // a finished run needs none (each process its own file)
  par::barrier();                // every piece written before process 0 moves the folder into place
  if (my_rank != 0) return 0;
  const bool replaces =
      fs::exists(fs::path(opt.out_dir) / "run.pvd") || fs::exists(fs::path(opt.out_dir) / "summary.json");
  stage.commit();
  // Images drawn from the frames this run has replaced would sit beside its results as if
  // they were its own (a frame_0040.png of t = 100 ms beside a run of 5 ms): they go with the
  // frames they were drawn from; `dspdem render` draws this run's. Only where a run was
  // replaced: a first run into a folder leaves an images/ it did not make alone.
  if (replaces) {
    // The results are in place: what fails from here on is warned of, and the run ends well.
    ReplacedImages images;
    try {
      images = remove_replaced_images(opt.out_dir);
    } catch (const std::exception& e) {
      log::warn("{}: the images of the run this one replaced may be left beside its results: {}", opt.out_dir,
                e.what());
    }
    switch (images.fate) {
      case ReplacedImages::Fate::none:
        break;
      case ReplacedImages::Fate::removed:
        log::info("  the images of the run this one replaced were removed (dspdem render {} draws its own)",
                  opt.out_dir);
        break;
      case ReplacedImages::Fate::render_drawing:
        log::warn(
            "{}: a render started during this run is drawing the run it replaced: its images were not removed and "
            "may mix both runs; draw this one again once it ends (dspdem render {})",
            opt.out_dir, opt.out_dir);
        break;
      case ReplacedImages::Fate::holds_inside:
        log::warn(
            "{}: the images of the run this one replaced were kept, since {} inside them holds a run, a report or a "
            "render drawing now, which removing them would take too; they are not this run's (draw this one with "
            "dspdem render {} --out OTHER)",
            opt.out_dir, images.inside, opt.out_dir);
        break;
      case ReplacedImages::Fate::not_drawn:
        log::warn(
            "{}: its images/ was kept, since it holds {}, which dspdem render does not write; its frames are not this "
            "run's (draw this one with dspdem render {} --out OTHER)",
            opt.out_dir, images.inside, opt.out_dir);
        break;
    }
  }
  // The folder a restart came from (an interrupted run, or the staging folder of a killed
  // one) is superseded by these results.
  if (!restart_file.empty()) {
    const fs::path src = fs::path(restart_file).parent_path();
    std::error_code ec;
    if (is_side_folder(src.string())) fs::remove_all(src, ec);
    if (ec) log::warn("{}: the folder the run restarted from was not removed: {}", src.string(), ec.message());
  }
  log::info("  {} steps to t = {:.6g} s in {:.2f} s ({:.3g} element-steps/s, {} threads); energy balance error {:.2e}",
            it.steps(), it.time(), wall.seconds(),
            static_cast<double>(it.steps() - s0) * whole_elements / wall.seconds(), omp_get_max_threads(),
            e.balance_error());
  log::info("  results in {}/ (run.pvd, {} frames, series.csv, summary.json)", opt.out_dir, frames.size());
  return 0;
}

}  // namespace dspdem
