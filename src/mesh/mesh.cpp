#include "mesh/mesh.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <limits>

#include "core/error.hpp"

namespace dspdem {

Index Mesh::n_elements() const {
  Index n = 0;
  for (const auto& b : blocks) n += b.size();
  return n;
}

const Group* Mesh::find_group(const std::string& name) const {
  for (const auto& g : groups)
    if (g.name == name) return &g;
  return nullptr;
}

std::string Mesh::group_names() const {
  std::string s;
  for (const auto& g : groups) s += (s.empty() ? "" : ", ") + g.name;
  return s.empty() ? "(none)" : s;
}

Real tet4_volume(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  return (b - a).cross(c - a).dot(d - a) / 6.0;
}

// Smallest corner Jacobian determinant of a trilinear hexahedron in gmsh order: at corner I
// with natural coordinates (a, b, c) the Jacobian's columns are a (X_I - X_xi) / 2,
// b (X_I - X_eta) / 2, c (X_I - X_zeta) / 2, the edges to its three neighbours. Negative
// or zero at some corner: the element is inverted or degenerate there.
Real hex8_min_corner_jacobian(const Vec3 (&X)[8]) {
  // gmsh: 0 (-,-,-) 1 (+,-,-) 2 (+,+,-) 3 (-,+,-), then 4-7 the same at zeta = +1.
  static const int sx[8] = {-1, 1, 1, -1, -1, 1, 1, -1}, sy[8] = {-1, -1, 1, 1, -1, -1, 1, 1},
                   sz[8] = {-1, -1, -1, -1, 1, 1, 1, 1};
  static const int nxi[8] = {1, 0, 3, 2, 5, 4, 7, 6}, neta[8] = {3, 2, 1, 0, 7, 6, 5, 4},
                   nzeta[8] = {4, 5, 6, 7, 0, 1, 2, 3};
  Real m = std::numeric_limits<Real>::infinity();
  for (int I = 0; I < 8; ++I) {
    const Vec3 a = 0.5 * sx[I] * (X[I] - X[nxi[I]]), b = 0.5 * sy[I] * (X[I] - X[neta[I]]),
               c = 0.5 * sz[I] * (X[I] - X[nzeta[I]]);
    m = std::min(m, a.dot(b.cross(c)));
  }
  return m;
}

void check_element_volumes(const Mesh& mesh) {
  for (const auto& blk : mesh.blocks) {
    const int npe = blk.npe();
    std::vector<std::size_t> bad;
    Index n_bad = 0;
    for (Index e = 0; e < blk.size(); ++e) {
      const Index* c = &blk.conn[static_cast<std::size_t>(e) * npe];
      bool ok = true;
      if (blk.type == CellType::Tet4) {
        const Real v =
            tet4_volume(node_pos(mesh.x, c[0]), node_pos(mesh.x, c[1]), node_pos(mesh.x, c[2]), node_pos(mesh.x, c[3]));
        // Relative threshold: a tet whose volume is a tiny fraction of its edge cube is degenerate.
        const Real h = (node_pos(mesh.x, c[1]) - node_pos(mesh.x, c[0])).norm();
        ok = v > 1e-12 * h * h * h;
      } else {
        Vec3 xe[8];
        for (int i = 0; i < 8; ++i) xe[i] = node_pos(mesh.x, c[i]);
        ok = hex8_min_corner_jacobian(xe) > 0.0;
      }
      if (!ok) {
        ++n_bad;
        if (bad.size() < 10) bad.push_back(blk.tag[e]);
      }
    }
    if (n_bad > 0) {
      std::string ids;
      for (auto t : bad) ids += (ids.empty() ? "" : ", ") + std::to_string(t);
      fail("mesh '{}': {} inverted or zero-volume {} element(s); first element tags: {}", mesh.source, n_bad,
           cell_name(blk.type), ids);
    }
  }
}

}  // namespace dspdem

namespace dspdem {
Vec3 element_centroid(const Mesh& mesh, const ElementBlock& blk, Index e) {
  const int npe = blk.npe();
  Vec3 c = Vec3::Zero();
  for (int k = 0; k < npe; ++k) c += node_pos(mesh.x, blk.conn[static_cast<std::size_t>(e) * npe + k]);
  return c / npe;
}

Real element_volume(const Mesh& mesh, const ElementBlock& blk, Index e) {
  const Index* c = &blk.conn[static_cast<std::size_t>(e) * blk.npe()];
  auto P = [&](int i) { return node_pos(mesh.x, c[i]); };
  if (blk.type == CellType::Tet4) return tet4_volume(P(0), P(1), P(2), P(3));
  const int t[6][4] = {{0, 1, 2, 6}, {0, 2, 3, 6}, {0, 3, 7, 6}, {0, 7, 4, 6}, {0, 4, 5, 6}, {0, 5, 1, 6}};
  Real v = 0;
  for (const auto& q : t) v += tet4_volume(P(q[0]), P(q[1]), P(q[2]), P(q[3]));
  return v;
}
}  // namespace dspdem
