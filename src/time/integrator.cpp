#include "time/integrator.hpp"

#include <algorithm>
#include <cmath>

#include "core/chunked_sum.hpp"
#include "core/error.hpp"
#include "joint/joint_forces.hpp"

namespace dspdem {

Real Energy::largest() const {
  return std::max({std::abs(kinetic), std::abs(internal), std::abs(external_work), std::abs(damping), std::abs(initial),
                   std::abs(joint_elastic), std::abs(fracture_I), std::abs(fracture_II), std::abs(contact_elastic),
                   std::abs(friction), std::abs(contact_damping), peak_work});
}

Real Energy::balance_error() const {
  const Real l = largest();
  return l > 0 ? std::abs(balance()) / l : 0.0;
}

Integrator::Integrator(Model& m, Real dt, Distribution* dist) : m_(m), dist_(dist), dt_(dt), h_last_(dt) {
  DSPDEM_CHECK(dt > 0 && std::isfinite(dt), "time step must be positive, got {}", dt);
  const std::size_t nd = 3 * static_cast<std::size_t>(m.fem.n_nodes);
  x_ = m.fem.x0;
  v_ = m.v0;
  f_.assign(nd, 0.0);
  f_ext_.assign(nd, 0.0);
  reaction_.assign(nd, 0.0);
  inv_mass_.resize(m.fem.n_nodes);
  for (Index i = 0; i < m.fem.n_nodes; ++i) inv_mass_[i] = 1.0 / m.fem.mass[i];
  constrained_.assign(nd, 0);
  v_target_.assign(nd, 0.0);
  special_.assign(nd, 0);
  for (const auto& c : m.constraints) special_[c.dof] = 1;
  for (const auto& l : m.loads) special_[l.dof] = 1;
  for (std::size_t k = 0; k < nd; ++k)
    if (special_[k]) special_list_.push_back(k);
  quiet_ = m.rigid.empty() && m.gravity == Vec3::Zero();
  for (Index i = 0; i < m.fem.n_nodes && quiet_; ++i)
    quiet_ = m.fem.node_alpha[i] == 0 && m.fem.mass[i] > 0 && std::isfinite(m.fem.mass[i]);
  for (const auto& c : m.constraints) constrained_[c.dof] = 1;
  if (!m.rigid.empty()) {
    rigid_node_.assign(static_cast<std::size_t>(m.fem.n_nodes), 0);
    for (const RigidBody& b : m.rigid)
      for (Index i : b.nodes) rigid_node_[i] = 1;
  }
  set_damp_alpha();
  if (!m.joints.closed.empty()) retie(true);
  for (const auto& c : m.constraints) v_[c.dof] = c.value * ramp_factor(0.0, c.ramp);
  for (const RigidBody& b : m.rigid) rigid_set_velocities(b, x_.data(), v_.data());
  if (m.contact.enabled()) m.contact.kick_walls(0.0, 0.0, m.gravity);  // prescribed wall velocities at t = 0
  if (dist) {
    // Elements with only own nodes: computed while the ghosts' values travel.
    interior_.assign(static_cast<std::size_t>(m.fem.n_elements), 1);
    for (const auto& b : m.fem.blocks)
      for (Index e = 0; e < b.size(); ++e)
        for (int i = 0; i < b.npe(); ++i)
          if (b.conn[static_cast<std::size_t>(e) * b.npe() + i] >= m.owned_nodes) interior_[b.elem[e]] = 0;
  }
  compute_forces(v_, 0.0, false);
  damp_lag_ = 0;
  const Energy e = energy();
  e0_ = e.kinetic + e.internal + e.joint_elastic + e.contact_elastic;
  kick0_ = e.kick;
}

Real Integrator::nodal_force(std::size_t i, int d, Real vk, Real& f, Real& dp) const {
  const Real m = m_.fem.mass[i];
  const Real fe = m * m_.gravity(d);
  const Real fd = -m_.fem.node_alpha[i] * m * vk;
  dp -= fd * vk;
  f = (f + fd) + fe;
  return fe;
}

void Integrator::compute_forces(const std::vector<Real>& vel, Real dt_contact, bool nodal_in_tail, bool exchange,
                                Real* stress) {
  ForceStatus st;
  if (exchange) {
    // The ghosts' values travel while the elements that need none are computed; the rest
    // after. The nodes' sums come after both, in their fixed order: the same bits.
    dist_->exchange_begin(x_.data(), v_.data());
    st = element_forces(m_.fem, x_.data(), vel.data(), nullptr, {interior_.data(), 1});
    dist_->exchange_end(x_.data(), v_.data());
    const ForceStatus s = element_forces(m_.fem, x_.data(), vel.data(), nullptr, {interior_.data(), 0});
    if (s.inverted_element >= 0 && (st.inverted_element < 0 || s.min_detF < st.min_detF)) st = s;
    gather_forces(m_.fem, f_.data());
  } else {
    st = internal_forces(m_.fem, x_.data(), vel.data(), f_.data(), stress);
  }
  if (st.inverted_element >= 0)
    throw NumericalError(fmt::format("element {} inverted (det F = {:.3g}) at step {}, t = {:.6g} s; the time step "
                                     "may be too large or the element too distorted",
                                     element_tag(st.inverted_element), st.min_detF, n_, t_),
                         n_, t_);
  if (m_.joints.size() > 0) joint::add_joint_forces(m_.joints, x_.data(), f_.data(), joint_slots_);
  // Contact forces are internal between bodies and external from walls; both go to f_.
  if (m_.contact.enabled()) m_.contact.add_forces(m_.mesh, m_.joints, x_.data(), vel.data(), dt_contact, f_.data());
  // Joints contact released just now had already added their forces. Left in f, they would
  // act through the next half kick while the books hold the joints as gone (their energy at x
  // booked as released), and that work would be booked nowhere: the sphere's ledger fell 0.046
  // J short of 292 J by 0.75 ms, growing with the pieces. Taken back, they are missing instead
  // from the step that ended here, whose trapezoid the joints' books hold whole: that half,
  // 1/2 h f . v, is booked with the released energy, so the books follow what the kicks did.
  // (No step ended here when dt_contact is 0: at the start, or a retie after the step's
  // whole kick, which applied those forces already.)
  if (!m_.joints.newly_released.empty())
    m_.joints.released_energy += joint::remove_joint_forces(m_.joints, m_.joints.newly_released, joint_slots_,
                                                            vel.data(), dt_contact, m_.joint_owned, f_.data());
  // f = (f + damping) + external at every dof, external = gravity + loads (+ the reaction,
  // added below at constrained dofs). Loaded and constrained dofs are done here; the others
  // here too, or in the step's last pass (nodal_in_tail), where the same arithmetic saves a
  // pass over the nodes.
  const Real* v = vel.data();
  Real* f = f_.data();
  Real* fe = f_ext_.data();
  for (std::size_t k : special_list_) fe[k] = m_.fem.mass[k / 3] * m_.gravity(k % 3);
  for (const auto& l : m_.loads) fe[l.dof] += l.value * ramp_factor(t_, l.ramp);
  for (std::size_t k : special_list_) {
    const Real fd = -m_.fem.node_alpha[k / 3] * m_.fem.mass[k / 3] * v[k];
    f[k] = (f[k] + fd) + fe[k];
  }
  if (!nodal_in_tail) {
    const Real mass_dpower =
        chunked_sums<1>(static_cast<std::size_t>(m_.n_owned_nodes()), [&](std::size_t b, std::size_t e) {
          Real dp = 0;
          for (std::size_t i = b; i < e; ++i)
            for (int d = 0; d < 3; ++d) {
              const std::size_t k = 3 * i + d;
              Real fk = f[k];
              const Real fek = nodal_force(i, d, v[k], fk, dp);
              if (!special_[k]) f[k] = fk, fe[k] = fek;
            }
          return std::array<Real, 1>{dp};
        })[0];
    dpower_ = mass_dpower + element_dpower();
  }
  // (nodal_in_tail: the step's last pass sums each group after its copies' damping and weight.)
  DSPDEM_CHECK(!nodal_in_tail || ties_.groups() == 0 || ties_fuse_,
               "internal: tied nodes with loads or supports need their forces complete before the tie");
  if (ties_.groups() > 0 && !nodal_in_tail) tie_forces();
  // Reaction = the force the support must supply so the dof follows its prescribed motion.
  // A tied group is one point: its reaction is the group's, booked once, at its first node.
  const Real* mass = m_.fem.mass.data();
  for (const auto& c : m_.constraints) {
    const Real a = c.value * ramp_rate(t_, c.ramp);
    const Index i = c.dof / 3, g = ties_.groups() > 0 ? ties_.group[i] : -1;
    const Real r = g < 0                           ? mass[i] * a - f_[c.dof]
                   : ties_.node[ties_.ptr[g]] == i ? group_mass_[g] * a - f_[c.dof]
                                                   : 0.0;
    reaction_[c.dof] = r;
    f_ext_[c.dof] += r;
    f_[c.dof] += r;
  }
}

Real Integrator::element_dpower() const {
  return m_.fem.any_stiffness_damping ? own_elements_sum(m_.fem.elem_dpower) : 0.0;
}

// Distributed: each element counted by the process that owns it (the mask), in fixed chunks.
Real Integrator::own_elements_sum(const std::vector<Real>& a) const {
  if (m_.elem_owned.empty()) return deterministic_sum(a);
  const char* own = m_.elem_owned.data();
  return chunked_sums<1>(a.size(), [&](std::size_t b, std::size_t e) {
    Real s = 0;
    for (std::size_t i = b; i < e; ++i)
      if (own[i]) s += a[i];
    return std::array<Real, 1>{s};
  })[0];
}

void Integrator::kick_nonnodal(Real h, Real t_target) {
  for (const auto& c : m_.constraints) v_[c.dof] = c.value * ramp_factor(t_target, c.ramp);
  for (RigidBody& b : m_.rigid) rigid_kick(b, f_.data(), x_.data(), h, v_.data());  // their nodes: one motion
  if (m_.contact.enabled()) m_.contact.kick_walls(h, t_target, m_.gravity);
}

// The passes over the nodes are fused where that keeps every operation and its order: the
// first half kick with the drift, the external work of the step's end with the second half
// kick and the finite check. Each runs in parallel over fixed chunks of nodes, and its sums
// (work, the finite check) are added in chunk order, so a step is the same to the bit on
// any thread count.
// Groups per chunk in the passes over tied groups: a group has tens of copies, so the
// nodes' 2048 per chunk would leave a disc's 3277 groups in two unequal chunks.
constexpr std::size_t kGroupChunk = 128;

void Integrator::step() {
  const Real h = dt_, hh = 0.5 * h;
  // The own nodes: a distributed run's ghosts get their motion from their owners below.
  const std::size_t nn = static_cast<std::size_t>(m_.n_owned_nodes());
  Real* x = x_.data();
  Real* v = v_.data();
  Real* f = f_.data();
  const Real* fe = f_ext_.data();
  const Real* im = inv_mass_.data();
  const Real* mass = m_.fem.mass.data();
  const Vec3 g = m_.gravity;
  const char* cons = constrained_.data();
  const char* special = special_.data();
  // Without rigid bodies, the external force of a dof with no load or constraint is its
  // weight, computed where it is needed rather than stored (fused passes below); in a quiet
  // model it is zero and its terms are skipped.
  // Tied copies (extrinsic insertion) fuse too, unless a load or a support holds any. A
  // group is one point: each pass first moves every group at its first copy (where the
  // group's force is kept), then the pass over the nodes copies that motion to the other
  // copies, in node order: an extrinsic body has tens of copies per point, and copying them
  // in order costs less than their arithmetic and far less than visiting them group by group.
  const bool fused = m_.rigid.empty() && (ties_.groups() == 0 || ties_fuse_);
  const std::size_t ng = fused ? static_cast<std::size_t>(ties_.groups()) : 0;
  const Index* rep = ng > 0 ? rep_.data() : nullptr;
  const Index* gptr = ties_.ptr.data();
  const Index* gnode = ties_.node.data();
  const Real* gmass = group_mass_.data();
  // Mass damping is booked below as h alpha m v+^2 at the mid-step velocity v+, but the
  // kicks apply its force lagged: -alpha m u in f (u the velocity it was evaluated at) with
  // the first half kick, -alpha m v+ with the second. Their trapezoid over the drift is
  // 1/2 h alpha m v+.(u + v+); the difference, 1/2 h alpha m v+.(u - v+) with u - v+ =
  // -(damp_lag_ + h/2) f / m, is booked too, so that the ledger's kick term closes it
  // (time/integrator.hpp). The first pass sums alpha v+.f over the free dofs (al: null when
  // no node is mass-damped).
  const Real* al = damp_alpha_.empty() ? nullptr : damp_alpha_.data();
  Real w = 0, bad = 0, vf = 0;
  if (fused) {
    // Half kick and drift in one pass: a constrained dof takes its prescribed velocity (the
    // last constraint on it wins, as in kick_nonnodal) before it drifts.
    Real* vt = v_target_.data();
    for (const auto& c : m_.constraints) vt[c.dof] = c.value * ramp_factor(t_ + hh, c.ramp);
    const std::array<Real, 3> rg = chunked_sums<3>(
        ng,
        [&](std::size_t b, std::size_t e) {
          Real s = 0, sd = 0;
          bool finite = true;
          for (std::size_t gi = b; gi < e; ++gi) {
            const std::size_t i = static_cast<std::size_t>(gnode[gptr[gi]]);
            Real pd = 0;
            for (int d = 0; d < 3; ++d) {
              const std::size_t k = 3 * i + d;
              v[k] += hh * f[k] * im[i];
              pd += v[k] * f[k];
              const Real dx = h * v[k];
              x[k] += dx;
              finite &= x[k] - x[k] == 0;
              if (!quiet_) s += 0.5 * (gmass[gi] * g(d)) * dx;
            }
            if (al) sd += al[i] * pd;
          }
          return std::array<Real, 3>{s, finite ? 0.0 : 1.0, sd};
        },
        kGroupChunk);
    const std::array<Real, 3> r = chunked_sums<3>(nn, [&](std::size_t b, std::size_t e) {
      // The arrays in locals: through the closure's references they were reloaded after
      // every store. The finite check is a flag, not a sum: a sum is a chain of dependent
      // adds, one per dof, and its latency was most of this pass's time.
      Real* const xl = x;
      Real* const vl = v;
      const Real *const fl = f, *const iml = im, *const vtl = vt, *const fel = fe, *const ml = mass, *const all = al;
      const char *const cl = cons, *const sl = special;
      const bool quiet = quiet_;
      Real s = 0, sd = 0;
      bool finite = true;
      for (std::size_t i = b; i < e; ++i) {
        if (rep && rep[i] >= 0) {
          const std::size_t r = static_cast<std::size_t>(rep[i]);
          if (r != i)
            for (int d = 0; d < 3; ++d) vl[3 * i + d] = vl[3 * r + d], xl[3 * i + d] = xl[3 * r + d];
          continue;
        }
        Real pd = 0;
        for (int d = 0; d < 3; ++d) {
          const std::size_t k = 3 * i + d;
          const Real vk = cl[k] ? vtl[k] : vl[k] + hh * fl[k] * iml[i];
          vl[k] = vk;
          if (all && !cl[k]) pd += vk * fl[k];
          const Real dx = h * vk;
          xl[k] += dx;
          finite &= xl[k] - xl[k] == 0;  // false once x is not finite
          if (sl[k])
            s += 0.5 * fel[k] * dx;
          else if (!quiet)
            s += 0.5 * (ml[i] * g(d)) * dx;
        }
        if (all) sd += all[i] * pd;
      }
      return std::array<Real, 3>{s, finite ? 0.0 : 1.0, sd};
    });
    w = rg[0] + r[0], bad = rg[1] + r[1], vf = rg[2] + r[2];
    if (m_.contact.enabled()) m_.contact.kick_walls(hh, t_ + hh, m_.gravity);
  } else {
    // Rigid bodies set their nodes' velocities from the whole kick: kick, then drift.
    kick_nodes(hh);
    kick_nonnodal(hh, t_ + hh);
    // alpha v+.f, as the fused pass sums it (al is 0 at rigid bodies' nodes and at the
    // copies a group's first copy stands for).
    if (al)
      vf = chunked_sums<1>(nn, [&](std::size_t b, std::size_t e) {
        Real sd = 0;
        for (std::size_t i = b; i < e; ++i) {
          if (al[i] == 0) continue;
          Real pd = 0;
          for (std::size_t k = 3 * i; k < 3 * i + 3; ++k)
            if (!cons[k]) pd += v[k] * f[k];
          sd += al[i] * pd;
        }
        return std::array<Real, 1>{sd};
      })[0];
    const std::array<Real, 2> r = chunked_sums<2>(nn, [&](std::size_t b, std::size_t e) {
      Real s = 0;
      bool finite = true;
      for (std::size_t k = 3 * b; k < 3 * e; ++k) {
        const Real dx = h * v[k];
        x[k] += dx;
        finite &= x[k] - x[k] == 0;
        s += 0.5 * fe[k] * dx;
      }
      return std::array<Real, 2>{s, finite ? 0.0 : 1.0};
    });
    w = r[0], bad = r[1];
    for (RigidBody& b : m_.rigid) w += 0.5 * rigid_drift(b, h, f_ext_.data(), x_.data(), v_.data());
  }
  const bool contact = m_.contact.enabled();
  const Real wall_power0 = contact ? m_.contact.wall_power() : 0.0;
  if (contact) m_.contact.drift_walls(h, m_.gravity);
  t_ += h;
  ++n_;
  h_last_ = h;
  // Ghosts take their owners' drifted positions and mid-step velocities, which are exactly
  // what this process would have computed with all of their forces (compute_forces).
  Real* keep = nullptr;
  if (stress_every_ > 0 && n_ % stress_every_ == 0 && !dist_) {
    stress_kept_.resize(6 * static_cast<std::size_t>(m_.fem.n_elements));
    keep = stress_kept_.data();
  }
  stress_step_ = -1;
  compute_forces(v_, h, fused, dist_ != nullptr, keep);  // v_: the mid-step velocity (damping lagged by h/2)
  if (keep) stress_step_ = n_;
  // The last pass: (fused) the damping and external forces of the dofs compute_forces left,
  // and the damping power; the end of the step's external work (at the mid-step velocity);
  // the half kick; a check that the velocities are finite (v - v is 0 unless v is not).
  // Quiet: no damping and no weight, so f = (f + (+-0)) + (+0) is f + 0 (which only turns
  // -0 into +0) and the work and power terms are +-0, which change no sum.
  // The groups first: at a group's first copy, each copy's damping and weight, then their
  // sum (in copy order, as tie_forces), then its velocity; the force is kept at the first
  // copy only, the one the first pass reads (the next force evaluation writes every copy's).
  const std::array<Real, 3> tg = chunked_sums<3>(
      ng,
      [&](std::size_t b, std::size_t e) {
        Real s = 0, dp = 0;
        bool finite = true;
        for (std::size_t gi = b; gi < e; ++gi) {
          const Index *q0 = gnode + gptr[gi], *q1 = gnode + gptr[gi + 1];
          Real F[3] = {0, 0, 0};
          for (const Index* q = q0; q < q1; ++q)
            for (int d = 0; d < 3; ++d) {
              const std::size_t n = static_cast<std::size_t>(*q), k = 3 * n + d;
              Real fk = f[k];
              if (!quiet_) s += 0.5 * nodal_force(n, d, v[k], fk, dp) * h * v[k];
              F[d] = q == q0 ? fk : F[d] + fk;
            }
          const std::size_t i = static_cast<std::size_t>(*q0);
          for (int d = 0; d < 3; ++d) {
            const std::size_t k = 3 * i + d;
            f[k] = F[d];
            v[k] += hh * F[d] * im[i];
            finite &= v[k] - v[k] == 0;
          }
        }
        return std::array<Real, 3>{s, finite ? 0.0 : 1.0, dp};
      },
      kGroupChunk);
  const std::array<Real, 3> tail = chunked_sums<3>(nn, [&](std::size_t b, std::size_t e) {
    Real* const fl = f;  // locals and a flag, as in the first pass
    Real* const vl = v;
    const Real *const fel = fe, *const iml = im;
    const char *const cl = cons, *const sl = special;
    const bool quiet = quiet_;
    Real s = 0, dp = 0;
    bool finite = true;
    for (std::size_t i = b; i < e; ++i) {
      if (rep && rep[i] >= 0) {
        const std::size_t r = static_cast<std::size_t>(rep[i]);
        if (r != i)
          for (int d = 0; d < 3; ++d) vl[3 * i + d] = vl[3 * r + d];
        continue;
      }
      for (int d = 0; d < 3; ++d) {
        const std::size_t k = 3 * i + d;
        const Real vk = vl[k];
        if (sl[k] || !fused) {
          s += 0.5 * fel[k] * h * vk;
          if (fused) {
            Real fk = fl[k];
            nodal_force(i, d, vk, fk, dp);  // the damping power only: f[k] is complete
          }
        } else if (quiet) {
          fl[k] = fl[k] + 0.0;
        } else {
          Real fk = fl[k];
          s += 0.5 * nodal_force(i, d, vk, fk, dp) * h * vk;
          fl[k] = fk;
        }
        vl[k] = vk + hh * fl[k] * iml[i];
        finite &= cl[k] || vl[k] - vl[k] == 0;  // constrained: checked below
      }
    }
    return std::array<Real, 3>{s, finite ? 0.0 : 1.0, dp};
  });
  if (fused) dpower_ = (tg[2] + tail[2]) + element_dpower();
  damp_ += h * dpower_ - 0.5 * h * (damp_lag_ + hh) * vf;
  damp_lag_ = hh;
  w += tg[0] + tail[0];
  w_ext_ += w;
  if (contact) m_.contact.add_wall_work(0.5 * h * (wall_power0 + m_.contact.wall_power()));
  // The reported external work is the integrator's plus the walls' (energy()). Distributed:
  // the whole work is the processes' shares added, one small reduction a step, so that the
  // peak (the ledger's scale) is the one-process run's.
  Real whole[2] = {w_ext_, flag_ && *flag_ ? 1.0 : 0.0};
  if (dist_) dist_->sum(whole, 2);
  flag_anywhere_ = whole[1] > 0;
  w_peak_ = std::max(w_peak_, std::abs(whole[0] + (contact ? m_.contact.wall_work() : 0.0)));
  kick_nonnodal(hh, t_);
  bool finite = std::isfinite(w) && bad == 0 && tg[1] == 0 && tail[1] == 0;
  // Rigid bodies and constraints wrote velocities after the check's pass: check them all.
  for (std::size_t k = 0; k < v_.size() && finite && !m_.rigid.empty(); ++k) finite = std::isfinite(v_[k]);
  for (const auto& c : m_.constraints) finite = finite && std::isfinite(v_[c.dof]);
  if (!finite) non_finite_state();
  // At the end of the step, so a stopped run's state and ledger are those of a whole step.
  if (contact && m_.contact.overlap_exceeded()) contact_crossed();
}

void Integrator::kick_nodes(Real h) {
  Real* v = v_.data();
  const Real* f = f_.data();
  const Real* im = inv_mass_.data();
  const long nn = static_cast<long>(m_.fem.n_nodes);
#pragma omp parallel for schedule(static) if (nn > 4096)
  for (long i = 0; i < nn; ++i)
    for (int d = 0; d < 3; ++d) v[3 * i + d] += h * f[3 * i + d] * im[i];
}

void Integrator::retie(bool average) {
  ties_ = joint::build_ties(m_.joints, m_.fem.n_nodes);
  const Real* mass = m_.fem.mass.data();
  for (Index i = 0; i < m_.fem.n_nodes; ++i) inv_mass_[i] = 1.0 / mass[i];
  set_damp_alpha();
  group_mass_.assign(static_cast<std::size_t>(ties_.groups()), 0.0);
  // The fused step finishes a group's force in its last pass, after the reactions and loads
  // were booked per copy: if any group holds a loaded or supported dof, the whole model
  // takes the per-copy path. Distributed runs refuse closed joints (par/subdomain.cpp); the
  // group passes would count a ghost group's work twice.
  DSPDEM_CHECK(dist_ == nullptr || ties_.groups() == 0, "internal: tied nodes in a distributed run");
  stress_step_ = -1;  // kept stresses are for the step's own state only
  ties_fuse_ = true;
  if (ties_.groups() > 0)
    for (std::size_t k : special_list_) ties_fuse_ = ties_fuse_ && ties_.group[k / 3] < 0;
  rep_.assign(static_cast<std::size_t>(m_.fem.n_nodes), -1);
  for (Index g = 0; g < ties_.groups(); ++g)
    for (Index q = ties_.ptr[g]; q < ties_.ptr[g + 1]; ++q) rep_[ties_.node[q]] = ties_.node[ties_.ptr[g]];
  for (Index g = 0; g < ties_.groups(); ++g) {
    const Index b = ties_.ptr[g], e = ties_.ptr[g + 1];
    Real M = 0;
    for (Index q = b; q < e; ++q) M += mass[ties_.node[q]];
    group_mass_[g] = M;
    for (Index q = b; q < e; ++q) inv_mass_[ties_.node[q]] = 1.0 / M;
    // One point moves one way: a support must hold all of its copies or none.
    for (int d = 0; d < 3; ++d)
      for (Index q = b + 1; q < e; ++q)
        if (constrained_[3 * ties_.node[q] + d] != constrained_[3 * ties_.node[b] + d])
          fail(
              "nodes {} and {} are tied across closed joints (extrinsic insertion) but only one is constrained in "
              "{}: constrain the whole group or neither",
              m_.mesh.node_tag[ties_.node[b]], m_.mesh.node_tag[ties_.node[q]], "xyz"[d]);
    if (!damp_alpha_.empty()) {
      Real am = 0;
      for (Index q = b; q < e; ++q) am += m_.fem.node_alpha[ties_.node[q]] * mass[ties_.node[q]];
      for (Index q = b; q < e; ++q) damp_alpha_[ties_.node[q]] = q == b ? am / M : 0.0;
    }
    if (average)
      for (int d = 0; d < 3; ++d) {
        Real p = 0;
        for (Index q = b; q < e; ++q) p += mass[ties_.node[q]] * v_[3 * ties_.node[q] + d];
        for (Index q = b; q < e; ++q) v_[3 * ties_.node[q] + d] = p / M;
      }
  }
}

void Integrator::set_damp_alpha() {
  damp_alpha_.clear();
  const std::vector<Real>& a = m_.fem.node_alpha;
  if (std::none_of(a.begin(), a.end(), [](Real x) { return x != 0; })) return;
  damp_alpha_ = a;
  for (std::size_t i = 0; i < rigid_node_.size(); ++i)  // they move with the body, not with the kicks
    if (rigid_node_[i]) damp_alpha_[i] = 0;
}

void Integrator::tie_forces() {
  const Index ng = ties_.groups();
  const Index* node = ties_.node.data();
  const Index* ptr = ties_.ptr.data();
  Real* f = f_.data();
  // One pass over a group's copies for all three components (each summed in copy order,
  // as before): the copies are scattered, and three passes read each one's line three times.
#pragma omp parallel for schedule(static) if (ng > 2048)
  for (Index g = 0; g < ng; ++g) {
    const Real* f0 = f + 3 * static_cast<std::size_t>(node[ptr[g]]);
    Real F0 = f0[0], F1 = f0[1], F2 = f0[2];
    for (Index q = ptr[g] + 1; q < ptr[g + 1]; ++q) {
      const Real* fq = f + 3 * static_cast<std::size_t>(node[q]);
      F0 += fq[0], F1 += fq[1], F2 += fq[2];
    }
    for (Index q = ptr[g]; q < ptr[g + 1]; ++q) {
      Real* fq = f + 3 * static_cast<std::size_t>(node[q]);
      fq[0] = F0, fq[1] = F1, fq[2] = F2;
    }
  }
}

void Integrator::non_finite_state() const {
  Index node = -1;
  for (std::size_t k = 0; k < v_.size() && node < 0; ++k)
    if (!std::isfinite(v_[k]) || !std::isfinite(x_[k])) node = static_cast<Index>(k / 3);
  // Name an element that holds the node, so the message points at the mesh.
  std::size_t elem_tag = 0;
  for (const auto& b : m_.fem.blocks)
    for (std::size_t i = 0; i < b.conn.size() && elem_tag == 0; ++i)
      if (b.conn[i] == node) elem_tag = m_.fem.elem_tag[b.elem[i / b.npe()]];
  throw NumericalError(fmt::format("non-finite position or velocity at node {} (element {}) at step {}, t = {:.6g} s; "
                                   "the time step is probably too large",
                                   node >= 0 ? m_.mesh.node_tag[node] : 0, elem_tag, n_, t_),
                       n_, t_);
}

void Integrator::contact_crossed() const {
  const contact::ContactTotals t = m_.contact.totals();
  throw NumericalError(
      fmt::format("contact too deep at step {}, t = {:.6g} s: {} overlap by {:.4f} times the sum of their contact "
                  "radii (limit {:g}; beyond 1 the contact skeletons cross, the contact loses the features inside the "
                  "other piece and the pieces can pass through each other); the contact is too soft or too thin for "
                  "this impact: raise contact_penalty or "
                  "contact_radius_fraction, or [checks] contact_overlap_limit to accept it",
                  n_, t_, m_.contact.deepest_contact(), t.max_overlap, m_.contact.overlap_limit()),
      n_, t_);
}

Energy Integrator::energy() const {
  Energy e;
  const Index nn = m_.n_owned_nodes();
  std::vector<Real> ke(nn), kick(nn, 0.0);
  // The kick's term 1/2 (h/2)^2 f^2 / m per free dof (Energy::kick), where the kicks apply
  // it: a tied group's force and inverse mass are at its first copy, which stands for the
  // group; a rigid body's nodes move with it, and its term is its momentum's, below.
  const Real hh = 0.5 * h_last_;
  for (Index i = 0; i < nn; ++i) {
    const std::size_t k0 = 3 * static_cast<std::size_t>(i);
    const Real* v = &v_[k0];
    ke[i] = 0.5 * m_.fem.mass[i] * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    if ((!rep_.empty() && rep_[i] >= 0 && rep_[i] != i) || (!rigid_node_.empty() && rigid_node_[i])) continue;
    Real f2 = 0;
    for (int d = 0; d < 3; ++d)
      if (!constrained_[k0 + d]) f2 += f_[k0 + d] * f_[k0 + d];
    kick[i] = 0.5 * hh * hh * f2 * inv_mass_[i];
  }
  e.kinetic = deterministic_sum(ke);
  e.kick = deterministic_sum(kick);
  for (const RigidBody& b : m_.rigid) {
    Vec3 F = Vec3::Zero();
    for (Index i : b.nodes) F += Vec3(f_[3 * i], f_[3 * i + 1], f_[3 * i + 2]);
    e.kick += 0.5 * hh * hh * F.squaredNorm() / b.mass;
  }
  e.internal = own_elements_sum(m_.fem.elem_energy);
  e.external_work = w_ext_;
  e.peak_work = w_peak_;
  e.damping = damp_;
  e.initial = e0_;
  if (m_.joints.size() > 0) {
    const joint::JointTotals t = joint::joint_totals(m_.joints, m_.joint_owned);
    e.joint_elastic = t.elastic, e.fracture_I = t.fracture_I, e.fracture_II = t.fracture_II;
    e.broken_joints = t.broken, e.crack_area = t.broken_area;
  }
  contact::ContactTotals ct;
  if (m_.contact.enabled()) {
    ct = m_.contact.totals();
    e.contact_elastic = ct.elastic, e.friction = ct.friction, e.contact_damping = ct.damping;
  }
  if (dist_) {
    // The processes' shares added in rank order; e0_ is already whole (the constructor
    // computed it through here), and so is w_peak_ (step()). Contact: each pair counted by
    // one process; the walls are the same on every process and added once, below.
    Real a[13] = {e.kinetic,       e.internal,        e.external_work, e.damping,
                  e.joint_elastic, e.fracture_I,      e.fracture_II,   static_cast<Real>(e.broken_joints),
                  e.crack_area,    e.contact_elastic, e.friction,      e.contact_damping,
                  e.kick};
    dist_->sum(a, 13);
    e.kinetic = a[0], e.internal = a[1], e.external_work = a[2], e.damping = a[3], e.joint_elastic = a[4];
    e.fracture_I = a[5], e.fracture_II = a[6], e.broken_joints = static_cast<Index>(a[7]), e.crack_area = a[8];
    e.contact_elastic = a[9], e.friction = a[10], e.contact_damping = a[11], e.kick = a[12];
  }
  e.kick -= kick0_;  // whole, as e0_
  if (m_.contact.enabled()) {
    e.kinetic += ct.wall_kinetic;
    e.external_work += ct.wall_work;
  }
  return e;
}

Energy Integrator::check_energy(Real factor) const {
  const Energy e = energy();
  const Real budget =
      e.initial + std::abs(e.external_work) + e.damping + e.fracture_I + e.fracture_II + e.friction + e.contact_damping;
  const Real floor = 1e-9 * std::max<Real>(1.0, budget);
  const Real held = e.kinetic + e.internal + e.joint_elastic + e.contact_elastic;
  if (held > factor * budget + floor) {
    Index worst = 0;
    for (Index k = 1; k < m_.fem.n_elements; ++k)
      if (m_.fem.elem_energy[k] > m_.fem.elem_energy[worst]) worst = k;
    // The sum printed is the one tested (contact springs included: a contact that creates
    // energy shows there first).
    throw NumericalError(
        fmt::format("energy blow-up at step {}, t = {:.6g} s: kinetic + internal (+ joint + contact) = {:.4g} J "
                    "(contact springs {:.4g} J) exceeds {} x (initial + work + dissipated = {:.4g} J); largest "
                    "strain energy in element {}",
                    n_, t_, held, e.contact_elastic, factor, budget, element_tag(worst)),
        n_, t_);
  }
  return e;
}

Real Integrator::monitor(const MonitorSet& ms) const {
  using T = MonitorConfig::Type;
  const int c = ms.cfg.component;
  auto pick = [c](const Vec3& v) { return c < 3 ? v(c) : v.norm(); };
  // A distributed run's monitor sets hold the own nodes only: sums and counts are added
  // over the processes (reduce), maxima taken over them.
  auto reduce = [&](Vec3 s) {
    if (dist_) dist_->sum(s.data(), 3);
    return s;
  };
  auto mean_of = [&](const std::vector<Index>& nodes, bool disp) {
    Real s[4] = {0, 0, 0, static_cast<Real>(nodes.size())};
    for (Index n : nodes)
      for (int d = 0; d < 3; ++d) {
        const std::size_t k = 3 * static_cast<std::size_t>(n) + d;
        s[d] += disp ? x_[k] - m_.fem.x0[k] : v_[k];
      }
    if (dist_) dist_->sum(s, 4);
    return Vec3(Vec3(s[0], s[1], s[2]) / s[3]);
  };
  switch (ms.cfg.type) {
    case T::Reaction: {
      Vec3 r = Vec3::Zero();
      for (std::size_t k = 0; k < reaction_.size(); ++k)
        if (ms.dof_in_group[k]) r(k % 3) += reaction_[k];
      return pick(reduce(r));
    }
    case T::Displacement:
      return pick(mean_of(ms.nodes, true));
    case T::Velocity:
      return pick(mean_of(ms.nodes, false));
    case T::Momentum: {
      Vec3 p = Vec3::Zero();
      for (Index n : ms.nodes) p += m_.fem.mass[n] * Vec3(v_[3 * n], v_[3 * n + 1], v_[3 * n + 2]);
      return pick(reduce(p));
    }
    case T::DisplacementDifference:
      return pick(Vec3(mean_of(ms.nodes2, true) - mean_of(ms.nodes, true)));
    case T::MaxDisplacement: {
      Real mx = 0;
      for (Index n : ms.nodes) {
        Vec3 u;
        for (int d = 0; d < 3; ++d) u(d) = x_[3 * n + d] - m_.fem.x0[3 * n + d];
        mx = std::max(mx, std::abs(pick(u)));
      }
      if (dist_) dist_->max(&mx, 1);
      return mx;
    }
    case T::BrokenJoints:
    case T::CrackArea: {
      // A distributed run's mask holds its own joints only (par/subdomain.cpp).
      const joint::JointSet& js = m_.joints;
      const bool area = ms.cfg.type == T::CrackArea;
      Real s = 0;
      for (Index j = 0; j < js.size(); ++j)
        if (ms.joint_in[j] && js.status[j] == joint::JointStatus::Broken) s += area ? js.area0[j] : 1.0;
      if (dist_) dist_->sum(&s, 1);
      return s;
    }
  }
  return 0;
}

void Integrator::stresses(std::vector<Real>& out) {
  if (stress_step_ == n_) {  // this step's force evaluation kept them (keep_stresses_every)
    out.swap(stress_kept_);
    stress_step_ = -1;
    return;
  }
  out.assign(6 * static_cast<std::size_t>(m_.fem.n_elements), 0.0);
  // The stresses only: the element force slots this leaves are rewritten by the next force
  // evaluation, so they are not gathered into nodal forces (the insertion check calls this
  // every few steps).
  element_forces(m_.fem, x_.data(), v_.data(), out.data(), {});
}

}  // namespace dspdem
