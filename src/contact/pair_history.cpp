#include "contact/pair_history.hpp"

namespace dspdem::contact {

namespace {
/// Calls match(i_old, i_new) for every key present in both sorted lists.
template <class F>
void merge_keys(const std::vector<PairKey>& a, const std::vector<PairKey>& b, F match) {
  std::size_t i = 0, j = 0;
  while (i < a.size() && j < b.size()) {
    if (a[i] < b[j])
      ++i;
    else if (b[j] < a[i])
      ++j;
    else
      match(i++, j++);
  }
}
}  // namespace

PairHistory remap_history(const PairHistory& old, const std::vector<PairKey>& old_keys,
                          const std::vector<PairKey>& new_keys, Real* released) {
  std::vector<Index> from(new_keys.size(), -1);
  std::vector<char> kept(old_keys.size(), 0);
  merge_keys(old_keys, new_keys, [&](std::size_t i, std::size_t j) { from[j] = static_cast<Index>(i), kept[i] = 1; });
  if (released)
    for (std::size_t i = 0; i + 1 < old.offset.size() && i < old_keys.size(); ++i)
      if (!kept[i])
        for (Index k = old.offset[i]; k < old.offset[i + 1]; ++k) *released += old.entry[k].spring_energy;
  PairHistory h;
  h.offset.assign(new_keys.size() + 1, 0);
  for (std::size_t j = 0; j < new_keys.size(); ++j) {
    if (from[j] >= 0)
      h.entry.insert(h.entry.end(), old.entry.begin() + old.offset[from[j]],
                     old.entry.begin() + old.offset[from[j] + 1]);
    h.offset[j + 1] = static_cast<Index>(h.entry.size());
  }
  return h;
}

std::vector<Real> remap_values(const std::vector<Real>& old, const std::vector<PairKey>& old_keys,
                               const std::vector<PairKey>& new_keys, Real absent) {
  std::vector<Real> out(new_keys.size(), absent);
  merge_keys(old_keys, new_keys, [&](std::size_t i, std::size_t j) { out[j] = old[i]; });
  return out;
}

}  // namespace dspdem::contact
