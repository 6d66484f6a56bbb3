// The stable step with joints. A joint's penalty springs add, at each of its nodes, a
// Gershgorin row sum of 2 k A / npf (k = max(k_n, k_s), A the face area) to the stiffness
// the element already gives. Per node: w^2 <= w_e^2 + 2 K_n / m_n, w_e the largest
// frequency of the node's elements (element eigenvalue bound), K_n the sum over its joints;
// dt = 2 / w. The limiter is "joint" when the joint term is the larger one.
//
// With extrinsic insertion (joint/ties.hpp) a closed joint has no spring, and the copies it
// ties move as one point: at the current state, only the open joints count, and a point's
// mass is its copies' masses added (Gershgorin on M^-1 K holds for any masses), its element
// term the largest of its copies'. The bound holds point by point: the elements give at most
// sum_p w2e(p) M_p |u_p|^2 and a spring k |u_a - u_b|^2 at most 2 k (|u_a|^2 + |u_b|^2). The
// tied state is the every-joint-open model constrained to equal copies, so its true step is
// never below that one's; the estimate can be (its element and joint terms may sit on
// different copies of a point), and a run takes the larger of the two (run/run_case.cpp).
#pragma once
#include "fem/fem_model.hpp"
#include "fem/stable_dt.hpp"
#include "joint/joint_set.hpp"
#include "joint/ties.hpp"

namespace dspdem::joint {

/// Combines the element step (`per_element` critical steps) with the joint penalties: every
/// joint as if open (ties null), or at the state `ties` describes (open joints only, tied
/// copies one point). `ties` must be built from js.closed as it is now (Integrator::retie):
/// stale ties would leave out the springs of faces opened since.
StableStep stable_step_with_joints(const FemModel& m, const JointSet& js, const std::vector<Real>& per_element,
                                   const Ties* ties = nullptr);

}  // namespace dspdem::joint
