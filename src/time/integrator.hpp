// Velocity Verlet (kick-drift-kick) time integration of M a = f_int + f_ext - C v with
// lumped mass, prescribed-velocity constraints, nodal loads, gravity and Rayleigh damping
// (README M4, paper eqs. 21-23). Damping forces use the mid-step velocity
// (lagged by half a step), as in central-difference codes.
//
// Energy ledger (all in J): kinetic and internal energy are state functions; external work
// (loads, gravity, support reactions) is integrated with the trapezoidal rule over each
// drift; damping dissipation as dt times the dissipation rate at the mid-step velocity, and
// for mass damping, as the trapezoid of the (lagged) damping forces the kicks applied.
// The balance error is |KE - K_h + IE + D - (E0 + W_ext)| over the largest of those terms and
// of the largest |W_ext| reached so far. K_h, the kick's term, is the change since the start
// of sum h^2 |f|^2 / 8m over the nodes: velocity Verlet's kinetic energy at whole steps
// exceeds the trapezoidal work of the forces by exactly that change (the two half kicks
// around a drift), so KE - K_h is what the work books; without it a body that rings shows
// h^2 |f|^2 / 8m as a balance error.
#pragma once
#include <cmath>
#include <csignal>
#include <string>
#include <vector>

#include "core/distribution.hpp"
#include "core/error.hpp"
#include "joint/ties.hpp"
#include "time/model.hpp"

namespace dspdem {

struct Energy {
  Real kinetic = 0, internal = 0, external_work = 0, damping = 0, initial = 0;
  Real joint_elastic = 0, fracture_I = 0, fracture_II = 0;  ///< joints (zero without)
  Index broken_joints = 0;
  Real crack_area = 0;
  Real contact_elastic = 0, friction = 0, contact_damping = 0;  ///< contact (zero without)
  /// The kick's term sum h^2 |f|^2 / 8m (h the last step, f the nodal force) less its value
  /// at the start, taken off the kinetic energy in the balance: see above. Not counted: a
  /// rigid body's rotation, free walls, constrained dofs, and the change a new step length
  /// or a retie's new forces leave at their step.
  Real kick = 0;
  /// Largest |external_work| reached so far in the run: the scale of the balance error
  /// too, so that a body that bounces back to where it started (every term near 0 again)
  /// is not judged by the rounding of its terms at the top of its bounce.
  Real peak_work = 0;
  Real balance() const {
    return kinetic - kick + internal + joint_elastic + contact_elastic + damping + fracture_I + fracture_II + friction +
           contact_damping - initial - external_work;
  }
  Real largest() const;        ///< the largest term, peak_work included
  Real balance_error() const;  ///< |balance| / largest term
};

class Integrator {
 public:
  /// Starts at t = 0 with the model's initial velocities and prescribed velocities.
  /// dist: a distributed run's exchange and reductions (m is then one process's share).
  Integrator(Model& m, Real dt, Distribution* dist = nullptr);

  /// One step. Throws NumericalError (with step, time, element) on an inverted element or
  /// a non-finite state.
  void step();

