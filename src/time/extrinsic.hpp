// Extrinsic insertion (issue 20): closed faces open when the traction on them reaches the
// strength of their joint law (joint/onset.hpp). Until then their two sides' nodes are tied
// (joint/ties.hpp) and the faces carry the elements' stresses as a continuum would; on
// opening, the joint's law starts from the elastic state whose traction is the face's
// (JointSet::offset), taken by the rule of joint::FaceStress: under one stress the traction
// does not jump; under "larger" with two different stresses it starts from the more stressed
// element's, up to half their difference from their mean (continuity checked every step; with
// insertion_interval k > 1 the traction may overshoot the onset by up to k steps of loading,
// and the law then drops to its softening curve at once), and it books no energy for that
// skipped elastic branch (its work integrals start at zero: the stored energy the law reports
// then is balanced by an equal negative dissipation until the joint has been opened by as
// much, and the ledger stays exact).
#pragma once
#include <vector>

#include "joint/onset.hpp"
#include "time/integrator.hpp"

namespace dspdem {

/// What opening a face does to the nodes of its crack front. Tied: nothing; a node's copies
/// part only once the opened faces cut all the way round it, so an opened face whose nodes are
/// still tied cannot open, and the stress does not redistribute until a whole ring of faces
/// round a node has reached the strength by itself. Cut: at each of an opened face's nodes
/// still tied across it, the closed faces of a least cut between its two sides (each costing
/// how far it stands from its onset, joint/min_cut.hpp) open too, as elastic joints carrying
/// their current traction (the two elements' mean), so that the opened face opens at once,
/// as an intrinsic joint would, and the faces next to it feel the redistribution. A face so
/// forced is freed at that node only: at its other nodes it may stay tied until the crack
/// reaches them. (Under the coupled law the mean of two stresses each below the onset can
/// lie just above it, where the ellipse meets the friction cone; such a face starts past its
/// onset and its law takes it to the softening curve at its first update.) Measured on the
/// Brazilian disc (opened joints' penalty 2, the step fixed at every joint open's): tied
/// +14.5 % of the intrinsic peak, cut -1.7 %; with the step falling as joints open, cut -4.0 %
/// (cases/README.md).
enum class InsertionFront : char { Tied = 0, Cut = 1 };

class ExtrinsicInsertion {
 public:
  /// Checks every `interval` steps, a face's traction taken by rule `stress`.
  ExtrinsicInsertion(long interval, joint::FaceStress stress, InsertionFront front = InsertionFront::Cut)
      : interval_(interval), stress_rule_(stress), front_(front) {}
  /// After a step: on a checking step, opens the closed joints whose face traction has
  /// reached their law's onset (decided in parallel, applied in joint order: the same on
  /// any thread count), with front Cut the faces that free them (in the same order), and
  /// reties the nodes. Returns how many opened, both kinds.
  Index check(Model& m, Integrator& it);
  Index opened() const { return opened_; }
  /// Of those, how many were opened below their onset to free a crack front (InsertionFront::Cut).
  Index forced() const { return forced_; }
  template <class Ar>
  void persist(Ar& ar) {
    ar(opened_, forced_);
  }

 private:
  long interval_;
  joint::FaceStress stress_rule_;
  InsertionFront front_;
  Index opened_ = 0, forced_ = 0;
  /// Opens the closed faces that tie the nodes of the faces `opened` across them (front_ Cut).
  Index cut_fronts(joint::JointSet& js, const Real* x, const std::vector<Index>& opened);
  std::vector<Index> node_ptr_, node_joint_;  ///< per node, the joints touching it (CSR)
  Index joints_indexed_ = -1;                 ///< the joint count node_ptr_ was built for
  std::vector<Index> local_;                  ///< per node: its vertex in the star being cut, or -1
  std::vector<Real> stress_, traction_;       ///< per element; per joint (t_n, then t_s as a vector)
  std::vector<char> open_;
  std::vector<Real> floor_, bound_;  ///< per joint, its law's onset_floor; per element, stress_bound
};

}  // namespace dspdem
