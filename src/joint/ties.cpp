#include "joint/ties.hpp"

#include <numeric>

namespace dspdem::joint {

namespace {
// Union-find whose root is always the smallest node of its set, so that the result does not
// depend on the order the pairs are joined in.
Index root(std::vector<Index>& parent, Index i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}
}  // namespace

Ties build_ties(const JointSet& js, Index n_nodes) {
  std::vector<Index> parent(static_cast<std::size_t>(n_nodes));
  std::iota(parent.begin(), parent.end(), Index{0});
  for (Index j = 0; j < static_cast<Index>(js.closed.size()); ++j) {
    if (!js.closed[j]) continue;
    for (int k = 0; k < js.npf[j]; ++k) {
      const Index ra = root(parent, js.a[4 * static_cast<std::size_t>(j) + k]);
      const Index rb = root(parent, js.b[4 * static_cast<std::size_t>(j) + k]);
      if (ra != rb) parent[std::max(ra, rb)] = std::min(ra, rb);
    }
  }
  Ties t;
  t.group.assign(static_cast<std::size_t>(n_nodes), -1);
  std::vector<Index> size(static_cast<std::size_t>(n_nodes), 0);
  for (Index i = 0; i < n_nodes; ++i) ++size[root(parent, i)];
  // Groups in the order of their roots (smallest nodes); members ascending.
  std::vector<Index> id(static_cast<std::size_t>(n_nodes), -1);
  t.ptr.assign(1, 0);
  for (Index i = 0; i < n_nodes; ++i)
    if (parent[i] == i && size[i] > 1) {
      id[i] = t.groups();
      t.ptr.push_back(t.ptr.back() + size[i]);
    }
  t.node.resize(static_cast<std::size_t>(t.ptr.back()));
  std::vector<Index> fill(t.ptr.begin(), t.ptr.end() - 1);
  for (Index i = 0; i < n_nodes; ++i) {
    const Index g = id[root(parent, i)];
    if (g < 0) continue;
    t.group[i] = g;
    t.node[fill[g]++] = i;
  }
  return t;
}

}  // namespace dspdem::joint