  Real time() const { return t_; }
  long steps() const { return n_; }
  Real dt() const { return dt_; }
  /// The step from the next one on (extrinsic insertion lowers it as joints open). Velocity
  /// Verlet's step ends with the whole kick, so the state is the same whatever step follows.
  void set_dt(Real dt) {
    DSPDEM_CHECK(dt > 0 && std::isfinite(dt), "time step must be positive, got {}", dt);
    dt_ = dt;
  }
  const std::vector<Real>& x() const { return x_; }
  const std::vector<Real>& v() const { return v_; }
  const std::vector<Real>& reaction() const { return reaction_; }
  /// Energy ledger at the current state (sums in a fixed order: thread-count independent).
  Energy energy() const;
  /// Distributed: the ghosts take their owners' positions and velocities now (collective;
  /// the motion does not depend on it). One process: nothing.
  void refresh_ghosts() {
    if (dist_) dist_->exchange(x_.data(), v_.data());
  }
  /// A flag set from outside (a signal handler's), read at each step's one reduction: after a
  /// step, flag_anywhere() says whether it was set on any process then (a distributed run's
  /// processes agree on the step to stop at, without a reduction of their own). One process:
  /// the flag itself.
  void watch_flag(const volatile std::sig_atomic_t* flag) { flag_ = flag; }
  bool flag_anywhere() const { return flag_anywhere_; }
  /// Throws NumericalError when KE + IE exceeds factor x (E0 + |W_ext| + D) + floor;
  /// else returns the energies it summed (a collective sum in a distributed run).
  Energy check_energy(Real factor) const;
  /// Value of a monitor at the current state.
  Real monitor(const MonitorSet& ms) const;
  /// Cauchy stress of every element at the current state (6 per element).
  void stresses(std::vector<Real>& out);
  /// Keep the element stresses of the force evaluation of every step whose count is a
  /// multiple of k (0: none), so that stresses() at the end of such a step hands them out
  /// rather than evaluating the elements again. (The stresses are the elastic ones, which
  /// depend on the positions only, and those do not change after the step's evaluation.)
  void keep_stresses_every(long k) { stress_every_ = k; }
  /// Rebuilds the groups of tied nodes from the joints' closed flags (joint/ties.hpp), after
  /// joints opened: each copy then takes its new group's inverse mass, and the forces are
  /// evaluated again so that each new group gets its own copies' forces (and the opened
  /// joints'), not the old group's total. Groups only split while a run goes on, and a split
  /// group's copies have the same position and velocity already, so these do not jump. The
  /// forces are taken at the end-of-step velocity (the step's own used the mid-step one for
  /// damping), and contact histories do not advance (no time passes).
  void retie() {
    retie(false);
    compute_forces(v_, 0.0, false);
    damp_lag_ = 0;
  }
  const joint::Ties& ties() const { return ties_; }
  /// The run's whole changing state, this integrator's and its model's, for checkpoints
  /// (core/archive.hpp): a run loaded from it goes on as the saved one would have, to the bit.
  /// Tied groups are rebuilt from the joints' closed flags; scratch is not stored.
  template <class Ar>
  void persist(Ar& ar) {
    ar.section("integrator");
    ar(dt_, h_last_, damp_lag_, t_, n_, x_, v_, f_, f_ext_, reaction_, w_ext_, w_peak_, damp_, e0_, kick0_, dpower_);
    ar.section("elements");
    ar(m_.fem.elem_energy, m_.fem.elem_dpower);
    ar.section("joints");
    ar(m_.joints);
    ar.section("contact");
    ar(m_.contact);
    ar.section("rigid bodies");
    ar.parts(m_.rigid, "rigid bodies");
    ar.section("end of model");
    if (!ar.loading()) return;
    stress_step_ = -1;  // kept stresses are not the loaded state's
    const std::size_t nd = 3 * static_cast<std::size_t>(m_.fem.n_nodes);
    DSPDEM_CHECK(x_.size() == nd && v_.size() == nd && f_.size() == nd && f_ext_.size() == nd && reaction_.size() == nd,
                 "checkpoint: {} nodal values for a model of {} dofs", x_.size(), nd);
    if (!m_.joints.closed.empty()) retie(false);
  }
  /// Gmsh tag of a global element, for messages.
  std::size_t element_tag(Index e) const { return m_.fem.elem_tag[e]; }

