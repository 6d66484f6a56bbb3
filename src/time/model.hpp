// A case turned into arrays the time loop can run: mesh, FEM blocks, nodal constraints,
// loads, initial velocities and monitor node sets.
#pragma once
#include <string>
#include <vector>

#include "contact/contact_system.hpp"
#include "fem/fem_model.hpp"
#include "fem/stable_dt.hpp"
#include "joint/joint_set.hpp"
#include "joint/ties.hpp"
#include "mesh/mesh.hpp"
#include "time/monitor.hpp"
#include "time/rigid_body.hpp"

namespace dspdem {

/// A prescribed-velocity degree of freedom (fixed = zero velocity).
struct Constraint {
  Index dof;   ///< 3 * node + component
  Real value;  ///< target velocity [m/s]
  Real ramp;   ///< ramp time [s]
};

/// A nodal force component from a force boundary condition.
struct NodalLoad {
  Index dof;
  Real value;  ///< full force [N]
  Real ramp;
};

struct MonitorSet {
  MonitorConfig cfg;
  std::vector<Index> nodes, nodes2;
  std::vector<char> dof_in_group;  ///< reaction monitors: 3 x n_nodes mask
  std::vector<char> joint_in;      ///< broken_joints / crack_area monitors: per joint, counted
};

struct Model {
  Mesh mesh;
  std::vector<Material> materials;
  FemModel fem;
  std::vector<Constraint> constraints;
  std::vector<NodalLoad> loads;
  std::vector<Real> v0;
  Vec3 gravity = Vec3::Zero();
  std::vector<MonitorSet> monitors;
  std::vector<std::string> body_names;
  joint::JointSet joints;
  joint::InsertionReport joint_report;
  /// Per body of the case: how many joints took its zone material (zone_groups, zone box);
  /// a zone in which no two fracturable elements share a face takes none, which the run warns of.
  std::vector<Index> zone_joints;
  contact::ContactSystem contact;  ///< disabled unless [contact] enabled
  std::vector<RigidBody> rigid;    ///< bodies with kinematics = "rigid"

  // One process's share of a distributed run (par/subdomain.hpp): nodes [0, owned_nodes) are
  // its own, the rest ghosts whose positions come from their owners each step; elements and
  // joints with a 0 in elem_owned / joint_owned are computed here for the own nodes they
  // touch but counted (energies, frames) by the process that owns them. A one-process run
  // leaves owned_nodes at -1 and the masks empty: everything is its own.
  Index owned_nodes = -1;
  std::vector<char> elem_owned, joint_owned;
  Index n_owned_nodes() const { return owned_nodes >= 0 ? owned_nodes : fem.n_nodes; }
  bool owns_element(Index e) const { return elem_owned.empty() || elem_owned[e]; }
};

/// Ramp factor of a boundary value at time t: min(1, t / ramp), or 1 without a ramp.
inline Real ramp_factor(Real t, Real ramp) { return ramp > 0 ? std::min<Real>(1.0, t / ramp) : 1.0; }
/// Its time derivative (for the inertia part of reactions).
inline Real ramp_rate(Real t, Real ramp) { return ramp > 0 && t < ramp ? 1.0 / ramp : 0.0; }

/// Critical time step of the model: elements, joint penalties and contact springs
/// (limiter says which). Closed joints (extrinsic insertion) count as if open.
StableStep stable_step(const Model& m);
/// The same from the elements' own critical steps (element_stable_step's per_element), at
/// the state `ties` describes when given: only the open joints count, and tied copies are
/// one point (joint/joint_dt.hpp): extrinsic insertion's step as joints open.
StableStep stable_step(const Model& m, const std::vector<Real>& per_element, const joint::Ties* ties = nullptr);

}  // namespace dspdem
