// One process's share of a model: the elements it owns, every element that touches a node
// it owns, and the elements across its joints (one layer of ghosts), with their nodes.
//
// Ownership: an element belongs to the process METIS gave it; a node to the process of the
// first element (in global order) that uses it; a joint to the process of its first node.
// Each process computes the forces of all its elements and joints, so an own node gets
// exactly the terms, in exactly the order, of a one-process run (elements and joints keep
// their global order): its motion is the same to the bit on any number of processes. Joints
// and elements on the cut are computed on both sides, each side from the same positions,
// so their histories stay equal; each is counted (energies, frames) by its owner only.
#pragma once
#include <vector>

#include "time/model.hpp"

namespace dspdem::par {

struct Subdomain {
  Model local;                      ///< own nodes first, then ghosts; owned_nodes and masks set
  std::vector<Index> node_global;   ///< local node -> global node
  std::vector<Index> elem_global;   ///< local element -> global element
  std::vector<Index> joint_global;  ///< local joint -> global joint
  std::vector<int> ghost_owner;     ///< per ghost (local node owned_nodes + k): its process
  std::vector<int> elem_owner;      ///< per local element: its process
};

/// The share of process `rank` of the one-process model `global` under the element
/// partition `part`.
Subdomain make_subdomain(const Model& global, const std::vector<int>& part, int rank);

}  // namespace dspdem::par