 private:
  /// dt_contact: time since the last evaluation (0 at the start), for contact histories.
  /// nodal_in_tail: leave damping and external forces of the dofs without a load or a
  /// constraint to the pass that ends the step (step()); otherwise add them here.
  /// exchange: a distributed run's ghosts are brought up to date first (overlapped with the
  /// elements that need none of them).
  void compute_forces(const std::vector<Real>& vel, Real dt_contact, bool nodal_in_tail, bool exchange = false,
                      Real* stress = nullptr);
  /// Damping and external force of one dof at velocity vk: adds to the damping power dp,
  /// returns the external force.
  Real nodal_force(std::size_t i, int d, Real vk, Real& f, Real& dp) const;
  Real element_dpower() const;                              ///< stiffness-damping power of the elements [W]
  Real own_elements_sum(const std::vector<Real>& a) const;  ///< per-element values, own elements only
  void kick_nodes(Real h);                                  ///< v += h f / m at every node
  void kick_nonnodal(Real h, Real t_target);                ///< constraints, rigid bodies, walls
  [[noreturn]] void non_finite_state() const;
  [[noreturn]] void contact_crossed() const;  ///< throws the diagnosis of a too-deep contact
  /// average: give each group its copies' mean velocity (momentum kept), at the start.
  void retie(bool average);
  /// Every copy of a tied group gets the group's force (its copies' forces summed in node
  /// order): with the group's inverse mass they then move alike to the bit. (The per-copy
  /// path only: the fused step sums each group in its last pass.)
  void tie_forces();
  void set_damp_alpha();  ///< damp_alpha_ for untied nodes (retie sets the groups')

  Model& m_;
  Distribution* dist_ = nullptr;
  const volatile std::sig_atomic_t* flag_ = nullptr;
  std::vector<char> interior_;  ///< distributed: per element, 1 when all its nodes are own
  bool flag_anywhere_ = false;
  Real dt_, t_ = 0;
  Real h_last_;  ///< the last step's length: the kick's term's h (dt_ may change after it)
  /// Mass damping's books: per node, the damping coefficient alpha where the kicks move it
  /// (a tied group's mass-weighted alpha at its first copy, 0 at the other copies and at
  /// rigid bodies' nodes); empty when no node is mass-damped. damp_lag_: the time from the
  /// velocity the damping in f_ was evaluated at to the current one (h/2 after a step, 0
  /// after an evaluation at the current velocity: the start, a retie).
  std::vector<Real> damp_alpha_;
  Real damp_lag_ = 0;
  long n_ = 0;
  /// f_ext_: external force per dof. Without rigid bodies it is kept only at loaded and
  /// constrained dofs (special_); elsewhere it is the weight, computed where it is used.
  /// f_ after a fused step with tied groups: the group's force at its first copy, and each
  /// other copy's own (without its damping and weight); x_ and v_ are every copy's.
  std::vector<Real> x_, v_, f_, f_ext_, reaction_, inv_mass_, joint_slots_;
  std::vector<Real> v_target_;  ///< prescribed velocities of constrained dofs (scratch)
  std::vector<char> constrained_;
  std::vector<char> rigid_node_;           ///< per node: 1 on a rigid body (empty without them)
  std::vector<char> special_;              ///< per dof: constrained or loaded
  std::vector<std::size_t> special_list_;  ///< those dofs, ascending
  /// No rigid bodies, no gravity, no mass damping: a dof without a load or a constraint has
  /// no nodal force besides f_ (its weight and damping are exactly +-0).
  bool quiet_ = false;
  Real w_ext_ = 0, w_peak_ = 0, damp_ = 0, e0_ = 0;
  Real kick0_ = 0;          ///< the kick's term at the start (Energy::kick is its change since)
  Real dpower_ = 0;         ///< dissipation rate at the last force evaluation
  joint::Ties ties_;        ///< nodes tied through closed joints (none: no groups)
  bool ties_fuse_ = true;   ///< no tied node is loaded or supported: the step fuses its passes
  std::vector<Index> rep_;  ///< per node: its group's first copy, or -1 when untied
  long stress_every_ = 0;   ///< keep_stresses_every
  long stress_step_ = -1;   ///< the step whose stresses stress_kept_ holds (-1: none)
  std::vector<Real> stress_kept_;
  std::vector<Real> group_mass_;  ///< per tied group, its copies' mass [kg]
};

}  // namespace dspdem
