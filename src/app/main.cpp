// dspdem: batch command-line front end. Thin: all work is in the libraries.
#include <unistd.h>

#include <CLI/CLI.hpp>
#ifdef _OPENMP
#include <omp.h>
#endif
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <exception>
#include <filesystem>

#include "app/figures_command.hpp"
#include "app/mesh_command.hpp"
#include "app/report_command.hpp"
#include "core/error.hpp"
#include "core/log.hpp"
#include "core/subprocess.hpp"
#include "io/case_config.hpp"
#include "meshing/generator.hpp"
#include "par/mpi_world.hpp"
#include "render/image_compare.hpp"
#include "run/checkpoint.hpp"
#include "run/montage.hpp"
#include "run/render_args.hpp"
#include "run/render_run.hpp"
#include "run/run_case.hpp"
#include "scenes/registry.hpp"

using namespace dspdem;

namespace {
// CLI11's number checks let NaN through (every comparison with it is false); these do not.
CLI::Validator number_check(const std::string& name, bool (*ok)(double), const std::string& what) {
  return CLI::Validator(
      [ok, what](std::string& v) {
        const double x = std::strtod(v.c_str(), nullptr);
        return std::isfinite(x) && ok(x) ? std::string() : "must be " + what + ", got " + v;
      },
      name);
}
const CLI::Validator kFiniteNonNegative = number_check(
    "NONNEGATIVE", [](double x) { return x >= 0; }, "a finite number >= 0");
const CLI::Validator kFinitePositive = number_check(
    "POSITIVE", [](double x) { return x > 0; }, "a finite number > 0");
// Speeds given as comma lists, once or repeated: every entry a finite number > 0, none empty.
std::vector<double> speed_list(const std::vector<std::string>& texts, const std::string& option) {
  std::vector<double> out;
  for (const auto& text : texts) {
    std::size_t from = 0;
    while (true) {
      const std::size_t comma = std::min(text.find(',', from), text.size());
      const std::string entry = text.substr(from, comma - from);
      double v = 0;
      DSPDEM_CHECK(whole_number(entry, v) && std::isfinite(v) && v > 0,
                   "{} {}: '{}' is not a speed (a finite number > 0, in m/s)", option, text, entry);
      out.push_back(v);
      if (comma == text.size()) break;
      from = comma + 1;
    }
  }
  return out;
}

// An empty --out would mean the default folder, not the one the user meant to name.
const CLI::Validator kNotEmpty(
    [](std::string& v) { return v.empty() ? std::string("must name a path, got an empty text") : std::string(); },
    "PATH");

const CLI::Validator kFraction = number_check(
    "FRACTION", [](double x) { return x >= 0 && x <= 1; }, "a number in [0, 1]");

int run_main(int argc, char** argv) {
  CLI::App app{"dspdem: deformable spheropolyhedral DEM with cohesive joints (batch, off-screen)"};
  app.require_subcommand(1);
  bool quiet = false, verbose = false;
  app.add_flag("-q,--quiet", quiet, "Only warnings and errors");
  app.add_flag("-v,--verbose", verbose, "Debug output (includes gmsh's log)");
  int threads = 0;
  app.add_option("-t,--threads", threads,
                 "Solver threads (default: OMP_NUM_THREADS, else all cores). Results do not depend on it; "
                 "use 1 per job when several jobs share a machine")
      ->check(CLI::Range(0, 4096));

  auto* run = app.add_subcommand("run", "Run a case: writes run.pvd, frames/, series.csv, summary.json into --out");
  std::string case_file, out_dir;
  std::vector<std::string> sets;
  bool progress = false, no_progress = false;
  std::string restart_path;
  double checkpoint_every = 0;
  double checkpoint_wall = kCheckpointWallDefault;
  auto* run_case_opt = run->add_option("case", case_file, "Case file (TOML); none with --restart");
  run->add_option("-o,--out", out_dir, "Output directory (default: results/<case name>)")->check(kNotEmpty);
  auto* run_set_opt =
      run->add_option("--set", sets, "Override a case key: section.key=value (repeatable; value in TOML syntax)");
  auto* restart_opt =
      run->add_option("--restart", restart_path,
                      "Continue the run whose output folder is RUN_DIR from its newest checkpoint, or from the "
                      "checkpoint file given, with the case and --set it was started with (outputs: the run's folder "
                      "unless --out)");
  restart_opt->excludes(run_case_opt)->excludes(run_set_opt)->type_name("RUN_DIR|CHECKPOINT");
  auto* ckpt_opt =
      run->add_option("--checkpoint-every", checkpoint_every,
                      "Write DIR/checkpoint.bin every T of simulated time (atomically, over the last one); "
                      "SIGINT/SIGTERM/SIGHUP write one anyway. Default with --restart: the interrupted run's")
          ->check(kFiniteNonNegative)
          ->type_name("T");
  auto* wall_opt =
      run->add_option("--checkpoint-wall", checkpoint_wall,
                      "Also write one every S seconds of wall time, so that a run killed outright (SIGKILL, out of "
                      "memory) loses at most that much: run --restart DIR goes on from it. One process only; 0: "
                      "never. Default with --restart: the interrupted run's")
          ->capture_default_str()
          ->check(kFiniteNonNegative)
          ->type_name("S");
  run->add_flag("--progress", progress, "Show a progress line (default: on when stderr is a terminal and CI is unset)");
  run->add_flag("--no-progress", no_progress, "Never show the progress line");
  bool estimate = false;
  run->add_flag("--estimate", estimate,
                "Set the case up (mesh, model, step), time its first steps for a few seconds in memory and print "
                "the steps, frames and wall time the run would take; nothing is written")
      ->excludes(restart_opt);
  bool discard_interrupted = false;
  run->add_flag("--discard-interrupted", discard_interrupted,
                "Start afresh in an output folder that holds the checkpoint of a run that was stopped or killed "
                "(this run replaces it when it finishes or is itself stopped); without it such a run is refused, so "
                "that the checkpoint is not lost by mistake");

  auto* mesh = app.add_subcommand("mesh", "Mesh a case: writes DIR/<case>.msh and DIR/quality.json");
  std::string mesh_case_file, mesh_out;
  std::vector<std::string> mesh_sets;
  mesh->add_option("case", mesh_case_file, "Case file (TOML)")->required();
  mesh->add_option("-o,--out", mesh_out, "Output directory (default: results/<case name>/mesh)")->check(kNotEmpty);
  mesh->add_option("--set", mesh_sets, "Override a case key: section.key=value (repeatable)");

  auto* rend = app.add_subcommand(
      "render", "Draw a run's frames off-screen: DIR/images/<view>/frame_NNNN.png, animations, plots");
  RenderArgs ra;
  MontageArgs ma;
  std::vector<std::string> render_dirs;
  rend->add_option("run_dir", render_dirs, "Output folder of a run (holds run.pvd); several with --montage")
      ->required()
      ->expected(1, -1);
  rend->add_option("--montage", ma.out,
                   "Write one PNG image OUT of the given runs side by side (a column per run, a row per --rows "
                   "entry) at --time; .png is added to a name that does not end in it")
      ->check(kNotEmpty);
  rend->add_option("--time", ma.time, "--montage: simulated time of the frames [s] (default: each run's last frame)")
      ->check(kFiniteNonNegative);  // a negative one read as "the last frame", an infinite one as the first
  rend->add_option("--label", ma.labels,
                   "Text in the corner in place of the case's name; with --montage a label per run, in order "
                   "(default: the folders' names)");
  rend->add_option("--rows", ma.rows,
                   "--montage: rows as view or view:cut, e.g. fragments:z fragments cracks (default: fragments)")
      ->delimiter(',');
  rend->add_option("--view", ra.views, "View: stress, fragments, cracks (repeatable; default from the case)");
  rend->add_option("--field", ra.field, "Field of the stress view");
  rend->add_option("--frames", ra.frames, "all (default), last, every:K, or indices i,j,k");
  rend->add_option("--camera", ra.camera, "front, back, top, side, iso");
  rend->add_option("--cut", ra.cut, "none, x, y, z: cut at the mid-plane");
  rend->add_option("--magnify", ra.magnify, "Displacement magnification (default: the case's)")->check(kFinitePositive);
  rend->add_option("--range", ra.range, "Colour range MIN:MAX");
  rend->add_option("--size", ra.size, "Image size WIDTHxHEIGHT (with --montage: of one panel)");
  rend->add_option("-j,--jobs", ra.jobs,
                   "Render processes, then views whose animations are encoded at once (default: -t's count, else "
                   "OMP_NUM_THREADS, else one per core)")
      ->check(CLI::Range(1, 256));  // as report's -j
  rend->add_option("--out", ra.out_dir,
                   "Write OUT/images/ instead of the run's images/ (the run's folder is then only read)")
      ->check(kNotEmpty);
  rend->add_flag("--no-animation", ra.no_animation, "Skip the animations");
  rend->add_flag("--edges", ra.edges, "Draw the element edges (stress and fragments views)");
  rend->add_option("--worker", ra.worker, "internal: render a share of the frames")->group("");

  auto* rep = app.add_subcommand(
      "report",
      "Run a benchmark scene's case and write DIR/report.md with its figures against the reference (--study: speed "
      "against error); `dspdem scenes` lists the scenes");
  auto* scn = app.add_subcommand("scenes", "List the benchmark scenes dspdem report knows ([case] scene = \"...\")");
  report::ReportArgs rpa;
  rep->add_option("case", rpa.case_file, "Case file (TOML)")->required();
  rep->add_option("-o,--out", rpa.out_dir, "Output directory (default: results/<case name>_report)")->check(kNotEmpty);
  rep->add_option("--set", rpa.sets, "Override a case key: section.key=value (repeatable)");
  rep->add_flag("--study", rpa.study, "Also run the sweep over mesh sizes and accuracy knobs");
  rep->add_flag("--no-render", rpa.no_render, "Skip the frame images and animations");
  rep->add_option("--from-run", rpa.from_runs,
                  "Analyse this finished run of the case instead of running it again; for a velocity sweep, an earlier "
                  "report's folder, repeatable to merge several reports' runs of the same case (each run taken from "
                  "the first folder that has it)")
      ->allow_extra_args(false);
  // Read as text and split here: CLI11's delimiter drops an empty entry ("5,,7" ran two speeds).
  std::vector<std::string> speeds_text, study_speeds_text;
  rep->add_option("--speeds", speeds_text,
                  "Impact speeds of a scene's velocity sweep [m/s] (the sphere impact), comma-separated");
  rep->add_option("--study-speeds", study_speeds_text,
                  "Impact speeds of the sphere impact's study [m/s] (default 7.5,20; each costs a mesh x2 and x4 run)");
  rep->add_option("--realisations", rpa.realisations,
                  "Runs per speed of a velocity sweep, the first the case itself, the others with the mesh turned "
                  "another way (mesh.<generator>.orientation): how often each speed gives the pattern")
      ->check(CLI::Range(1, 100));
  rep->add_option("--draws", rpa.draws,
                  "Runs of each speed on each mesh of a velocity sweep, the first the run itself, the others with "
                  "the impact speed nudged by 1e-5 m/s per draw: how much of the pattern is chance on one mesh and "
                  "how much the mesh's")
      ->check(CLI::Range(1, 100));
  rep->add_option("-j,--jobs", rpa.jobs,
                  "Runs of a sweep or study at once, each a process with -t 1 (default: one per core)")
      ->check(CLI::Range(1, 256));
  rep->add_flag("--resume", rpa.runs.resume,
                "Keep the runs (the report's run, its study, a sweep) an earlier report left in the output folder "
                "when they are the same runs (same resolved case, same dspdem build); continue interrupted or killed "
                "ones from their checkpoints; run the rest");
  rep->add_option("--checkpoint-wall", rpa.runs.checkpoint_wall,
                  "Each run's checkpoints by wall time, as run --checkpoint-wall: a run killed outright goes on from "
                  "its last with --resume. 0: never")
      ->capture_default_str()
      ->check(kFiniteNonNegative)
      ->type_name("S");
  rep->add_flag("--no-stress-check", rpa.no_stress_check,
                "Skip the stress check (sigma along the diameter, elastic, on a mesh that resolves the loads)");

  auto* fig = app.add_subcommand(
      "figures",
      "Every scene's report and one static site over them: DIR/index.html (and index.md) with each scene's headline "
      "figures against the paper, thumbnails linking to its report page, its animation");
  FiguresArgs fga;
  fig->add_option("cases", fga.cases, "Case files, one per scene (default: every scene's shipped case)");
  fig->add_option("-o,--out", fga.out, "Output directory of the site (default: results/figures)")->check(kNotEmpty);
  fig->add_flag("--quick", fga.quick, "CI-sized meshes and runs, no studies (the whole set in minutes on 2 cores)");
  bool fig_no_study = false;
  fig->add_flag("--no-study", fig_no_study, "Full set without the speed-against-error studies (hours less)");
  fig->add_option("--from-runs", fga.from_runs,
                  "Reuse the report folders FROM/<scene> made earlier (by figures or by report --out); run nothing")
      ->check(CLI::ExistingDirectory)
      ->type_name("FROM");
  fig->add_flag("--resume", fga.resume,
                "Each report with --resume: the runs a stopped figures (or report --out DIR/<scene>) left are kept "
                "when finished, continued from their checkpoints when stopped or killed");
  fig->add_option("--checkpoint-wall", fga.checkpoint_wall, "Each report with --checkpoint-wall S")
      ->check(kFiniteNonNegative)
      ->type_name("S");

  auto* imgdiff =
      app.add_subcommand("imgdiff", "Compare two PNG images; exit 1 when they differ by more than the threshold");
  std::string img_a, img_b, img_diff;
  double img_threshold = 0.002;
  int img_tol = 16;
  imgdiff->add_option("a", img_a, "First image")->required();
  imgdiff->add_option("b", img_b, "Second image (e.g. the baseline)")->required();
  imgdiff
      ->add_option("--threshold", img_threshold,
                   "Largest accepted fraction of changed pixels (after a one-pixel shift and the channel tolerance)")
      ->check(kFraction);
  imgdiff->add_option("--tolerance", img_tol, "Per-channel difference ignored (0-255)")->check(CLI::Range(0, 255));
  imgdiff->add_option("--diff", img_diff, "Where to write the difference image (default: <a>.diff.png)");

  auto* keys =
      app.add_subcommand("keys", "Print every case-file key (type, default, range, unit, meaning) as Markdown");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // A misspelt command reads to CLI11 as a stray argument and a missing command; say what it is.
    if (app.get_subcommands().empty() && !app.remaining().empty() && app.remaining().front()[0] != '-') {
      std::vector<std::string> names;
      for (const CLI::App* sub : app.get_subcommands({})) names.push_back(sub->get_name());
      fmt::print(stderr, "error: unknown command '{}'; the commands are {}\nRun with --help for more information.\n",
                 app.remaining().front(), fmt::join(names, ", "));
      return 1;
    }
    const int code = app.exit(e);  // prints help or the message
    // README: 1 is a command-line error, whatever CLI11 calls it; but imgdiff's 1 is "the
    // images differ", which a script must tell from a mistyped option: 2 there.
    return code == 0 ? 0 : *imgdiff ? 2 : 1;
  }
  log::set_level(quiet ? log::Level::Quiet : verbose ? log::Level::Debug : log::Level::Info);
  if (par::rank() > 0) log::set_level(log::Level::Quiet), log::set_warnings(false);  // one log: process 0's
#ifdef _OPENMP
  if (threads > 0) omp_set_num_threads(threads);
#endif

