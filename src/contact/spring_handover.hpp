// Which tangential spring of the last step each touch of a contact pair goes on with.
//
// A touch is named by its feature pair (kind, fa, fb). Faces lying on each other, as a
// joint's two faces after it broke, trade vertex-on-face for edge-on-edge touches along their
// rims from one step to the next, so the name of the touch that carries a contact changes
// while the contact stays. Its spring must go on with the touch that takes its place:
// dropped, the friction fell below mu N while the new spring loaded again, and the old
// force's half of the step's trapezoid was booked nowhere (4-6 % of the friction's work on a
// broken face sliding; test ContactBorn.AJointReleasedWhilePressedLeavesTheBooksClosed).
#pragma once
#include <cmath>
#include <vector>

#include "contact/narrow_phase.hpp"
#include "contact/pair_history.hpp"

namespace dspdem::contact {

/// One contact point for both sides (the middle of the overlap), so the pair's forces are
/// equal, opposite and collinear: momentum and angular momentum are exact. Also where a
/// touch's spring is stored (HistoryEntry::c), and so where a successor looks for it.
inline Vec3 contact_point(const Touch& t, Real ra, Real rb) { return 0.5 * (t.pa - ra * t.n + t.pb + rb * t.n); }

/// Where a touch's tangential spring comes from: its own entry of the last step, or the
/// entry of a touch it takes over from (successor), or none (a new contact).
struct SpringFrom {
  const HistoryEntry* entry = nullptr;
  bool successor = false;
};

/// Pair p's touches' springs in `h`, the history of the last step (out[i] for touches[i];
/// ra, rb the two roundings, `offset` the overlap the pair was born with):
/// - a touch with an entry of its own feature pair takes it, found once here;
/// - a touch without one that will push (overlap ra + rb - d - offset > 0) and carries weight
///   takes over the entry that no touch claimed and that has weight (a faded touch of weight
///   0 would hold the spring's energy at none) whose point lies nearest, within `reach`;
///   matched greedily in the touches' order (deterministic: one pair on one thread).
/// Whether an entry goes on is settled by the evaluation: see mark_ended.
void springs_of(const PairHistory& h, Index p, const std::vector<Touch>& touches, Real ra, Real rb, Real offset,
                Real reach, std::vector<SpringFrom>& out);

/// Marks pair p's entries of `h` in `ended` (one per entry of h, indexed as h.entry): 1 for
/// each spring no touch goes on with, 0 for the others. A spring goes on with the touch that
/// took it (springs_of, `from`) if that touch pushes this step (`pushes[i]`: its evaluation
/// gave a force); so a touch that matched its own entry but has opened ends it. The caller
/// books the ended springs' energy as released. Writes only pair p's entries: pairs may be
/// marked on several threads at once.
void mark_ended(const PairHistory& h, Index p, const std::vector<SpringFrom>& from, const std::vector<char>& pushes,
                std::vector<char>& ended);

/// The elongation a touch starts its law with: zero for a new contact; its own spring carried
/// to its share (PairHistory::carry; the fade's gradient is in the force); a successor's
/// spring at the ended touch's stored energy, weight x |xi|^2 kept at the new weight.
inline Vec3 starting_spring(const SpringFrom& s, const Touch& t) {
  if (!s.entry) return Vec3::Zero();
  if (s.successor) return s.entry->xi * std::sqrt(s.entry->weight / t.weight);
  return PairHistory::carry(*s.entry, t.share);
}

}  // namespace dspdem::contact
