// Nodes tied through closed faces: the kinematics of extrinsic insertion (issue 20).
//
// A body with extrinsic joints is set up as with intrinsic ones (every face between its
// elements gets a joint and its own copy of each node), but a face's joint stays closed
// until the traction on it reaches the strength: while it is closed, the node pairs across
// it are one node. The copies joined this way, directly or through other closed faces, form
// a group that moves as one point: the integrator moves every copy of a group with the
// group's summed force and inverse mass, so that all keep the same position and velocity to
// the bit (time/integrator.cpp; its fused step keeps the sum at the group's first copy
// only). A closed joint applies no force, so it adds no compliance: its penalty acts only
// once it is open (a run's step falls as joints open, joint_dt.hpp), and can be low,
// where an intrinsic joint's must be high. Opening joints splits the groups of their nodes
// where no closed face joins the copies any more: a crack frees a node only once it has cut
// all the way around it.
#pragma once
#include <vector>

#include "joint/joint_set.hpp"

namespace dspdem::joint {

struct Ties {
  std::vector<Index> group;      ///< per node: its group, or -1 when it is tied to no other
  std::vector<Index> ptr, node;  ///< each group's nodes, ascending (CSR over groups)
  Index groups() const { return ptr.empty() ? 0 : static_cast<Index>(ptr.size()) - 1; }
};

/// The groups of the nodes joined by the node pairs (a[k], b[k]) of the closed joints
/// (js.closed[j] != 0; none when closed is empty), over n_nodes nodes. Deterministic: groups
/// are numbered in the order of their smallest node.
Ties build_ties(const JointSet& js, Index n_nodes);

}  // namespace dspdem::joint
