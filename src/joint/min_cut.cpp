#include "joint/min_cut.hpp"

#include <algorithm>
#include <limits>

#include "core/error.hpp"

namespace dspdem::joint {

std::vector<int> min_cut(int n, const std::vector<std::array<int, 2>>& edge, const std::vector<Real>& cap, int s,
                         int t) {
  const int ne = static_cast<int>(edge.size());
  std::vector<std::vector<int>> adj(static_cast<std::size_t>(n));  // edge ids at each vertex
  Real cmin = std::numeric_limits<Real>::infinity(), cmax = 0;
  for (int k = 0; k < ne; ++k) {
    DSPDEM_CHECK(cap[k] > 0, "internal: min_cut edge {} has capacity {} (must be > 0)", k, cap[k]);
    adj[edge[k][0]].push_back(k), adj[edge[k][1]].push_back(k);
    cmin = std::min(cmin, cap[k]), cmax = std::max(cmax, cap[k]);
  }
  // flow[k] runs from edge[k][0] to edge[k][1] (negative: the other way); what is left from
  // vertex u along edge k is cap - flow away from u. Below eps counts as saturated, so that
  // rounding in the augmentations (relative to the largest capacity) cannot leave a path
  // open by an ulp; but never as much as half the smallest capacity, so that no edge counts
  // as saturated before it carries flow.
  std::vector<Real> flow(static_cast<std::size_t>(ne), 0.0);
  const Real eps = ne > 0 ? std::min(1e-12 * cmax, 0.5 * cmin) : 0.0;
  auto residual = [&](int k, int from) { return cap[k] - (edge[k][0] == from ? flow[k] : -flow[k]); };
  std::vector<int> via(static_cast<std::size_t>(n));  // the edge a vertex was reached by
  auto reach = [&]() {  // breadth first from s over unsaturated edges; true when t is reached
    std::fill(via.begin(), via.end(), -2);
    via[s] = -1;
    std::vector<int> queue{s};
    for (std::size_t q = 0; q < queue.size(); ++q) {
      const int u = queue[q];
      for (int k : adj[u]) {
        const int v = edge[k][0] == u ? edge[k][1] : edge[k][0];
        if (via[v] != -2 || residual(k, u) <= eps) continue;
        via[v] = k;
        if (v == t) return true;
        queue.push_back(v);
      }
    }
    return false;
  };
  while (reach()) {
    Real push = std::numeric_limits<Real>::infinity();
    for (int v = t; v != s;) {
      const int k = via[v], u = edge[k][0] == v ? edge[k][1] : edge[k][0];
      push = std::min(push, residual(k, u));
      v = u;
    }
    for (int v = t; v != s;) {
      const int k = via[v], u = edge[k][0] == v ? edge[k][1] : edge[k][0];
      flow[k] += edge[k][0] == u ? push : -push;
      v = u;
    }
  }
  // The cut: edges from the vertices still reachable from s to the others (none when s and
  // t are apart: s's side then holds every edge it touches).
  std::vector<int> cut;
  for (int k = 0; k < ne; ++k)
    if ((via[edge[k][0]] != -2) != (via[edge[k][1]] != -2)) cut.push_back(k);
  return cut;
}

}  // namespace dspdem::joint
