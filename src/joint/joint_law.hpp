// Which law a joint point follows, by its material's choice (CohesiveParams::law): the
// dispatch between the paper's law (cohesive_law.hpp), the coupled law (coupled_law.hpp) and
// the paper's law with its text's shear softening (residual_law.hpp).
#pragma once
#include "joint/coupled_law.hpp"
#include "joint/residual_law.hpp"

namespace dspdem::joint {

/// How far a point is along its way to failure, in [0, 1] (1: broken): the coupled law's
/// damage; for the paper's laws the eq. 6 index sqrt(a^2 + b^2) of its largest opening and
/// its shear damage; for mode I only, a. For output (the joints frame's damage field).
inline Real damage_index(const CohesiveParams& p, const CohesiveState& s) {
  if (s.status == JointStatus::Broken) return 1.0;
  if (p.law == JointLaw::Coupled) return s.damage;
  const Real a = std::max<Real>(0, s.dn_max - p.ft / p.kn) / (2 * p.GfI / p.ft);
  if (p.law == JointLaw::ModeI) return std::min<Real>(1.0, a);
  return std::min<Real>(1.0, std::sqrt(a * a + s.damage * s.damage));
}

/// The law a point follows, by its material's choice.
inline void joint_law_update(const CohesiveParams& p, Real dn, const Slip& sl, CohesiveState& s) {
  if (p.law == JointLaw::Coupled)
    coupled_update(p, dn, sl, s);
  else if (p.law == JointLaw::PaperResidual)
    residual_update(p, dn, sl, s);
  else
    cohesive_update(p, dn, sl, s);
}

/// Fails a point because its joint failed at another point (joint_forces.cpp: a face is the
/// crack's unit), as its law does it.
inline void joint_force_break(const CohesiveParams& p, CohesiveState& s) {
  if (p.law == JointLaw::PaperResidual)
    residual_force_break(p, s);
  else
    force_break(s);
}

}  // namespace dspdem::joint
