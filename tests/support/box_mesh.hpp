// Structured box meshes built in code for unit and verification tests (no gmsh needed):
// nx x ny x nz cells of hex8, or each cell split into 6 tet4 (Kuhn split, conforming).
// Groups: "all" (volume), "xmin" ... "zmax" (boundary faces, as quads).
#pragma once
#include <random>

#include "mesh/mesh.hpp"

namespace dspdem::testsupport {

inline Mesh box_mesh(CellType type, int nx, int ny, int nz, Vec3 size, Real distort = 0.0, unsigned seed = 1) {
  Mesh m;
  m.source = "box_mesh";
  auto id = [&](int i, int j, int k) { return static_cast<Index>(i + (nx + 1) * (j + (ny + 1) * k)); };
  std::mt19937 rng(seed);
  std::uniform_real_distribution<Real> U(-1.0, 1.0);
  const Vec3 h(size(0) / nx, size(1) / ny, size(2) / nz);
  for (int k = 0; k <= nz; ++k)
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i) {
        Vec3 p(i * h(0), j * h(1), k * h(2));
        const bool interior = i > 0 && i < nx && j > 0 && j < ny && k > 0 && k < nz;
        if (interior && distort > 0)
          for (int d = 0; d < 3; ++d) p(d) += distort * h(d) * U(rng);
        for (int d = 0; d < 3; ++d) m.x.push_back(p(d));
        m.node_tag.push_back(m.node_tag.size() + 1);
      }
  ElementBlock tets{CellType::Tet4, {}, {}}, hexes{CellType::Hex8, {}, {}};
  std::size_t tag = 1;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        const Index c[8] = {id(i, j, k),     id(i + 1, j, k),     id(i + 1, j + 1, k),     id(i, j + 1, k),
                            id(i, j, k + 1), id(i + 1, j, k + 1), id(i + 1, j + 1, k + 1), id(i, j + 1, k + 1)};
        if (type == CellType::Hex8) {
          hexes.conn.insert(hexes.conn.end(), c, c + 8);
          hexes.tag.push_back(tag++);
          continue;
        }
        // Kuhn split: paths 000 -> 111 along the axes in every order.
        const int perm[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
        for (const auto& p : perm) {
          int b[3] = {0, 0, 0};
          Index t[4];
          auto corner = [&]() { return id(i + b[0], j + b[1], k + b[2]); };
          t[0] = corner();
          for (int s = 0; s < 3; ++s) b[p[s]] = 1, t[s + 1] = corner();
          if (tet4_volume(node_pos(m.x, t[0]), node_pos(m.x, t[1]), node_pos(m.x, t[2]), node_pos(m.x, t[3])) < 0)
            std::swap(t[2], t[3]);
          tets.conn.insert(tets.conn.end(), t, t + 4);
          tets.tag.push_back(tag++);
        }
      }
  m.blocks.push_back(std::move(tets));
  m.blocks.push_back(std::move(hexes));
  Group all;
  all.name = "all";
  all.dim = 3;
  all.elements.resize(2);
  for (std::size_t b = 0; b < 2; ++b)
    for (Index e = 0; e < m.blocks[b].size(); ++e) all.elements[b].push_back(e);
  for (Index n = 0; n < m.n_nodes(); ++n) all.nodes.push_back(n);
  m.groups.push_back(all);
  const int n[3] = {nx, ny, nz};
  const char* names[3][2] = {{"xmin", "xmax"}, {"ymin", "ymax"}, {"zmin", "zmax"}};
  for (int ax = 0; ax < 3; ++ax)
    for (int side = 0; side < 2; ++side) {
      Group g;
      g.name = names[ax][side];
      g.dim = 2;
      const int a1 = (ax + 1) % 3, a2 = (ax + 2) % 3;
      auto nid = [&](int u, int w) {
        int ijk[3];
        ijk[ax] = side ? n[ax] : 0, ijk[a1] = u, ijk[a2] = w;
        return id(ijk[0], ijk[1], ijk[2]);
      };
      for (int u = 0; u <= n[a1]; ++u)
        for (int w = 0; w <= n[a2]; ++w) g.nodes.push_back(nid(u, w));
      for (int u = 0; u < n[a1]; ++u)
        for (int w = 0; w < n[a2]; ++w) {
          const Index q[4] = {nid(u, w), nid(u + 1, w), nid(u + 1, w + 1), nid(u, w + 1)};
          g.quad.insert(g.quad.end(), q, q + 4);
        }
      std::sort(g.nodes.begin(), g.nodes.end());
      m.groups.push_back(g);
    }
  check_element_volumes(m);
  return m;
}

}  // namespace dspdem::testsupport
