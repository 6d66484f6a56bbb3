#include "run/montage.hpp"

#include <vtkImageData.h>
#include <vtkPolyData.h>
#include <vtkUnstructuredGrid.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <set>

#include "core/error.hpp"
#include "core/log.hpp"
#include "io/case_config.hpp"
#include "render/colormap.hpp"
#include "render/montage.hpp"
#include "render/offscreen.hpp"
#include "render/series.hpp"
#include "render/views.hpp"
#include "run/render_args.hpp"
#include "run/wall_shapes.hpp"

namespace dspdem {

namespace {
namespace fs = std::filesystem;

struct Row {
  std::string view, cut = "none";
};

Row parse_row(const std::string& spec) {
  Row r;
  const auto colon = spec.find(':');
  r.view = spec.substr(0, colon);
  if (colon != std::string::npos) r.cut = spec.substr(colon + 1);
  if (r.view != "stress" && r.view != "fragments" && r.view != "cracks")
    fail("--rows '{}': unknown view '{}' (known: stress, fragments, cracks)", spec, r.view);
  if (r.cut != "none" && r.cut != "x" && r.cut != "y" && r.cut != "z")
    fail("--rows '{}': unknown cut '{}' (known: none, x, y, z)", spec, r.cut);
  return r;
}

// The frame of `frames` nearest to time t (t < 0: the last). A time past the last frame is
// the last frame: far past it every distance rounds to the same, and the first won that tie
// (a probe's: --time 1e15 drew t = 0).
std::size_t nearest(const std::vector<render::FrameRef>& frames, double t) {
  if (t < 0 || t >= frames.back().time) return frames.size() - 1;
  std::size_t best = 0;
  for (std::size_t i = 1; i < frames.size(); ++i)
    if (std::abs(frames[i].time - t) < std::abs(frames[best].time - t)) best = i;
  return best;
}

// The file a montage goes to: it is a PNG, so a name that does not end in .png gets ".png"
// (a dot in it, as in montage_v7.5, is part of the name), as plotting tools do; a name with
// another image or document type's extension is refused before anything is drawn rather than
// given PNG bytes, and so is a folder.
fs::path png_path(const std::string& name) {
  fs::path out = name;
  const std::string file = out.filename().string();
  DSPDEM_CHECK(!file.empty() && file != "." && file != "..", "--montage {}: names a folder, not an image file", name);
  std::string ext = out.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char ch) { return std::tolower(ch); });
  if (ext == ".png") return out;
  static const std::set<std::string> other = {".jpg", ".jpeg", ".tif", ".tiff", ".bmp", ".gif", ".ppm",
                                              ".pnm", ".webp", ".svg", ".pdf",  ".eps", ".ps"};
  DSPDEM_CHECK(!other.count(ext), "--montage {}: a montage is a PNG image; name it .png (or leave the type off)", name);
  return out += ".png";
}
}  // namespace

