// Convex polytopes for contact: the skeletons of elements (tet4, hex8) and rigid boxes,
// as vertex positions plus a fixed topology per shape (edges with their two adjacent
// triangles, outward triangles, vertex neighbours). Hexahedron faces are split into two
// triangles each; the split diagonals are not edges (they are not features of the shape).
#pragma once
#include <array>
#include <vector>

#include "core/types.hpp"

namespace dspdem::contact {

struct Topology {
  int nv = 0, nf = 0;  ///< vertices, faces (a face is one triangle or a split quadrilateral)
  std::vector<std::array<int, 2>> edges;
  std::vector<std::array<int, 2>> edge_faces;  ///< the two faces sharing each edge
  std::vector<std::array<int, 3>> tris;        ///< outward (counter-clockwise seen from outside)
  std::vector<int> tri_face;                   ///< face of each triangle
  /// Per triangle: local vertex (0-2) opposite the split diagonal in the first triangle of a
  /// quadrilateral, whose barycentric may be zero (a point on the diagonal belongs to the
  /// first triangle); -1 otherwise.
  std::vector<int> tri_diag;
  std::vector<std::vector<int>> neighbours;    ///< per vertex: vertices joined to it by an edge
  std::vector<std::vector<int>> vertex_faces;  ///< per vertex: faces that contain it
};

// Segment: two vertices joined by one edge, no faces: the skeleton of a spherocylinder
// (a rigid cylinder wall is the segment of its axis dilated by its radius).
enum class Shape { Tet, Hex, Segment };
const Topology& topology(Shape s);

/// A convex polytope in its current position: at most 8 vertices.
struct Poly {
  const Topology* topo = nullptr;
  std::array<Vec3, 8> v;
  Vec3 centre() const;
};

}  // namespace dspdem::contact
