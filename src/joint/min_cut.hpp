// The least-capacity cut between two vertices of a small undirected graph: which closed faces
// around a node a crack front opens so that an opened face can open (time/extrinsic.cpp).
#pragma once
#include <array>
#include <vector>

#include "core/types.hpp"

namespace dspdem::joint {

/// Edges (u, v) of an undirected graph over vertices 0..n-1 with capacities cap > 0: the
/// edges of a cut separating s from t of least total capacity, ascending; empty when s and t
/// are not connected. Edmonds-Karp (shortest augmenting paths), deterministic: the graphs
/// here are a node's star (tens of vertices), where its O(V E^2) is nothing.
std::vector<int> min_cut(int n, const std::vector<std::array<int, 2>>& edge, const std::vector<Real>& cap, int s,
                         int t);

}  // namespace dspdem::joint
