// Fragments: connected sets of elements, through shared nodes and through joints that have
// not failed (union-find). A fragment's id is the smallest global element id in it, so the
// id (and the colour drawn from it) of a piece stays the same while other pieces split off.
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

}  // namespace dspdem::joint