  try {
    DSPDEM_CHECK(par::size() == 1 || *run,
                 "only `dspdem run` runs on several processes (mpirun -n {}); give the others "
                 "one process",
                 par::size());
    if (*keys) {
      fmt::print("{}", case_schema_markdown());
      return 0;
    }
    if (*rend) {
      if (!ma.out.empty()) {
        DSPDEM_CHECK(ra.out_dir.empty(), "render: --out and --montage: the montage is written to --montage's file");
        ma.run_dirs = render_dirs;
        ma.camera = ra.camera, ma.field = ra.field, ma.range = ra.range;
        if (!ra.size.empty()) parse_image_size(ra.size, "--size", ma.width, ma.height);
        write_montage(ma);
        return 0;
      }
      DSPDEM_CHECK(render_dirs.size() == 1,
                   "render: {} run folders given; several are drawn together only with --montage OUT.png",
                   render_dirs.size());
      DSPDEM_CHECK(ma.time < 0, "render: --time goes with --montage");
      DSPDEM_CHECK(ma.labels.size() <= 1, "render: {} labels for one run folder (several go with --montage)",
                   ma.labels.size());
      if (!ma.labels.empty()) ra.label = ma.labels.front();
      ra.run_dir = render_dirs[0];
      return render_command(ra);
    }
    if (*rep) {
      rpa.speeds = speed_list(speeds_text, "--speeds");
      rpa.study_speeds = speed_list(study_speeds_text, "--study-speeds");
      return report_command(rpa);
    }
    if (*fig) {
      fga.threads = threads;
      fga.study = !fig_no_study;
      return figures_command(fga);
    }
    if (*scn) {
      for (const auto& sc : scenes::all())
        fmt::print("{:<16} {} (cases with mesh generator '{}' by default)\n", sc.name, sc.title, sc.generator);
      return 0;
    }
    if (*imgdiff) {
      const std::string diff = img_diff.empty() ? img_a.substr(0, img_a.rfind('.')) + ".diff.png" : img_diff;
      const render::ImageDiff d = render::compare_png(img_a, img_b, diff, img_tol);
      const bool pass = d.changed_fraction <= img_threshold;
      fmt::print(
          "{}: {:.4f} % of pixels changed (threshold {:.4f} %; VTK thresholded error {:.4g}), {}x{}; difference "
          "image {}\n",
          pass ? "same" : "DIFFERENT", 100 * d.changed_fraction, 100 * img_threshold, d.vtk_error, d.width, d.height,
          diff);
      return pass ? 0 : 1;
    }
    if (*mesh) {
      const CaseConfig c = read_case(mesh_case_file, mesh_sets);
      return mesh_command(c,
                          mesh_out.empty() ? (std::filesystem::path("results") / c.name / "mesh").string() : mesh_out);
    }
    if (*run) {
      if (case_file.empty() && restart_path.empty()) {  // a command-line error (exit 1), as CLI11's own
        fmt::print(stderr,
                   "error: run: give a case file, or --restart RUN_DIR\nRun with --help for more information.\n");
        return 1;
      }
      RunOptions opt;
      opt.checkpoint_every = checkpoint_every;
      opt.checkpoint_wall = checkpoint_wall;
      if (!restart_path.empty()) {
        // The case and overrides come from the checkpoint; run_case checks that the case
        // still reads as it did then.
        const FoundCheckpoint f = restart_checkpoint(restart_path);
        const CheckpointHeader& h = f.header;
        require_this_build(h, f.path);
        opt.restart_file = f.path;
        case_file = h.case_path, sets = h.sets;
        if (ckpt_opt->count() == 0) opt.checkpoint_every = h.checkpoint_every;
        if (wall_opt->count() == 0) opt.checkpoint_wall = h.checkpoint_wall;
        // The folder the checkpoint belongs to, also when RUN_DIR is given as DIR/interrupted_run
        // (which a finished run removes).
        if (out_dir.empty()) out_dir = run_folder_of(f.path);
        log::info("dspdem run --restart: {} (step {}, t = {:.6g} s)", opt.restart_file, h.steps, h.time);
      }
      if (par::size() > 1 && wall_opt->count() > 0 && checkpoint_wall > 0)
        log::warn(
            "--checkpoint-wall {} is not used in a distributed run (mpirun -n {}): its processes would not agree on "
            "the step; --checkpoint-every T writes checkpoints by simulated time",
            checkpoint_wall, par::size());
      DSPDEM_CHECK(!estimate || par::size() == 1,
                   "run --estimate: the case is set up and timed on one process (without mpirun)");
      const CaseConfig c = read_case(case_file, sets);
      // A misspelt scene would surface only at the report, after the run's hours.
      if (!c.scene.empty()) (void)scenes::of_case(c);
      opt.sets = sets;
      opt.out_dir = out_dir.empty() ? (std::filesystem::path("results") / c.name).string() : out_dir;
      // A finished run supersedes an interrupted or killed one in its folder, checkpoint and all
      // (Staging::commit): the same command given again instead of --restart would lose hours of
      // a long run. Continuing into the folder the checkpoint belongs to is what --restart is for.
      namespace fs = std::filesystem;
      const std::vector<std::string> left = checkpoints_left(opt.out_dir);
      const bool continuing = !restart_path.empty() && fs::weakly_canonical(run_folder_of(opt.restart_file)) ==
                                                           fs::weakly_canonical(opt.out_dir);
      opt.estimate = estimate;
      DSPDEM_CHECK(left.empty() || continuing || discard_interrupted || estimate,
                   "run: {} holds the checkpoint of a run that was stopped or killed ({}): continue it with `dspdem "
                   "run --restart {}`, or start afresh with --discard-interrupted",
                   opt.out_dir, fmt::join(left, ", "), opt.out_dir);
      const bool in_ci = std::getenv("CI") != nullptr;
      opt.progress = !no_progress && (progress || (isatty(STDERR_FILENO) && !in_ci && !quiet)) && par::rank() == 0;
      return run_case(c, opt);
    }
  } catch (const Interrupted& e) {
    if (par::rank() == 0) fmt::print(stderr, "stopped by a signal: {}\n", e.what());
    return kExitInterrupted;
  } catch (const NumericalError& e) {
    fmt::print(stderr, "error: numerical failure: {}\n", log::printable(e.what()));
    return 3;
  } catch (const Error& e) {
    fmt::print(stderr, "error: {}\n", log::printable(e.what()));
    return 2;
  } catch (const std::exception& e) {
    fmt::print(stderr, "error: unexpected failure: {}\n", log::printable(e.what()));
    return 4;
  } catch (const std::string& e) {  // the gmsh API throws its messages as strings
    fmt::print(stderr, "error: gmsh: {}\n", log::printable(e));
    return 2;
  }
  return 0;
}
}  // namespace

