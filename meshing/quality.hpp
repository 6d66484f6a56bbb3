// Mesh quality figures for `dspdem mesh` (quality.json).
//   tet4: gamma = 3 r_in / R_circ (1 for the regular tetrahedron, 0 for a flat one; the
//         measure gmsh calls "gamma"), and the six dihedral angles;
//   hex8: scaled Jacobian = min over corners of det[e1 e2 e3] / (|e1||e2||e3|) (1 for a
//         cube), and the dihedral angles at the twelve edges.
// A "sliver" is a tetrahedron with gamma below 0.1.
#pragma once
#include <map>
#include <string>

#include "mesh/mesh.hpp"

namespace dspdem::meshing {

struct Quality {
  std::map<std::string, Index> elements_per_group;  ///< volume groups
  Index n_tet4 = 0, n_hex8 = 0;
  double min_dihedral_deg = 180, max_dihedral_deg = 0;
  double quality_min = 1, quality_p01 = 1, quality_mean = 1;  ///< gamma (tets) / scaled Jacobian (hexes)
  Index n_slivers = 0;
  double sliver_threshold = 0.1;
};

Quality mesh_quality(const Mesh& m);
std::string quality_json(const Quality& q, const std::string& extra_fields = "");

/// gamma = 3 r_in / R_circ of a tetrahedron.
double tet_gamma(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d);

}  // namespace dspdem::meshing
