#include "joint/fragments.hpp"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <map>
#include <numeric>

#include "core/error.hpp"

namespace dspdem::joint {

Fragments find_fragments(const Mesh& mesh, const JointSet& js, const std::vector<Real>& elem_mass) {
  const Index ne = mesh.n_elements();
  std::vector<Index> parent(ne);
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](Index i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  auto unite = [&](Index a, Index b) {
    a = find(a), b = find(b);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);
  };
  // Shared nodes: every element meets the first element seen at each of its nodes.
  std::vector<Index> first(mesh.n_nodes(), -1);
  Index g = 0;
  for (const auto& b : mesh.blocks)
    for (Index e = 0; e < b.size(); ++e, ++g)
      for (int i = 0; i < b.npe(); ++i) {
        Index& f = first[b.conn[static_cast<std::size_t>(e) * b.npe() + i]];
        if (f < 0)
          f = g;
        else
          unite(f, g);
      }
  for (Index j = 0; j < js.size(); ++j)
    if (js.status[j] != JointStatus::Broken) unite(js.ea[j], js.eb[j]);
  // Each set named by the smallest mesh-file tag in it: the name of a piece then depends on
  // the mesh alone, not on the order the elements are kept in memory (mesh/locality.hpp).
  std::vector<std::size_t> min_tag(static_cast<std::size_t>(ne), SIZE_MAX);
  g = 0;
  for (const auto& b : mesh.blocks)
    for (Index e = 0; e < b.size(); ++e, ++g) {
      DSPDEM_CHECK(b.tag[e] <= static_cast<std::size_t>(std::numeric_limits<Index>::max()),
                   "element tag {} is too large to name a fragment", b.tag[e]);
      std::size_t& t = min_tag[find(g)];
      t = std::min(t, b.tag[e]);
    }
  Fragments fr;
  fr.id.resize(ne);
  std::map<Index, Real> mass;
  for (Index e = 0; e < ne; ++e) {
    fr.id[e] = static_cast<Index>(min_tag[find(e)]);
    mass[fr.id[e]] += elem_mass[e];
  }
  fr.count = static_cast<Index>(mass.size());
  for (auto& [id, m] : mass) fr.mass.push_back(m);
  std::sort(fr.mass.rbegin(), fr.mass.rend());
  return fr;
}

std::vector<FragmentInfo> describe_fragments(const Mesh& mesh, const Fragments& fr, const Real* x,
                                             const std::vector<Real>& elem_mass) {
  std::map<Index, FragmentInfo> by_id;  // ordered by id: the sums below run in a fixed order
  Index g = 0;
  for (const auto& b : mesh.blocks)
    for (Index e = 0; e < b.size(); ++e, ++g) {
      Vec3 c = Vec3::Zero();
      for (int i = 0; i < b.npe(); ++i) {
        const Index n = b.conn[static_cast<std::size_t>(e) * b.npe() + i];
        c += Vec3(x[3 * n], x[3 * n + 1], x[3 * n + 2]);
      }
      FragmentInfo& f = by_id[fr.id[g]];
      f.id = fr.id[g];
      f.mass += elem_mass[g];
      f.centroid += elem_mass[g] * c / b.npe();
      ++f.elements;
    }
  std::vector<FragmentInfo> out;
  out.reserve(by_id.size());
  for (auto& [id, f] : by_id) {
    if (f.mass > 0) f.centroid /= f.mass;
    out.push_back(f);
  }
  std::stable_sort(out.begin(), out.end(),
                   [](const FragmentInfo& a, const FragmentInfo& b) { return a.mass > b.mass; });
  return out;
}

}  // namespace dspdem::joint