MontageFrames write_montage(const MontageArgs& a) {
  DSPDEM_CHECK(!a.run_dirs.empty(), "--montage: no run folder given");
  DSPDEM_CHECK(!a.out.empty(), "--montage: no output image given");
  const fs::path out = png_path(a.out);
  // A run's frames/ holds its frame files only: the next run into that folder is refused
  // while anything else is there (io/run_place.hpp, check_run_frames).
  const fs::path holder = fs::absolute(out).parent_path();
  DSPDEM_CHECK(holder.filename() != "frames" || !fs::exists(holder.parent_path() / "run.pvd"),
               "--montage {}: that is inside the frames/ of the run in {}, which holds its frame files only; write the "
               "montage elsewhere",
               a.out, holder.parent_path().string());
  DSPDEM_CHECK(a.labels.empty() || a.labels.size() == a.run_dirs.size(),
               "--montage: {} label(s) for {} run folder(s): give one per run or none", a.labels.size(),
               a.run_dirs.size());
  DSPDEM_CHECK(!a.rows.empty(), "--montage: no row given");
  DSPDEM_CHECK(a.times.empty() || a.times.size() == a.run_dirs.size(), "--montage: {} time(s) for {} run folder(s)",
               a.times.size(), a.run_dirs.size());
  std::vector<Row> rows;
  for (const auto& s : a.rows) rows.push_back(parse_row(s));
  const bool cracks = std::any_of(rows.begin(), rows.end(), [](const Row& r) { return r.view == "cracks"; });

  // Defaults from the first run's case, as `dspdem render` takes them.
  CaseConfig c;
  const fs::path resolved = fs::path(a.run_dirs[0]) / "case.resolved.toml";
  if (fs::exists(resolved)) c = read_case(resolved.string());
  render::ViewOptions base;
  base.camera = a.camera.empty() ? c.render.camera : a.camera;
  base.fit = c.render.fit;
  base.field = a.field.empty() ? c.render.field : a.field;
  base.magnify = 1.0;  // a montage compares runs as they are
  base.edges = c.render.edges;
  base.width = a.width, base.height = a.height;
  base.background = {c.render.background(0), c.render.background(1), c.render.background(2)};

  MontageFrames used;
  std::vector<vtkSmartPointer<vtkUnstructuredGrid>> grids, joint_grids;
  std::vector<vtkSmartPointer<vtkPolyData>> walls;
  std::vector<std::string> files, labels;
  for (std::size_t r = 0; r < a.run_dirs.size(); ++r) {
    const auto frames = render::read_series(a.run_dirs[r]);
    const double want = a.times.empty() ? a.time : a.times[r];
    const std::size_t i = nearest(frames, want);
    used.frame.push_back(i), used.time.push_back(frames[i].time);
    files.push_back(frames[i].file);
    grids.push_back(render::read_frame(frames[i].file));
    if (r == 0) render::read_frame(frames[0].file)->GetBounds(base.bounds);  // every panel framed alike
    {  // each run's own walls (a sweep's runs may differ in them)
      const fs::path rc = fs::path(a.run_dirs[r]) / "case.resolved.toml";
      const CaseConfig cr = r == 0 || !fs::exists(rc) ? c : read_case(rc.string());
      walls.push_back(wall_surfaces(cr.walls, grids.back(), base.bounds));
    }
    if (r == 0 && a.frame_walls && walls.back() && walls.back()->GetNumberOfPoints() > 0) {
      // The drawn frame's bodies and the walls: a heap in its box, not the cloud it fell from.
      double b[6], w[6];
      grids.back()->GetBounds(b);
      walls.back()->GetBounds(w);
      for (int k = 0; k < 3; ++k)
        base.bounds[2 * k] = std::min(b[2 * k], w[2 * k]),
                        base.bounds[2 * k + 1] = std::max(b[2 * k + 1], w[2 * k + 1]);
    }
    if (cracks) {
      DSPDEM_CHECK(fs::exists(fs::path(a.run_dirs[r]) / "joints.pvd"),
                   "--montage: a cracks row needs the joints dataset, which run '{}' does not have", a.run_dirs[r]);
      joint_grids.push_back(render::read_frame(render::read_series(a.run_dirs[r], "joints.pvd")[i].file));
    }
    labels.push_back(a.labels.empty() ? fs::path(a.run_dirs[r]).filename().string() : a.labels[r]);
    if (want >= 0 && frames.size() > 1) {
      const double spacing = frames.back().time / static_cast<double>(frames.size() - 1);
      if (std::abs(frames[i].time - want) > 0.51 * spacing)
        log::warn("montage: run '{}' has no frame near t = {:.4g} s; its panel shows t = {:.4g} s", a.run_dirs[r], want,
                  frames[i].time);
    }
  }
  if (std::any_of(rows.begin(), rows.end(), [](const Row& r) { return r.view == "stress"; })) {
    if (!a.range.empty()) {
      parse_range(a.range, "--range", base.range[0], base.range[1]);
    } else {  // one colour range over every panel, 0.5th to 99.5th percentile
      std::vector<double> v;
      for (std::size_t r = 0; r < grids.size(); ++r) {
        const auto f = render::field_values(grids[r], base.field, files[r]);
        v.insert(v.end(), f.begin(), f.end());
      }
      std::sort(v.begin(), v.end());
      base.range[0] = v[static_cast<std::size_t>(0.005 * static_cast<double>(v.size() - 1))];
      base.range[1] = v[static_cast<std::size_t>(0.995 * static_cast<double>(v.size() - 1))];
      // As a run's own frames (render_run.cpp): magnitudes from zero, signed stresses centred on it.
      if (!render::field_display(base.field).is_signed && base.range[0] > 0) base.range[0] = 0;
      if (render::field_display(base.field).is_signed)
        base.range[1] = std::max(std::abs(base.range[0]), std::abs(base.range[1])), base.range[0] = -base.range[1];
      if (!(base.range[1] > base.range[0]))
        base.range[1] = base.range[0] + 1e-6 * std::max(1.0, std::abs(base.range[0]));
    }
  }

  std::vector<vtkSmartPointer<vtkImageData>> panels;
  for (const Row& row : rows) {
    render::ViewOptions o = base;
    o.view = row.view, o.cut = row.cut;
    for (std::size_t r = 0; r < grids.size(); ++r) {
      o.label = labels[r];
      log::debug("montage panel {}: label '{}'", r, o.label);
      render::FrameRenderer fr(o);  // a renderer per panel: the label is fixed at construction
      panels.push_back(
          fr.render(grids[r], used.time[r], files[r], cracks ? joint_grids[r].Get() : nullptr, walls[r].Get()));
    }
  }
  const auto img = render::tile_images(panels, static_cast<int>(grids.size()));
  fs::create_directories(fs::absolute(out).parent_path());
  render::write_png(img, out.string());
  log::info("dspdem render --montage: {} run(s) x {} row(s) -> {}", grids.size(), rows.size(), out.string());
  return used;
}

}  // namespace dspdem
