#include "scenes/packing/analysis.hpp"

#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkIdList.h>
#include <vtkUnstructuredGrid.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>

#include "core/error.hpp"
#include "render/series.hpp"
#include "report/run_data.hpp"

namespace dspdem {

namespace {
namespace fs = std::filesystem;

// The material index (into the case's [materials]) of the body made of the particles group.
long particle_material(const CaseConfig& c) {
  for (const auto& b : c.bodies)
    if (std::find(b.groups.begin(), b.groups.end(), "particles") != b.groups.end())
      for (std::size_t m = 0; m < c.materials.size(); ++m)
        if (c.materials[m].name == b.material) return static_cast<long>(m);
  fail("{}: the packing scene needs a [[bodies]] entry over the group \"particles\"", c.path);
}
}  // namespace

PackingResult analyse_packing_run(const CaseConfig& c, const std::string& run_dir, const std::string& files_dir) {
  DSPDEM_CHECK(c.mesh_generator == "packing", "{}: the packing scene needs the packing generator", c.path);
  PackingResult r;
  r.run_dir = run_dir;
  r.box_x = mesh_param(c, "box_x"), r.box_z = mesh_param(c, "box_z"), r.box_height = mesh_param(c, "box_height");
  r.cell = 2 * mesh_param(c, "size_max");
  const long mat = particle_material(c);
  const report::RunData run = report::RunData::open(run_dir);
  const report::Series& s = run.series;
  const auto &t = s["time"], &ke = s["kinetic"], &w = s["external_work"], &nc = s["contacts"];
  const auto& bal = s["balance_error"];
  const std::size_t n = t.size();
  DSPDEM_CHECK(n > 1, "{}: series.csv has no rows after the start", run_dir);
  r.released = w[n - 1], r.kinetic_end = ke[n - 1], r.contacts_end = nc[n - 1];
  r.balance_max = *std::max_element(bal.begin(), bal.end());
  // At rest from the first row after which every row is below the ratio.
  for (std::size_t i = n; i-- > 0;) {
    if (!(w[i] > 0 && ke[i] < PackingResult::rest_ratio * w[i])) break;
    r.t_rest = t[i];
  }

  // The last frame: particles' centroids, highest vertices and volumes. A particle is one
  // body (split_components): one tetrahedron, or a small meshed polyhedron (mesh.packing.refine),
  // whose centroid is its cells' centroids weighted by their volumes.
  const std::string& frame = run.frames.back().file;
  auto g = render::read_frame(frame);
  vtkDataArray* matf = g->GetCellData()->GetArray("material");
  vtkDataArray* bodyf = g->GetCellData()->GetArray("body");
  DSPDEM_CHECK(matf, "frame '{}' has no 'material' cell field (add it to [output] fields)", frame);
  DSPDEM_CHECK(bodyf || mesh_param(c, "refine") == 0,
               "frame '{}' has no 'body' cell field, which meshed particles need (add it to [output] fields)", frame);
  struct Particle {
    double volume = 0, top = -INFINITY;
    Vec3 moment = Vec3::Zero();
  };
  std::map<long, Particle> particles;  // by body (by cell without the body field: one tet each)
  vtkNew<vtkIdList> ids;
  for (vtkIdType e = 0; e < g->GetNumberOfCells(); ++e) {
    if (std::lround(matf->GetTuple1(e)) != mat) continue;
    g->GetCellPoints(e, ids);
    DSPDEM_CHECK(ids->GetNumberOfIds() == 4, "frame '{}' cell {}: packing particles are made of tetrahedra", frame, e);
    Vec3 p[4], ctr = Vec3::Zero();
    Particle& q = particles[bodyf ? std::lround(bodyf->GetTuple1(e)) : static_cast<long>(e)];
    for (int k = 0; k < 4; ++k) {
      g->GetPoint(ids->GetId(k), p[k].data());
      ctr += 0.25 * p[k];
      q.top = std::max(q.top, p[k](1));
    }
    const double vol = std::abs((p[1] - p[0]).cross(p[2] - p[0]).dot(p[3] - p[0])) / 6;
    q.volume += vol;
    q.moment += vol * ctr;
  }
  const long gx = std::max(1L, std::lround(r.box_x / r.cell)), gz = std::max(1L, std::lround(r.box_z / r.cell));
  std::vector<double> surface(static_cast<std::size_t>(gx * gz), 0.0);
  for (const auto& [body, q] : particles) {
    const Vec3 ctr = q.moment / q.volume;
    ++r.particles;
    r.solid_volume += q.volume;
    r.centroid_max = std::max(r.centroid_max, ctr(1));
    if (ctr(0) < 0 || ctr(0) > r.box_x || ctr(2) < 0 || ctr(2) > r.box_z || ctr(1) < 0) {
      ++r.escaped;
      continue;
    }
    const long ix = std::min(gx - 1, static_cast<long>(ctr(0) / r.box_x * gx));
    const long iz = std::min(gz - 1, static_cast<long>(ctr(2) / r.box_z * gz));
    double& cell = surface[static_cast<std::size_t>(iz * gx + ix)];
    cell = std::max(cell, q.top);
  }
  DSPDEM_CHECK(r.particles > 0, "frame '{}': no particle cells (material {})", frame, mat);
  for (double h : surface) r.surface_mean += h / static_cast<double>(surface.size());
  r.surface_max = *std::max_element(surface.begin(), surface.end());
  r.packing_fraction = r.surface_mean > 0 ? r.solid_volume / (r.box_x * r.box_z * r.surface_mean) : 0.0;

  const RunSummary& sum = run.summary;
  r.steps = sum.steps, r.dt = sum.dt, r.wall_s = sum.wall_s, r.t_end = t[n - 1];
  r.particle_steps_per_s =
      r.wall_s > 0 ? static_cast<double>(r.particles) * static_cast<double>(r.steps) / r.wall_s : 0;

  if (!files_dir.empty()) {
    const double weight = sum.total_mass * c.gravity.norm();
    std::ofstream f(fs::path(files_dir) / "packing_series.csv");
    DSPDEM_CHECK(f.good(), "cannot write '{}/packing_series.csv'", files_dir);
    f << "time,kinetic_over_released,log10_kinetic_over_released,contacts_per_particle,floor_force_over_weight\n";
    for (std::size_t i = 0; i < n; ++i) {
      const double ratio = w[i] > 0 ? ke[i] / w[i] : 1.0;
      f << fmt::format("{:.6g},{:.6g},{:.6g},{:.6g},{:.6g}\n", t[i], ratio, std::log10(std::max(ratio, 1e-12)),
                       nc[i] / static_cast<double>(r.particles),
                       s.has("floor_fy") && weight > 0 ? -s["floor_fy"][i] / weight : 0.0);
    }
    std::ofstream h(fs::path(files_dir) / "heap_surface.csv");
    DSPDEM_CHECK(h.good(), "cannot write '{}/heap_surface.csv'", files_dir);
    h << "x,z,surface_height\n";
    for (long iz = 0; iz < gz; ++iz)
      for (long ix = 0; ix < gx; ++ix)
        h << fmt::format("{:.4g},{:.4g},{:.4g}\n", (ix + 0.5) * r.box_x / gx, (iz + 0.5) * r.box_z / gz,
                         surface[static_cast<std::size_t>(iz * gx + ix)]);
  }
  return r;
}

}  // namespace dspdem
