#include "report/crack_sampling.hpp"

#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkIdList.h>
#include <vtkNew.h>
#include <vtkUnstructuredGrid.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "core/error.hpp"
#include "render/series.hpp"

namespace dspdem::report {

std::vector<CrackPiece> broken_joints(const std::string& joints_vtu, int min_state) {
  std::vector<CrackPiece> out;
  if (!std::filesystem::exists(joints_vtu)) return out;
  auto g = render::read_frame(joints_vtu);
  vtkDataArray* state = g->GetCellData()->GetArray("state");
  DSPDEM_CHECK(state, "'{}' has no cell array 'state' (not a joints frame)", joints_vtu);
  vtkDataArray* opening = g->GetCellData()->GetArray("opening");
  vtkDataArray* slip = g->GetCellData()->GetArray("slip");
  vtkNew<vtkIdList> ids;
  for (vtkIdType e = 0; e < g->GetNumberOfCells(); ++e) {
    if (state->GetComponent(e, 0) < min_state) continue;
    g->GetCellPoints(e, ids);
    const vtkIdType nv = ids->GetNumberOfIds();
    std::vector<Vec3> v(nv);
    for (vtkIdType k = 0; k < nv; ++k) {
      double q[3];
      g->GetPoint(ids->GetId(k), q);
      v[k] = Vec3(q[0], q[1], q[2]);
    }
    CrackPiece p;
    p.centroid = Vec3::Zero();
    for (const auto& q : v) p.centroid += q;
    p.centroid /= static_cast<Real>(nv);
    Vec3 n = Vec3::Zero();
    for (vtkIdType k = 1; k + 1 < nv; ++k) {
      const Vec3 c = (v[k] - v[0]).cross(v[k + 1] - v[0]);
      p.area += 0.5 * c.norm(), n += c;
    }
    if (n.norm() > 0) p.normal = n.normalized();
    if (opening && slip) p.jump = std::hypot(std::max(0.0, opening->GetComponent(e, 0)), slip->GetComponent(e, 0));
    out.push_back(p);
  }
  return out;
}

std::vector<int> joint_states(const std::string& joints_vtu) {
  auto g = render::read_frame(joints_vtu);
  vtkDataArray* state = g->GetCellData()->GetArray("state");
  DSPDEM_CHECK(state, "'{}' has no cell array 'state' (not a joints frame)", joints_vtu);
  std::vector<int> out(static_cast<std::size_t>(g->GetNumberOfCells()));
  for (vtkIdType e = 0; e < g->GetNumberOfCells(); ++e) out[e] = static_cast<int>(state->GetComponent(e, 0));
  return out;
}

CrackReach crack_reach(const std::vector<CrackPiece>& where, const std::vector<int>& states, const Vec3& origin,
                       const Vec3& dir, double quantile, int min_state) {
  DSPDEM_CHECK(where.size() == states.size(), "crack_reach: {} joint positions for {} joint states", where.size(),
               states.size());
  DSPDEM_CHECK(quantile > 0 && quantile <= 1, "crack_reach: quantile {} outside (0, 1]", quantile);
  std::vector<std::pair<double, double>> sa;  // (s, area) of the counted joints
  for (std::size_t j = 0; j < where.size(); ++j)
    if (states[j] >= min_state) sa.emplace_back((where[j].centroid - origin).dot(dir), where[j].area);
  CrackReach r;
  if (sa.empty()) return r;
  std::sort(sa.begin(), sa.end());
  for (const auto& [s, a] : sa) r.area += a;
  r.furthest = sa.back().first;
  double below = 0;
  r.at_quantile = sa.back().first;
  for (const auto& [s, a] : sa) {
    below += a;  // summed in the order of r.area's sum, so a quantile of 1 ends on the last joint
    if (below >= quantile * r.area) {
      r.at_quantile = s;
      break;
    }
  }
  return r;
}

std::vector<long> count_by_band(const std::vector<CrackPiece>& where, const std::vector<int>& states,
                                const Vec3& origin, const Vec3& dir, const std::vector<double>& edges, int min_state) {
  DSPDEM_CHECK(where.size() == states.size(), "count_by_band: {} joint positions for {} joint states", where.size(),
               states.size());
  DSPDEM_CHECK(edges.size() >= 2 && std::is_sorted(edges.begin(), edges.end()),
               "count_by_band: the band edges must be ascending, at least two");
  std::vector<long> n(edges.size() - 1, 0);
  for (std::size_t j = 0; j < where.size(); ++j) {
    if (states[j] < min_state) continue;
    const double s = (where[j].centroid - origin).dot(dir);
    if (s < edges.front() || s > edges.back()) continue;
    // The first edge above s closes its band; s on the top edge falls in the last band.
    const auto up = std::upper_bound(edges.begin(), edges.end(), s);
    const std::size_t band = up == edges.end() ? n.size() - 1 : static_cast<std::size_t>(up - edges.begin()) - 1;
    ++n[band];
  }
  return n;
}

std::vector<std::pair<double, double>> trace_path(const std::vector<CrackPiece>& pieces, int along, int across,
                                                  double lo, double hi, int bins,
                                                  bool (*keep)(const Vec3&, const void*), const void* ctx,
                                                  PathWeight weight) {
  std::vector<double> w(bins, 0), s_along(bins, 0), s_across(bins, 0);
  const double d = (hi - lo) / bins;
  for (const auto& p : pieces) {
    const double a = p.centroid(along);
    if (a <= lo || a >= hi || (keep && !keep(p.centroid, ctx))) continue;
    const int b = std::min(bins - 1, static_cast<int>((a - lo) / d));
    const double pw = weight == PathWeight::AreaWidth ? p.area * p.jump : p.area;
    w[b] += pw, s_along[b] += pw * a, s_across[b] += pw * p.centroid(across);
  }
  std::vector<std::pair<double, double>> path;
  for (int b = 0; b < bins; ++b)
    if (w[b] > 0) path.emplace_back(s_along[b] / w[b], s_across[b] / w[b]);
  return path;
}

namespace {
double point_to_polyline(const std::pair<double, double>& p, const std::vector<std::pair<double, double>>& l) {
  double best = INFINITY;
  const Eigen::Vector2d q(p.first, p.second);
  for (std::size_t i = 0; i < l.size(); ++i) {
    const Eigen::Vector2d a(l[i].first, l[i].second);
    if (i + 1 == l.size()) {
      best = std::min(best, (q - a).norm());
      break;
    }
    const Eigen::Vector2d b(l[i + 1].first, l[i + 1].second), ab = b - a;
    const double t = ab.squaredNorm() > 0 ? std::clamp((q - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0) : 0.0;
    best = std::min(best, (q - (a + t * ab)).norm());
  }
  return best;
}
}  // namespace

PathDistance path_distance(const std::vector<std::pair<double, double>>& a,
                           const std::vector<std::pair<double, double>>& b) {
  DSPDEM_CHECK(!a.empty() && !b.empty(), "path_distance: an empty path");
  PathDistance d;
  for (const auto& p : a) {
    const double x = point_to_polyline(p, b);
    d.mean += x, d.hausdorff = std::max(d.hausdorff, x);
  }
  d.mean /= static_cast<double>(a.size());
  for (const auto& p : b) d.hausdorff = std::max(d.hausdorff, point_to_polyline(p, a));
  return d;
}

}  // namespace dspdem::report
