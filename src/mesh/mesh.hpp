// Mesh: flat node coordinates, one ElementBlock per cell type, and named physical groups.
#pragma once
#include <string>
#include <vector>

#include "core/types.hpp"

namespace dspdem {

enum class CellType : int { Tet4 = 0, Hex8 = 1 };

constexpr int nodes_per_cell(CellType t) { return t == CellType::Tet4 ? 4 : 8; }
inline const char* cell_name(CellType t) { return t == CellType::Tet4 ? "tet4" : "hex8"; }

/// All cells of one type. Connectivity is n x nodes_per_cell, row-major, 0-based node indices.
struct ElementBlock {
  CellType type = CellType::Tet4;
  std::vector<Index> conn;
  std::vector<std::size_t> tag;  ///< original (gmsh) element tag, used in messages
  Index size() const { return static_cast<Index>(tag.size()); }
  int npe() const { return nodes_per_cell(type); }
};

/// A named physical group. Volume groups (dim 3) list elements per block; lower-dimensional
/// groups list nodes and, for surfaces, their boundary faces (for distributing loads).
struct Group {
  std::string name;
  int dim = 0;
  std::vector<Index> nodes;                  ///< sorted, unique
  std::vector<std::vector<Index>> elements;  ///< dim 3: per block, element indices
  std::vector<Index> tri;                    ///< dim 2: triangles, 3 node indices each
  std::vector<Index> quad;                   ///< dim 2: quadrilaterals, 4 node indices each
};

struct Mesh {
  std::string source;                 ///< file it came from, for messages
  std::vector<Real> x;                ///< 3 x n_nodes, xyz interleaved
  std::vector<std::size_t> node_tag;  ///< original node tags
  std::vector<ElementBlock> blocks;
  std::vector<Group> groups;

  Index n_nodes() const { return static_cast<Index>(node_tag.size()); }
  Index n_elements() const;
  const Group* find_group(const std::string& name) const;
  /// Names of all groups, comma separated (for messages).
  std::string group_names() const;
};

/// Signed volume of every element; throws Error naming the first inverted or degenerate
/// elements (by tag) of the mesh.
void check_element_volumes(const Mesh& mesh);

/// Smallest Jacobian determinant over the eight corners of a trilinear hexahedron (gmsh
/// node order); the element is valid when it is positive.
Real hex8_min_corner_jacobian(const Vec3 (&X)[8]);

/// Volume of a tet4 from its four corner positions (positive for gmsh's orientation).
Real tet4_volume(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d);

/// Nodal position as a Vec3.
inline Vec3 node_pos(const std::vector<Real>& x, Index i) { return {x[3 * i], x[3 * i + 1], x[3 * i + 2]}; }

}  // namespace dspdem

namespace dspdem {
/// Nodal position from a raw coordinate array.
inline Vec3 node_pos_ptr(const Real* x, Index i) { return {x[3 * i], x[3 * i + 1], x[3 * i + 2]}; }
}  // namespace dspdem

namespace dspdem {
/// Volume of element e of a block at the mesh's coordinates (hex8: 6-tet split).
Real element_volume(const Mesh& mesh, const ElementBlock& blk, Index e);
/// Mean of element e's node positions (its centroid for a tet; the mean of its corners for a hex).
Vec3 element_centroid(const Mesh& mesh, const ElementBlock& blk, Index e);
}  // namespace dspdem
