// Fragments of a distributed run: a union-find on each process's share, then labels made
// equal over the copies of each element (its owner's and the ghosts') until no label
// changes anywhere. Every connection (a shared node, an intact joint) is seen whole on at
// least one process, so the pieces are the one-process run's, named alike (smallest
// element tag), whatever the number of processes.
#pragma once
#include <vector>

#include "joint/fragments.hpp"
#include "par/halo.hpp"
#include "time/model.hpp"

namespace dspdem::par {

struct DistributedFragments {
  joint::Fragments fr;                    ///< id per local element; count and masses whole
  std::vector<joint::FragmentInfo> info;  ///< whole, largest first, the same on every process
};

/// Collective. `m` is the share (owned masks set), `elem_mass` per local element, `x` the
/// share's positions.
DistributedFragments find_fragments(const Model& m, MpiHalo& halo, const std::vector<Real>& elem_mass, const Real* x);

}  // namespace dspdem::par
