#include "contact/polytope.hpp"

#include <algorithm>
#include <map>

#include "joint/joint_set.hpp"

namespace dspdem::contact {

namespace {
// Triangles and edges from the outward faces of a cell; quads are split along 0-2.
Topology make(CellType t) {
  Topology tp;
  tp.nv = nodes_per_cell(t);
  std::map<std::array<int, 2>, std::vector<int>> edge_faces;
  tp.vertex_faces.resize(tp.nv);
  for (const auto& f : joint::cell_faces(t)) {
    const int n = static_cast<int>(f.size());
    const int face = tp.nf++;
    if (n == 3) {
      tp.tris.push_back({f[0], f[1], f[2]}), tp.tri_face.push_back(face), tp.tri_diag.push_back(-1);
    } else {
      // Diagonal 0-2: opposite local vertex 1 in (0, 1, 2).
      tp.tris.push_back({f[0], f[1], f[2]}), tp.tri_face.push_back(face), tp.tri_diag.push_back(1);
      tp.tris.push_back({f[0], f[2], f[3]}), tp.tri_face.push_back(face), tp.tri_diag.push_back(-1);
    }
    for (int k = 0; k < n; ++k) {
      const int a = f[k], b = f[(k + 1) % n];
      edge_faces[{std::min(a, b), std::max(a, b)}].push_back(face);
      tp.vertex_faces[a].push_back(face);
    }
  }
  tp.neighbours.resize(tp.nv);
  for (const auto& [e, fs] : edge_faces) {
    tp.edges.push_back(e);
    tp.edge_faces.push_back({fs.at(0), fs.at(1)});
    tp.neighbours[e[0]].push_back(e[1]);
    tp.neighbours[e[1]].push_back(e[0]);
  }
  return tp;
}

Topology make_segment() {
  Topology tp;
  tp.nv = 2;
  tp.edges = {{0, 1}};
  tp.edge_faces = {{-1, -1}};
  tp.neighbours = {{1}, {0}};
  tp.vertex_faces.resize(2);
  return tp;
}
}  // namespace

const Topology& topology(Shape s) {
  static const Topology tet = make(CellType::Tet4), hex = make(CellType::Hex8), seg = make_segment();
  return s == Shape::Tet ? tet : s == Shape::Hex ? hex : seg;
}

Vec3 Poly::centre() const {
  Vec3 c = Vec3::Zero();
  for (int i = 0; i < topo->nv; ++i) c += v[i];
  return c / topo->nv;
}

}  // namespace dspdem::contact
