#include "contact/spring_handover.hpp"

#include <algorithm>

#include "core/error.hpp"

namespace dspdem::contact {

void springs_of(const PairHistory& h, Index p, const std::vector<Touch>& touches, Real ra, Real rb, Real offset,
                Real reach, std::vector<SpringFrom>& out) {
  out.assign(touches.size(), SpringFrom{});
  if (p >= h.pairs()) return;
  const Index k0 = h.offset[p], k1 = h.offset[p + 1];
  if (k0 == k1) return;
  thread_local std::vector<char> claimed;
  claimed.assign(static_cast<std::size_t>(k1 - k0), 0);
  bool all_own = true;
  for (std::size_t i = 0; i < touches.size(); ++i) {
    for (Index k = k0; k < k1 && !out[i].entry; ++k) {
      const HistoryEntry& e = h.entry[k];
      if (e.kind == static_cast<int>(touches[i].kind) && e.fa == touches[i].fa && e.fb == touches[i].fb)
        claimed[k - k0] = 1, out[i].entry = &e;
    }
    all_own = all_own && out[i].entry;
  }
  if (all_own) return;
  for (std::size_t i = 0; i < touches.size(); ++i) {
    const Touch& t = touches[i];
    if (out[i].entry || t.weight <= 0 || ra + rb - t.d - offset <= 0) continue;
    const Vec3 c = contact_point(t, ra, rb);
    Index best = -1;
    Real nearest = reach;
    for (Index k = k0; k < k1; ++k) {
      const HistoryEntry& e = h.entry[k];
      if (claimed[k - k0] || e.weight <= 0) continue;
      const Real d = (e.c - c).norm();
      if (d < nearest) nearest = d, best = k;
    }
    if (best >= 0) claimed[best - k0] = 1, out[i] = SpringFrom{&h.entry[best], true};
  }
}

void mark_ended(const PairHistory& h, Index p, const std::vector<SpringFrom>& from, const std::vector<char>& pushes,
                std::vector<char>& ended) {
  DSPDEM_ASSERT(pushes.size() == from.size() && ended.size() == h.entry.size());
  if (p >= h.pairs()) return;
  const Index k0 = h.offset[p], k1 = h.offset[p + 1];
  std::fill(ended.begin() + k0, ended.begin() + k1, char{1});
  for (std::size_t i = 0; i < from.size(); ++i) {
    if (!from[i].entry || !pushes[i]) continue;
    const Index k = static_cast<Index>(from[i].entry - h.entry.data());
    DSPDEM_ASSERT(k >= k0 && k < k1);  // springs_of gives pair p's own entries of h only
    ended[static_cast<std::size_t>(k)] = 0;
  }
}

}  // namespace dspdem::contact
