#include "mesh/mesh.hpp"

#include <Eigen/Dense>
#include <algorithm>

#include "core/error.hpp"
#include "fem/hex8.hpp"

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
        Eigen::Matrix<Real, 3, 8> xe;
        for (int i = 0; i < 8; ++i) xe.col(i) = node_pos(mesh.x, c[i]);
        ok = hex8::min_corner_jacobian(xe) > 0.0;
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
