// Meshed rigid bodies ([[bodies]] kinematics = "rigid"): every node of the body follows one
// rigid motion (centre, velocity, orientation quaternion, angular momentum). The elements
// give mass and contact skeletons but no internal force. Mass, centre and inertia are those
// of the lumped nodal masses, the same masses the kinetic energy is summed from, so a rigid
// body's kinetic energy in the ledger is exactly 1/2 M v^2 + 1/2 w.I w; the lumped inertia
// tends to the solid's as the mesh is refined (a body of a few elements is off: a single
// hexahedron's lumped inertia is 3x the solid cube's).
//
// Time stepping follows the free walls': kick the momentum and angular momentum with the
// summed nodal force and torque, drift the centre and rotate the orientation by h w, then
// place the nodes and give them v + w x r.
#pragma once
#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "core/types.hpp"

namespace dspdem {

struct RigidBody {
  std::string name;
  std::vector<Index> nodes;  ///< its nodes, increasing (sums run in this order)
  std::vector<Vec3> offset;  ///< node positions relative to the centre, in the body frame
  Real mass = 0;
  Mat3 inertia_body = Mat3::Zero();  ///< about the centre, body frame
  Vec3 centre = Vec3::Zero(), velocity = Vec3::Zero();
  Vec3 angular_momentum = Vec3::Zero(), omega = Vec3::Zero();
  Eigen::Quaternion<Real> q = Eigen::Quaternion<Real>::Identity();

  /// What moves (core/archive.hpp).
  template <class Ar>
  void persist(Ar& ar) {
    ar(centre, velocity, angular_momentum, omega, q);
  }
  Mat3 inertia_world() const;
  void update_omega() { omega = inertia_world().ldlt().solve(angular_momentum); }
};

/// The rigid body of `nodes` (positions x, 3 per node; lumped masses `mass`, one per node),
/// starting with the momentum and angular momentum of the nodal velocities `v`. Throws Error
/// naming the body when it has no mass or its nodes are all on one line (no inertia to turn
/// about).
RigidBody make_rigid_body(const std::string& name, std::vector<Index> nodes, const std::vector<Real>& x,
                          const std::vector<Real>& mass, const std::vector<Real>& v);

/// Sets the body's nodal velocities in `v` to its rigid field v + w x r at positions `x`.
void rigid_set_velocities(const RigidBody& b, const Real* x, Real* v);

/// Half a kick: momentum += h F, angular momentum += h T from the nodal forces `f` at `x`,
/// then the nodal velocities.
void rigid_kick(RigidBody& b, const Real* f, const Real* x, Real h, Real* v);

/// Drift by h: centre += h v, orientation rotated by h w, nodes placed (x) and given the
/// rigid velocity field at the new pose (v). Returns sum f_ext . (x_new - x_in) over the
/// body's nodes, the work `f_ext` does on the difference between where the nodes were
/// moved (x_in, a straight drift) and where the rigid motion puts them.
Real rigid_drift(RigidBody& b, Real h, const Real* f_ext, Real* x, Real* v);

}  // namespace dspdem
