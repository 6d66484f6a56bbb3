// The least s-t cut (joint/min_cut.hpp) that frees an extrinsic crack front: against cuts
// found by hand and against every edge subset of small random graphs.
#include <gtest/gtest.h>

#include <random>

#include "joint/min_cut.hpp"

using namespace dspdem;
using namespace dspdem::joint;

namespace {
// Whether t is reachable from s over the edges not in `removed` (a bit per edge).
bool connected(int n, const std::vector<std::array<int, 2>>& edge, unsigned removed, int s, int t) {
  std::vector<char> seen(static_cast<std::size_t>(n), 0);
  std::vector<int> stack{s};
  seen[s] = 1;
  while (!stack.empty()) {
    const int u = stack.back();
    stack.pop_back();
    for (std::size_t k = 0; k < edge.size(); ++k) {
      if (removed >> k & 1u) continue;
      for (int side : {0, 1})
        if (edge[k][side] == u && !seen[edge[k][1 - side]])
          seen[edge[k][1 - side]] = 1, stack.push_back(edge[k][1 - side]);
    }
  }
  return seen[t];
}
}  // namespace

TEST(MinCut, TwoPathsAreCutAtTheirCheapestEdges) {
  // s = 0 to t = 3 along 0-1-3 (capacities 1, 5) and 0-2-3 (4, 2): the cut is {0-1, 2-3}.
  const std::vector<std::array<int, 2>> e{{0, 1}, {1, 3}, {0, 2}, {2, 3}};
  EXPECT_EQ(min_cut(4, e, {1, 5, 4, 2}, 0, 3), (std::vector<int>{0, 3}));
}

TEST(MinCut, ARingAroundANodeIsCutOnEachSide) {
  // A node's star seen from its link: six element corners in a ring, the opened face between
  // corners 0 and 5 already gone. Separating 0 from 5 takes one face on the ring's only path;
  // it is the one nearest its onset (cheapest).
  const std::vector<std::array<int, 2>> e{{0, 1}, {1, 2}, {2, 3}, {3, 4}, {4, 5}};
  EXPECT_EQ(min_cut(6, e, {0.9, 0.4, 0.05, 0.3, 0.7}, 0, 5), (std::vector<int>{2}));
  // With a centre corner 6 tied to all, every path through it must be cut too: the cheapest is
  // to cut corner 5 off (4-5 and 5-6, 0.9), against corner 0 (1.0) or a ring face and spokes
  // (2-3 and three spokes at least 2.15).
  std::vector<std::array<int, 2>> w = e;
  for (int v = 0; v < 6; ++v) w.push_back({v, 6});
  const std::vector<int> cut = min_cut(7, w, {0.9, 0.4, 0.05, 0.3, 0.7, 0.1, 1, 1, 1, 1, 0.2}, 0, 5);
  EXPECT_EQ(cut, (std::vector<int>{4, 10}));
}

TEST(MinCut, NothingToCutWhenTheSidesAreApart) {
  const std::vector<std::array<int, 2>> e{{0, 1}, {2, 3}};
  EXPECT_TRUE(min_cut(4, e, {1, 1}, 0, 3).empty());
}

TEST(MinCut, MatchesTheLeastOfAllEdgeSubsetsOnRandomGraphs) {
  // 200 random graphs of 6 vertices and 10 edges (2^10 subsets each, all tried): the cut
  // returned separates s from t and its capacity is the least of any subset that does.
  // Capacities are drawn from 1..100 in whole numbers, so sums compare exactly.
  std::mt19937 rng(20261127);
  std::uniform_int_distribution<int> vertex(0, 5), capacity(1, 100);
  for (int g = 0; g < 200; ++g) {
    std::vector<std::array<int, 2>> e;
    std::vector<Real> c;
    while (e.size() < 10) {
      const int u = vertex(rng), v = vertex(rng);
      if (u == v) continue;
      e.push_back({u, v}), c.push_back(capacity(rng));
    }
    const int s = 0, t = 5;
    Real best = -1;
    for (unsigned m = 0; m < (1u << e.size()); ++m) {
      if (connected(6, e, m, s, t)) continue;
      Real sum = 0;
      for (std::size_t k = 0; k < e.size(); ++k)
        if (m >> k & 1u) sum += c[k];
      if (best < 0 || sum < best) best = sum;
    }
    const std::vector<int> cut = min_cut(6, e, c, s, t);
    if (!connected(6, e, 0, s, t)) {
      EXPECT_TRUE(cut.empty()) << "graph " << g;
      continue;
    }
    unsigned removed = 0;
    Real sum = 0;
    for (int k : cut) removed |= 1u << k, sum += c[k];
    EXPECT_FALSE(connected(6, e, removed, s, t)) << "graph " << g;
    EXPECT_EQ(sum, best) << "graph " << g;
  }
}