namespace {
std::terminate_handler g_previous_terminate = nullptr;

// gmsh throws some of its errors (a mesh size far too small: "Identical points in
// triangulation") as strings inside its own OpenMP regions, which no handler can catch: the
// runtime calls std::terminate, and the run would end in an abort and a core dump with no
// word of what failed. Those are said here as an error, with the mesh being made, and the
// exit code of run_main's own gmsh errors; anything else is a bug and goes on to the
// previous handler (the message with the exception's type, and the abort).
[[noreturn]] void on_terminate() {
  if (const std::exception_ptr e = std::current_exception()) {
    try {
      std::rethrow_exception(e);
    } catch (const std::string& s) {
      const std::string what = meshing::meshing_now();
      fmt::print(stderr, "error: gmsh: {}{}\n", s, what.empty() ? "" : " (while meshing: " + what + ")");
      std::_Exit(2);
    } catch (...) {
    }
  }
  if (g_previous_terminate) g_previous_terminate();
  std::abort();
}
}  // namespace

// Under mpirun each process runs the same command on its share (par/); a failure on one ends
// them all, since the others would wait for it at the next exchange. An interruption is
// agreed by all at the same step (run_case), so they end together and normally.
int main(int argc, char** argv) {
  g_previous_terminate = std::set_terminate(on_terminate);
  stop_with_parent();  // a sweep's job: a SIGTERM if the report dies, even by SIGKILL
  par::init(&argc, &argv);
  const int code = run_main(argc, argv);
  if (code != 0 && code != kExitInterrupted && par::size() > 1) par::abort(code);
  par::finalize();
  return code;
}
