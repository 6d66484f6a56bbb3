// The contact parameters a case sets: per material and for the whole model. Apart from the
// contact system so the case format needs only these, not the system.
#pragma once
#include "core/types.hpp"

namespace dspdem::contact {

/// Contact properties of a material.
struct ContactMaterial {
  Real radius = 0;  ///< dilation radius [m]; 0: radius_fraction x inradius
  Real radius_fraction = 0.1;
  Real penalty = 10;       ///< kn = penalty x E x 2 inradius of the element, when kn = 0
  Real kn = 0;             ///< [N/m]
  Real kt_ratio = 1.0;     ///< kt = kt_ratio x kn
  Real friction = 0.5;     ///< Coulomb coefficient
  Real damping_ratio = 0;  ///< normal viscous damping, fraction of critical
};

struct ContactSettings {
  Real skin = 0;  ///< broad-phase skin [m]; 0: 0.2 x the mean radius-inflated element size
  /// Stop the run when a contact's overlap / (r_a + r_b) exceeds this (0: never). Beyond 1
  /// the skeletons themselves cross: the narrow phase then loses the deep features and the
  /// pieces can pass through each other, so 1 is where the contact stops being a model.
  Real overlap_limit = 1.0;
  /// The contact springs bound the step at this fraction of their stability limit
  /// 2 sqrt(m / (4 kn)) (ContactSystem::stable_dt says why the default is half of it).
  Real step_fraction = 0.5;
};

}  // namespace dspdem::contact
