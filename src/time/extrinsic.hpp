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

class ExtrinsicInsertion {
 public:
  /// Checks every `interval` steps, a face's traction taken by rule `stress`.
  ExtrinsicInsertion(long interval, joint::FaceStress stress) : interval_(interval), stress_rule_(stress) {}
  /// After a step: on a checking step, opens the closed joints whose face traction has
  /// reached their law's onset (decided in parallel, applied in joint order: the same on
  /// any thread count) and reties the nodes. Returns how many opened.
  Index check(Model& m, Integrator& it);
  Index opened() const { return opened_; }
  template <class Ar>
  void persist(Ar& ar) {
    ar(opened_);
  }

 private:
  long interval_;
  joint::FaceStress stress_rule_;
  Index opened_ = 0;
  std::vector<Real> stress_, traction_;  ///< per element; per joint (t_n, then t_s as a vector)
  std::vector<char> open_;
  std::vector<Real> floor_, bound_;  ///< per joint, its law's onset_floor; per element, stress_bound
};

}  // namespace dspdem
