// Scenes for contact tests: several box meshes in one mesh, each a volume group of its own
// ("b0", "b1", ...), placed and rotated in code.
#pragma once
#include <string>
#include <utility>

#include "support/box_mesh.hpp"

namespace dspdem::testsupport {

/// Appends `src` to `dst` rotated by Q about src's centre `c`, then moved so that centre
/// lands on `at`; its volume group is named `name`. The "all" group of dst grows too.
inline void add_part(Mesh& dst, const Mesh& src, const std::string& name, const Vec3& c, const Vec3& at,
                     const Mat3& Q = Mat3::Identity()) {
  const Index n0 = dst.n_nodes();
  for (Index n = 0; n < src.n_nodes(); ++n) {
    const Vec3 p = at + Q * (node_pos(src.x, n) - c);
    for (int d = 0; d < 3; ++d) dst.x.push_back(p(d));
    dst.node_tag.push_back(dst.node_tag.size() + 1);
  }
  if (dst.blocks.empty()) dst.blocks = {ElementBlock{CellType::Tet4, {}, {}}, ElementBlock{CellType::Hex8, {}, {}}};
  Group g;
  g.name = name;
  g.dim = 3;
  g.elements.resize(2);
  for (std::size_t b = 0; b < 2; ++b) {
    auto& db = dst.blocks[b];
    for (Index e = 0; e < src.blocks[b].size(); ++e) {
      g.elements[b].push_back(db.size());
      for (int i = 0; i < db.npe(); ++i) db.conn.push_back(n0 + src.blocks[b].conn[e * db.npe() + i]);
      db.tag.push_back(db.tag.size() + 1 + (b == 1 ? 1000000 : 0));
    }
  }
  for (Index n = 0; n < src.n_nodes(); ++n) g.nodes.push_back(n0 + n);
  dst.groups.push_back(g);
  Group* all = nullptr;
  for (auto& gg : dst.groups)
    if (gg.name == "all") all = &gg;
  if (!all) {
    dst.groups.push_back(Group{"all", 3, {}, {{}, {}}, {}, {}});
    all = &dst.groups.back();
  }
  for (std::size_t b = 0; b < 2; ++b)
    all->elements[b].insert(all->elements[b].end(), g.elements[b].begin(), g.elements[b].end());
  all->nodes.insert(all->nodes.end(), g.nodes.begin(), g.nodes.end());
}

/// One tetrahedron with its vertex 0 at the origin pointing down (-z), or up (+z), its
/// opposite face at |z| = h, spanning 2s.
inline Mesh tip_tet(Real s, Real h, bool up = false) {
  Mesh m;
  m.source = "tip_tet";
  const Real z = up ? -h : h;
  const Vec3 p[4] = {Vec3(0, 0, 0), Vec3(-s, -s, z), Vec3(s, -s, z), Vec3(0, s, z)};
  for (const Vec3& q : p) m.x.insert(m.x.end(), {q(0), q(1), q(2)}), m.node_tag.push_back(m.node_tag.size() + 1);
  ElementBlock tets{CellType::Tet4, {0, 1, 2, 3}, {1}};
  if (tet4_volume(p[0], p[1], p[2], p[3]) < 0) std::swap(tets.conn[2], tets.conn[3]);
  m.blocks = {tets, ElementBlock{CellType::Hex8, {}, {}}};
  return m;
}

/// A cube of side a meshed as n^3 cells (hex8, or 6 tet4 per cell), centred at the origin.
inline Mesh cube(CellType t, int n, Real a) { return box_mesh(t, n, n, n, Vec3(a, a, a)); }

}  // namespace dspdem::testsupport
