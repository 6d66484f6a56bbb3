#include "par/fragments.hpp"

#include <algorithm>
#include <map>

namespace dspdem::par {

DistributedFragments find_fragments(const Model& m, MpiHalo& halo, const std::vector<Real>& elem_mass, const Real* x) {
  DistributedFragments out;
  const std::vector<Index> label = halo.fragment_ids(m.mesh, m.joints);
  out.fr.id = label;
  // Each process sums its own elements per piece; the sums are gathered and added in rank
  // order on every process: id, mass, elements, mass-weighted centroid.
  std::map<Index, std::array<Real, 5>> mine;
  Index g = 0;
  for (const auto& b : m.mesh.blocks)
    for (Index e = 0; e < b.size(); ++e, ++g) {
      if (!m.owns_element(g)) continue;
      Vec3 c = Vec3::Zero();
      for (int i = 0; i < b.npe(); ++i) {
        const Index n = b.conn[static_cast<std::size_t>(e) * b.npe() + i];
        c += Vec3(x[3 * n], x[3 * n + 1], x[3 * n + 2]);
      }
      c = elem_mass[g] * c / b.npe();
      auto& r = mine.try_emplace(label[g], std::array<Real, 5>{}).first->second;
      r[0] += elem_mass[g], r[1] += 1, r[2] += c(0), r[3] += c(1), r[4] += c(2);
    }
  std::vector<double> send;
  for (const auto& [id, r] : mine) {
    send.push_back(static_cast<double>(id));
    send.insert(send.end(), r.begin(), r.end());
  }
  std::map<Index, joint::FragmentInfo> by_id;
  for (const std::vector<Real>& all : halo.all_gather(send))  // in rank order
    for (std::size_t k = 0; k + 6 <= all.size(); k += 6) {
      joint::FragmentInfo& f = by_id[static_cast<Index>(all[k])];
      f.id = static_cast<Index>(all[k]);
      f.mass += all[k + 1];
      f.elements += static_cast<Index>(all[k + 2]);
      f.centroid += Vec3(all[k + 3], all[k + 4], all[k + 5]);
    }
  for (auto& [id, f] : by_id) {
    if (f.mass > 0) f.centroid /= f.mass;
    out.info.push_back(f);
  }
  std::stable_sort(out.info.begin(), out.info.end(),
                   [](const joint::FragmentInfo& a, const joint::FragmentInfo& b) { return a.mass > b.mass; });
  out.fr.count = static_cast<Index>(out.info.size());
  for (const auto& f : out.info) out.fr.mass.push_back(f.mass);
  return out;
}

}  // namespace dspdem::par
