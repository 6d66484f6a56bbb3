#include "meshing/quality.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "fem/hex8.hpp"

namespace dspdem::meshing {

double tet_gamma(const Vec3& p0, const Vec3& p1, const Vec3& p2, const Vec3& p3) {
  const Vec3 a = p1 - p0, b = p2 - p0, c = p3 - p0;
  const double V = std::abs(a.cross(b).dot(c)) / 6.0;
  const double A = 0.5 * (a.cross(b).norm() + b.cross(c).norm() + c.cross(a).norm() + (p2 - p1).cross(p3 - p1).norm());
  if (V <= 0 || A <= 0) return 0.0;
  const double r_in = 3 * V / A;
  const double R =
      (a.squaredNorm() * b.cross(c) + b.squaredNorm() * c.cross(a) + c.squaredNorm() * a.cross(b)).norm() / (12 * V);
  return 3 * r_in / R;
}

namespace {
double angle_deg(const Vec3& n1, const Vec3& n2) {
  // Dihedral angle between two faces with outward normals n1, n2.
  const double c = std::clamp(n1.normalized().dot(n2.normalized()), -1.0, 1.0);
  return 180.0 - std::acos(c) * 180.0 / M_PI;
}
}  // namespace

Quality mesh_quality(const Mesh& m) {
  Quality q;
  std::vector<double> qual;
  for (const auto& g : m.groups)
    if (g.dim == 3) {
      Index n = 0;
      for (const auto& e : g.elements) n += static_cast<Index>(e.size());
      q.elements_per_group[g.name] = n;
    }
  for (const auto& blk : m.blocks) {
    const int npe = blk.npe();
    for (Index e = 0; e < blk.size(); ++e) {
      const Index* c = &blk.conn[static_cast<std::size_t>(e) * npe];
      if (blk.type == CellType::Tet4) {
        ++q.n_tet4;
        Vec3 p[4];
        for (int i = 0; i < 4; ++i) p[i] = node_pos(m.x, c[i]);
        const double g = tet_gamma(p[0], p[1], p[2], p[3]);
        qual.push_back(g);
        if (g < q.sliver_threshold) ++q.n_slivers;
        // Outward normal of the face opposite vertex i.
        Vec3 n[4];
        for (int i = 0; i < 4; ++i) {
          const Vec3 &a = p[(i + 1) % 4], &b = p[(i + 2) % 4], &d = p[(i + 3) % 4];
          n[i] = (b - a).cross(d - a);
          if (n[i].dot(p[i] - a) > 0) n[i] = -n[i];
        }
        for (int i = 0; i < 4; ++i)
          for (int j = i + 1; j < 4; ++j) {
            const double ang = angle_deg(n[i], n[j]);
            q.min_dihedral_deg = std::min(q.min_dihedral_deg, ang);
            q.max_dihedral_deg = std::max(q.max_dihedral_deg, ang);
          }
      } else {
        ++q.n_hex8;
        Vec3 p[8];
        for (int i = 0; i < 8; ++i) p[i] = node_pos(m.x, c[i]);
        // Corner neighbours in gmsh order: along xi, eta, zeta.
        static const int nb[8][3] = {{1, 3, 4}, {0, 2, 5}, {3, 1, 6}, {2, 0, 7},
                                     {5, 7, 0}, {4, 6, 1}, {7, 5, 2}, {6, 4, 3}};
        double sj = 1;
        for (int i = 0; i < 8; ++i) {
          const Vec3 e1 = p[nb[i][0]] - p[i], e2 = p[nb[i][1]] - p[i], e3 = p[nb[i][2]] - p[i];
          // The edges point along -+xi, -+eta, -+zeta: their handedness is -(n_xi n_eta n_zeta).
          const Vec3 nc = hex8::natural_coords().col(i);
          const double hand = -nc(0) * nc(1) * nc(2);
          sj = std::min(sj, hand * e1.cross(e2).dot(e3) / (e1.norm() * e2.norm() * e3.norm()));
        }
        qual.push_back(sj);
        // Faces: outward normals from the diagonals' cross product.
        static const int f[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {2, 3, 7, 6}, {1, 2, 6, 5}, {0, 4, 7, 3}};
        Vec3 centre = Vec3::Zero();
        for (auto& pi : p) centre += pi / 8;
        Vec3 n[6];
        for (int k = 0; k < 6; ++k) {
          n[k] = (p[f[k][2]] - p[f[k][0]]).cross(p[f[k][3]] - p[f[k][1]]);
          if (n[k].dot(p[f[k][0]] - centre) < 0) n[k] = -n[k];
        }
        // Adjacent face pairs share two nodes.
        for (int a = 0; a < 6; ++a)
          for (int b = a + 1; b < 6; ++b) {
            int shared = 0;
            for (int i = 0; i < 4; ++i)
              for (int j = 0; j < 4; ++j) shared += f[a][i] == f[b][j];
            if (shared != 2) continue;
            const double ang = angle_deg(n[a], n[b]);
            q.min_dihedral_deg = std::min(q.min_dihedral_deg, ang);
            q.max_dihedral_deg = std::max(q.max_dihedral_deg, ang);
          }
      }
    }
  }
  if (!qual.empty()) {
    std::sort(qual.begin(), qual.end());
    q.quality_min = qual.front();
    q.quality_p01 = qual[static_cast<std::size_t>(0.01 * static_cast<double>(qual.size() - 1))];
    double s = 0;
    for (double v : qual) s += v;
    q.quality_mean = s / static_cast<double>(qual.size());
  }
  return q;
}

std::string quality_json(const Quality& q, const std::string& extra) {
  std::string groups;
  for (const auto& [k, v] : q.elements_per_group)
    groups += fmt::format("{}\"{}\": {}", groups.empty() ? "" : ", ", k, v);
  return fmt::format(
      "{{\n{}  \"elements_per_group\": {{{}}},\n  \"tet4\": {},\n  \"hex8\": {},\n  \"min_dihedral_deg\": {:.4f},\n"
      "  \"max_dihedral_deg\": {:.4f},\n  \"quality_measure\": \"tet4: gamma = 3 r_in / R_circ; hex8: scaled "
      "Jacobian\",\n"
      "  \"quality_min\": {:.6f},\n  \"quality_p01\": {:.6f},\n  \"quality_mean\": {:.6f},\n  \"sliver_threshold\": "
      "{},\n"
      "  \"slivers\": {}\n}}\n",
      extra, groups, q.n_tet4, q.n_hex8, q.min_dihedral_deg, q.max_dihedral_deg, q.quality_min, q.quality_p01,
      q.quality_mean, q.sliver_threshold, q.n_slivers);
}

}  // namespace dspdem::meshing
