#include "run/render_run.hpp"

#include <omp.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>
#include <vtkCellData.h>
#include <vtkImageData.h>
#include <vtkPolyData.h>
#include <vtkUnstructuredGrid.h>

#include <algorithm>
#include <filesystem>
#include <optional>
#include <sstream>

#include "core/error.hpp"
#include "core/folder_lock.hpp"
#include "core/log.hpp"
#include "core/subprocess.hpp"
#include "core/timer.hpp"
#include "io/case_config.hpp"
#include "io/run_place.hpp"
#include "render/animation.hpp"
#include "render/colormap.hpp"
#include "render/offscreen.hpp"
#include "render/plot.hpp"
#include "render/series.hpp"
#include "render/views.hpp"
#include "run/render_args.hpp"
#include "run/series_units.hpp"
#include "run/wall_shapes.hpp"

namespace dspdem {

namespace {
namespace fs = std::filesystem;

std::vector<std::size_t> select_frames(const std::string& spec, std::size_t n) {
  std::vector<std::size_t> out;
  if (spec == "all") {
    for (std::size_t i = 0; i < n; ++i) out.push_back(i);
  } else if (spec == "last") {
    out.push_back(n - 1);
  } else if (spec.rfind("every:", 0) == 0) {
    const std::string stride = spec.substr(6);
    long k = 0;
    DSPDEM_CHECK(whole_number(stride, k) && k > 0, "--frames {}: the stride '{}' is not a positive whole number", spec,
                 stride);
    for (std::size_t i = 0; i < n; i += static_cast<std::size_t>(k)) out.push_back(i);
  } else {
    std::stringstream ss(spec);
    for (std::string t; std::getline(ss, t, ',');) {
      long i = 0;
      DSPDEM_CHECK(whole_number(t, i) && i >= 0 && static_cast<std::size_t>(i) < n,
                   "--frames {}: '{}' is not a frame index (the run has {} frames)", spec, t, n);
      out.push_back(static_cast<std::size_t>(i));
    }
  }
  DSPDEM_CHECK(!out.empty(), "--frames {}: no frame selected", spec);
  return out;
}

// Robust colour range over every selected frame: 0.5th to 99.5th percentile.
void auto_range(const std::vector<render::FrameRef>& frames, const std::vector<std::size_t>& sel,
                render::ViewOptions& o, const RenderConfig& rc) {
  std::vector<double> v;
  for (std::size_t i : sel) {
    auto g = render::read_frame(frames[i].file);
    const auto f = render::field_values(g, o.field, frames[i].file);
    const std::size_t stride = std::max<std::size_t>(1, f.size() * sel.size() / 2000000);
    for (std::size_t k = 0; k < f.size(); k += stride) v.push_back(f[k]);
  }
  std::sort(v.begin(), v.end());
  double lo = v[static_cast<std::size_t>(0.005 * (v.size() - 1))],
         hi = v[static_cast<std::size_t>(0.995 * (v.size() - 1))];
  // Magnitudes from zero; signed stresses centred on zero, so the diverging map's white is zero.
  if (render::field_display(o.field).is_signed)
    hi = std::max(std::abs(lo), std::abs(hi)), lo = -hi;
  else
    lo = 0;
  if (!rc.auto_min) lo = rc.range_min;
  if (!rc.auto_max) hi = rc.range_max;
  if (!(hi > lo)) hi = lo + std::max(1.0, std::abs(lo)) * 1e-6;
  o.range[0] = lo, o.range[1] = hi;
}

std::string view_dir(const std::string& run, const std::string& view) {
  return (fs::path(run) / "images" / view).string();
}

void spawn_workers(const RenderArgs& a, const render::ViewOptions& o, int jobs, std::vector<pid_t>& pids) {
  for (int k = 1; k < jobs; ++k) {
    std::vector<std::string> args = {"-q",
                                     "render",
                                     a.run_dir,
                                     "--out",
                                     a.out_dir,
                                     "--worker",
                                     fmt::format("{}/{}", k, jobs),
                                     "--frames",
                                     a.frames,
                                     "--field",
                                     o.field,
                                     "--camera",
                                     o.camera,
                                     "--cut",
                                     o.cut,
                                     "--magnify",
                                     fmt::format("{:.17g}", o.magnify),
                                     "--range",
                                     fmt::format("{:.17g}:{:.17g}", o.range[0], o.range[1]),
                                     "--size",
                                     fmt::format("{}x{}", o.width, o.height)};
    if (o.edges) args.push_back("--edges");
    if (!a.label.empty()) args.push_back("--label"), args.push_back(a.label);
    for (const auto& v : a.views) args.push_back("--view"), args.push_back(v);
    // Its messages on our stderr. In a group of its own, so that it is stopped when this render
    // dies, however it dies (stop_with_parent): none draws on into a folder whose lock is gone.
    SpawnOptions so;
    so.own_group = true;
    const pid_t pid = spawn_program("/proc/self/exe", args, so);
    if (pid > 0)
      pids.push_back(pid);
    else
      log::warn("could not start render worker {}; rendering its frames here", k);
  }
}
}  // namespace

std::string common_range(const std::vector<std::string>& run_dirs, const std::string& field, const RenderConfig& rc) {
  std::vector<render::FrameRef> frames;
  for (const auto& d : run_dirs) {
    const auto f = render::read_series(d);
    frames.insert(frames.end(), f.begin(), f.end());
  }
  DSPDEM_CHECK(!frames.empty(), "common_range: no frames in {} run folder(s)", run_dirs.size());
  std::vector<std::size_t> all(frames.size());
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = i;
  render::ViewOptions o;
  o.field = field;
  auto_range(frames, all, o, rc);
  return fmt::format("{:.17g}:{:.17g}", o.range[0], o.range[1]);
}

int render_command(const RenderArgs& in) {
  Timer wall;
  RenderArgs a = in;
  if (a.out_dir.empty()) a.out_dir = a.run_dir;
  const fs::path resolved = fs::path(a.run_dir) / "case.resolved.toml";
  CaseConfig c;
  if (fs::exists(resolved))
    c = read_case(resolved.string());
  else if (a.worker.empty())
    log::warn("{}: no case.resolved.toml: drawn with the default [render] settings (views, size, camera)", a.run_dir);
  const RenderConfig& rc = c.render;
  if (a.views.empty()) a.views = rc.views;
  render::ViewOptions o;
  o.field = a.field.empty() ? rc.field : a.field;
  o.camera = a.camera.empty() ? rc.camera : a.camera;
  o.cut = a.cut.empty() ? rc.cut : a.cut;
  o.fit = rc.fit;
  o.magnify = a.magnify > 0 ? a.magnify : rc.magnify;
  o.width = rc.width, o.height = rc.height;
  if (!a.size.empty()) parse_image_size(a.size, "--size", o.width, o.height);
  o.background = {rc.background(0), rc.background(1), rc.background(2)};
  o.title = c.name;
  o.label = a.label;
  o.edges = a.edges || rc.edges;

  const std::vector<render::FrameRef> frames = render::read_series(a.run_dir);
  const std::vector<std::size_t> sel = select_frames(a.frames, frames.size());
  // Validate every view on the first selected frame before writing anything.
  auto first = render::read_frame(frames[sel[0]].file);
  first->GetBounds(o.bounds);
  for (const auto& v : a.views) {
    if (v == "stress")
      render::field_values(first, o.field, frames[sel[0]].file);
    else if (v == "fragments") {
      if (!first->GetCellData()->GetArray("fragment") && !first->GetCellData()->GetArray("body"))
        fail("frame '{}' has neither 'fragment' nor 'body' cell data: the fragments view needs one",
             frames[sel[0]].file);
    } else if (v == "cracks") {
      if (!fs::exists(fs::path(a.run_dir) / "joints.pvd"))
        fail(
            "the cracks view needs the joints dataset (joints.pvd), which run '{}' does not have: the run has no "
            "fracturable body",
            a.run_dir);
    } else {
      fail("unknown view '{}' (known: stress, fragments, cracks)", v);
    }
  }
  // The series the plots are drawn from, read before anything is drawn: a damaged one, found
  // at the plots, left the frames drawn anew beside the plots of before (a probe's).
  const fs::path csv = fs::path(a.run_dir) / "series.csv";
  std::vector<std::string> names;
  std::vector<std::vector<double>> cols;
  const bool plots = a.worker.empty() && fs::exists(csv);
  if (plots) render::read_csv(csv.string(), names, cols);
  if (!a.range.empty()) {
    parse_range(a.range, "--range", o.range[0], o.range[1]);
  } else if (std::find(a.views.begin(), a.views.end(), "stress") != a.views.end()) {
    auto_range(frames, sel, o, rc);
  }

  int k = 0, n = 1;
  const bool worker = !a.worker.empty();
  if (worker)
    DSPDEM_CHECK(std::sscanf(a.worker.c_str(), "%d/%d", &k, &n) == 2 && n > 0 && k >= 0 && k < n, "--worker {}",
                 a.worker);
  // By default as many as the solver's threads (-t, else OMP_NUM_THREADS, else the cores): a
  // report given -t 1 on a shared machine renders on one core too.
  int jobs = a.jobs > 0 ? a.jobs : std::max(1, omp_get_max_threads());
  jobs = std::min<int>(jobs, static_cast<int>(sel.size()));
  // Into another folder (--out): one that another run's images were drawn into is emptied
  // first, so that frames not drawn again do not sit beside these as theirs; one holding a run
  // or files not derived from a run is refused (io/run_place.hpp). Checked before the lock too,
  // so that a folder refused is not made.
  if (!worker) check_derived_place(a.out_dir, a.run_dir);
  // One render at a time into a folder: two would draw over each other's frames, and one
  // emptying a place another is drawing into would leave both runs' frames mixed. Held until
  // the render ends; its workers draw under it.
  std::optional<FolderLock> lock;
  if (!worker) lock.emplace(a.out_dir, render_lock_file, "another render (or a run or a report emptying it)");
  if (!worker) prepare_derived_place(a.out_dir, a.run_dir);
  std::vector<pid_t> pids;
  // Workers still drawing when this render stops early on an error below are stopped and waited
  // for before its lock goes: none may draw on into a folder another render then takes.
  struct StopWorkers {
    std::vector<pid_t>& pids;
    ~StopWorkers() {
      for (pid_t p : pids) ::kill(p, SIGTERM);
      for (pid_t p : pids) wait_program(p);
    }
  } stop_workers{pids};
  if (!worker && jobs > 1) {
    spawn_workers(a, o, jobs, pids);
    n = static_cast<int>(pids.size()) + 1;
  }
  for (const auto& v : a.views) fs::create_directories(view_dir(a.out_dir, v));

  std::vector<render::FrameRef> joint_frames;
  if (std::find(a.views.begin(), a.views.end(), "cracks") != a.views.end()) {
    joint_frames = render::read_series(a.run_dir, "joints.pvd");
    DSPDEM_CHECK(joint_frames.size() == frames.size(), "'{}/joints.pvd' lists {} frames, run.pvd {}", a.run_dir,
                 joint_frames.size(), frames.size());
  }
  Timer t;
  std::string gl;
  long drawn = 0;
  for (const auto& view : a.views) {
    render::ViewOptions vo = o;
    vo.view = view;
    render::FrameRenderer fr(vo);
    gl = fr.gl_info();
    for (std::size_t s = 0; s < sel.size(); ++s) {
      if (static_cast<int>(s % static_cast<std::size_t>(n)) != k) continue;
      const std::size_t i = sel[s];
      auto g = s == 0 ? first : render::read_frame(frames[i].file);
      vtkSmartPointer<vtkUnstructuredGrid> jg;
      if (view == "cracks") jg = render::read_frame(joint_frames[i].file);
      const auto walls = wall_surfaces(c.walls, g, o.bounds);
      auto img = fr.render(g, frames[i].time, frames[i].file, jg, walls);
      render::write_png(img, (fs::path(view_dir(a.out_dir, view)) / fmt::format("frame_{:04d}.png", i)).string());
      ++drawn;
    }
  }
  const double t_frames = t.seconds();
  int failed = 0;
  for (pid_t p : pids) {
    int st = 0;
    waitpid(p, &st, 0);
    failed += !(WIFEXITED(st) && WEXITSTATUS(st) == 0);
  }
  pids.clear();  // all ended
  if (worker) return 0;
  DSPDEM_CHECK(failed == 0, "{} render worker(s) failed; see their messages above", failed);
  log::info("dspdem render: {} frame(s) x {} view(s) of {} at {}x{} with {} process(es), {:.3f} s per image here ({})",
            sel.size(), a.views.size(), a.run_dir, o.width, o.height, n, drawn > 0 ? t_frames / drawn : 0.0, gl);
  if (std::find(a.views.begin(), a.views.end(), "stress") != a.views.end())
    log::info("  stress view: {} in [{:.4g}, {:.4g}], magnification {}", o.field, o.range[0], o.range[1], o.magnify);

  if (rc.animation && !a.no_animation && sel.size() > 1) {
    std::vector<render::AnimationJob> todo;
    for (const auto& view : a.views) {
      render::AnimationJob j{{}, view_dir(a.out_dir, view)};
      for (std::size_t i : sel)
        j.pngs.push_back((fs::path(view_dir(a.out_dir, view)) / fmt::format("frame_{:04d}.png", i)).string());
      todo.push_back(std::move(j));
    }
    for (const auto& files : render::write_animations(todo, rc.fps, jobs))
      for (const auto& f : files) log::info("  animation {}", f);
  }
  // Plots: energies and monitors against time, then the case's extra plots.
  if (plots) {
    const fs::path pdir = fs::path(a.out_dir) / "images" / "plots";
    fs::create_directories(pdir);
    render::PlotSpec energy{"time", {"kinetic", "internal", "external_work", "damping"}, "", "energy ledger [J]"};
    energy.y_title = "energy [J]";
    if (std::find(names.begin(), names.end(), "fracture_I") != names.end())
      energy.y.insert(energy.y.end(), {"joint_elastic", "fracture_I", "fracture_II"});
    if (std::find(names.begin(), names.end(), "contact_elastic") != names.end())
      energy.y.insert(energy.y.end(), {"contact_elastic", "friction", "contact_damping"});
    render::plot_csv(csv.string(), energy, (pdir / "energy.png").string());
    // Monitors follow the balance_error column.
    const std::size_t first_monitor =
        static_cast<std::size_t>(std::find(names.begin(), names.end(), "balance_error") - names.begin() + 1);
    // A column that is zero on every row (a wall nothing touched, a support the beam left) is
    // not drawn: a flat line on a +-1e-7 axis tells nothing; the log names them.
    std::vector<std::string> zero;
    for (std::size_t i = first_monitor; i < names.size(); ++i) {
      if (std::all_of(cols[i].begin(), cols[i].end(), [](double v) { return v == 0.0; })) {
        zero.push_back(names[i]);
        continue;
      }
      render::PlotSpec m{"time", {names[i]}, "", names[i]};
      m.y_title = series_axis_title(c, names[i]);
      render::plot_csv(csv.string(), m, (pdir / (names[i] + ".png")).string());
    }
    for (const auto& p : rc.plots) {
      render::PlotSpec s;
      s.x = p.substr(0, p.find(':'));
      std::stringstream ys(p.substr(p.find(':') + 1));
      for (std::string y; std::getline(ys, y, ',');) s.y.push_back(y);
      s.reference_csv = rc.plot_reference;
      s.title = p;
      s.x_title = series_axis_title(c, s.x);
      // One unit for all the curves on the axis, or none named.
      const std::string u = series_unit(c, s.y.front());
      if (std::all_of(s.y.begin(), s.y.end(), [&](const std::string& y) { return series_unit(c, y) == u; }))
        s.y_title = s.y.size() == 1             ? series_axis_title(c, s.y.front())
                    : u.empty() || u == "count" ? ""
                                                : "[" + u + "]";
      std::string name = p;
      std::replace(name.begin(), name.end(), ':', '_');
      std::replace(name.begin(), name.end(), ',', '_');
      render::plot_csv(csv.string(), s, (pdir / (name + ".png")).string());
    }
    log::info("  plots in {}", pdir.string());
    if (!zero.empty()) log::info("  not plotted, zero throughout: {}", fmt::join(zero, ", "));
  }
  log::info("  images in {}/images/ ({:.2f} s in all)", a.out_dir, wall.seconds());
  return 0;
}

}  // namespace dspdem
