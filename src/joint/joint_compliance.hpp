// How much softer the intact joints make a body (the price of the penalty method: the
// joints are springs in series with the elements). For a joint population of isotropic
// orientations under uniaxial stress sigma along e, each joint (area A, normal n, stiffness
// k_n, k_s) opens by t/k with t = sigma (n.e) e, which adds the strain
//   e.eps.e = (sigma / V) sum A [ (n.e)^4 / k_n + ((n.e)^2 - (n.e)^4) / k_s ];
// averaging over directions (<(n.e)^2> = 1/3, <(n.e)^4> = 1/5) gives the added compliance
// relative to the elements' 1/E:
//   C = (E / V) sum A [ 1 / (5 k_n) + 2 / (15 k_s) ].
// With k = p E / h and tets (sum over faces of A h = 6 V) that is 2 / p: 2 % at the
// default p = 100 (the tension block measured about 1.5 / p).
#pragma once
#include <vector>

#include "core/types.hpp"
#include "joint/joint_set.hpp"

namespace dspdem::joint {

/// Added compliance of one joint population over a volume V of elements of modulus E.
inline Real added_compliance_term(Real area, Real kn, Real ks) { return area * (0.2 / kn + (2.0 / 15.0) / ks); }

/// Added compliance of all intact-at-start joints of a model: sum over joints of
/// E_j added_compliance_term, divided by the volume of the elements that carry joints.
/// `elem_E` and `elem_volume` are per global element.
Real added_compliance(const JointSet& js, const std::vector<Real>& elem_E, const std::vector<Real>& elem_volume);

}  // namespace dspdem::joint
