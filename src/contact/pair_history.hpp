// Tangential history of the contacts, in flat arrays keyed by candidate pair (no hash map
// per step). A pair's entries are its touches of the last step, each named by its feature
// pair (kind, fa, fb) and holding the tangential spring elongation xi. The entries of pair p
// are entry[offset[p] .. offset[p+1]); a step writes the next history in pair order, and a
// rebuild of the candidate list carries the entries of the pairs that stay candidates over
// to their new index (both lists are sorted, so this is one merge).
#pragma once
#include <cmath>
#include <utility>
#include <vector>

#include "core/types.hpp"

namespace dspdem::contact {

struct HistoryEntry {
  int kind = 0, fa = 0, fb = 0;
  Vec3 xi = Vec3::Zero();
  /// The energy in the touch's tangential spring as the ledger holds it (weight x kt |xi|^2 / 2;
  /// 0 where this process does not count the touch): booked as dissipated when the touch
  /// ends while its spring is loaded and no touch goes on with it (mark_ended in
  /// spring_handover.hpp; ContactSystem::add_forces).
  Real spring_energy = 0;
  /// The touch's cluster share (Touch::share) when xi was stored: see carry.
  Real share = 1;
  Vec3 c = Vec3::Zero();  ///< the touch's contact point when stored: where a successor takes its spring over
  Real weight = 1;        ///< the touch's weight (share x fade): a successor keeps weight x |xi|^2
  template <class Ar>
  void persist(Ar& ar) {
    ar(kind, fa, fb, xi, spring_energy, share, c, weight);
  }
};

/// A candidate pair's name: (ea, eb) for elements ea < eb; (n_elements + w, e) for element e
/// against wall w, so that wall pairs sort after element pairs, as they are evaluated.
using PairKey = std::pair<Index, Index>;

struct PairHistory {
  std::vector<Index> offset{0};  ///< size pairs + 1
  std::vector<HistoryEntry> entry;

  Index pairs() const { return static_cast<Index>(offset.size()) - 1; }
  /// Entry h's xi carried to the cluster share `share` of the touch that goes on with it: scaled by
  /// sqrt(share before / share now), so that the spring's stored energy, share x fade x kt
  /// |xi|^2 / 2, does not change with the share. Coincident touches share one contact by
  /// weight (weigh in narrow_phase.cpp) but keep their own springs, and the shares move
  /// with the positions with no force for their gradient: unscaled, a loaded spring's energy
  /// followed its share with no work done (+25 J, 8.5 % of the impact, in the sphere impact
  /// at friction 2.0: src/scenes/sphere_impact/REFERENCE.md). A spring scaled past its
  /// Coulomb cap slides back at once, and the law books that as friction. The force
  /// share x kt xi changes by sqrt(share now / share before): a spring sliding at its cap
  /// whose share rises falls below the cap until the motion loads it again (a model choice:
  /// energy kept, not force). The fade's part of the weight is not scaled here: its gradient
  /// is in the force (Touch::Fade).
  static Vec3 carry(const HistoryEntry& h, Real share) {
    return h.xi * std::sqrt(h.share / share);  // an unchanged share keeps xi's bits: x / x is exactly 1
  }
  void clear(Index pairs) {
    offset.assign(static_cast<std::size_t>(pairs) + 1, 0);
    entry.clear();
  }
};

/// The history of the pairs `old_keys` (with `old`) re-indexed to `new_keys`; both key lists
/// sorted ascending. Pairs only in `new_keys` start empty; pairs only in `old_keys` are gone,
/// and the spring energy of their entries is added to *released when given.
PairHistory remap_history(const PairHistory& old, const std::vector<PairKey>& old_keys,
                          const std::vector<PairKey>& new_keys, Real* released = nullptr);

/// Values per pair carried over the same way (`absent` for new pairs).
std::vector<Real> remap_values(const std::vector<Real>& old, const std::vector<PairKey>& old_keys,
                               const std::vector<PairKey>& new_keys, Real absent);

}  // namespace dspdem::contact
