// Fragments: connected sets of elements, through shared nodes and through joints that have
// not failed (union-find). A fragment's id is the smallest element tag (the mesh file's
// element number) in it, so the id (and the colour drawn from it) of a piece stays the same
// while other pieces split off, whatever order the elements are kept in.
#pragma once
#include <vector>

#include "joint/joint_set.hpp"
#include "mesh/mesh.hpp"

namespace dspdem::joint {

struct Fragments {
  std::vector<Index> id;  ///< per global element
  Index count = 0;
  std::vector<Real> mass;  ///< per fragment, largest first
};

/// `elem_mass` per global element.
Fragments find_fragments(const Mesh& mesh, const JointSet& js, const std::vector<Real>& elem_mass);

/// One fragment described for output: where it is and how heavy.
struct FragmentInfo {
  Index id = 0;  ///< as in Fragments::id (smallest element tag in it)
  Real mass = 0;
  Index elements = 0;
  Vec3 centroid = Vec3::Zero();  ///< mass-weighted mean of its elements' node averages at `x`
};

/// The fragments of `fr`, largest mass first (ties: smaller id first), at positions `x`
/// (3 per node, as Mesh::x).
std::vector<FragmentInfo> describe_fragments(const Mesh& mesh, const Fragments& fr, const Real* x,
                                             const std::vector<Real>& elem_mass);

}  // namespace dspdem::joint
