// Contact between the pieces of a model (README M3): which elements can touch,
// the broad phase with a skin, the narrow phase per candidate pair, the force law with its
// tangential history, nodal forces by the original element's shape functions (eq. 16),
// rigid walls, the energy terms and the contact limit of the time step.
//
// Candidates: elements with a free face (outer boundary, or a face of a broken joint), in
// pairs from different fragments (pieces connected through nodes or unbroken joints never
// touch each other). The candidate list is rebuilt when a node has moved more than half the
// skin since the last build, when a wall has, or when joints have failed.
//
// A step runs in parallel and gives the same bits on any number of threads: the skeletons
// of the surface elements are computed once (not once per pair), each candidate pair's
// touches are evaluated into records of its own, and the records are then added to the
// nodes, walls, ledger and history in the fixed order of the pairs, one thread (the order
// of a serial loop, so the sums do not depend on how the pairs were shared out).
//
// A distributed run (contact_share.cpp): each process evaluates every pair with an element
// that it owns or that touches a node it owns, and adds the pairs in the same global order,
// so its own nodes get the one-process run's terms in the one-process order. The partners it
// lacks are lent to it at each rebuild by their owners (a broad phase on the processes'
// bounding boxes), with their nodes' positions and velocities sent each step. Each pair's
// energy and wall force is counted by the owner of its first element; the wall forces are
// gathered and added in the one-process order on every process, so walls move alike.
#pragma once
#include <algorithm>
#include <cstdint>
#include <vector>

#include "contact/broad_phase.hpp"
#include "contact/contact_exchange.hpp"
#include "contact/contact_law.hpp"
#include "contact/contact_params.hpp"
#include "contact/narrow_phase.hpp"
#include "contact/pair_history.hpp"
#include "contact/skeleton.hpp"
#include "contact/spring_handover.hpp"
#include "contact/walls.hpp"
#include "joint/joint_set.hpp"
#include "mesh/mesh.hpp"

namespace dspdem::contact {

/// Pairs first found overlapping at a rebuild after the first (ContactSystem::rebuild): how
/// many so far, the normal spring energy their overlaps held when found, and the largest
/// overlap / (r_a + r_b). Overlaps under kRoundOff of r_a + r_b (two coincident faces) are
/// not counted.
struct BornOverlaps {
  static constexpr Real kRoundOff = 1e-9;
  Real energy = 0, max_ratio = 0;
  std::int64_t pairs = 0;  // 64 bits: no padding in checkpoints
  void add(Real e, Real ratio) {
    if (ratio <= kRoundOff) return;
    energy += e, max_ratio = std::max(max_ratio, ratio), ++pairs;
  }
};
/// Element pairs start from such an overlap (forgiven: no push, no energy, so the balance
/// does not see it); wall pairs push with it (their energy enters the balance). `split`: the
/// two elements had a joint between them, whose failure split them; the overlap is what
/// their compression brought (the skeletons move with the elements' strain; the joint's own
/// compression). `unseen`: no joint between them, so mostly an overlap no contact computed
/// (an element reached through an edge or vertex before a joint of it failed, or two parts
/// of one piece); a pair that comes into reach in the ordinary way adds at most a step's
/// approach or two. A run whose unseen energy is a sizeable part of its ledger has elements
/// inside each other that its balance cannot show.
struct BornTotals {
  BornOverlaps split, unseen, wall;
};

struct ContactTotals {
  Real elastic = 0;       ///< stored in the springs now [J]
  Real friction = 0;      ///< dissipated by sliding so far [J]
  Real damping = 0;       ///< dissipated by normal damping so far [J]
  Real wall_work = 0;     ///< work of prescribed walls on the model so far [J]
  Real wall_kinetic = 0;  ///< kinetic energy of free walls [J]
  Index contacts = 0, pairs = 0, surface_elements = 0, rebuilds = 0;
  Real max_overlap = 0;  ///< largest overlap / (r_a + r_b) in the last evaluation (> 1: skeletons cross)
  std::size_t deepest_a = 0, deepest_b = 0;  ///< element tags of that contact (deepest_b 0: a wall)
  std::int64_t deepest_wall = -1;            ///< the wall's index when it is one (64 bits: no padding in checkpoints)
  BornTotals born;                           ///< pairs first found overlapping (a distributed run: all processes')
};

class ContactSystem {
 public:
  bool enabled() const { return enabled_; }
  /// True when the last evaluation's deepest contact exceeds ContactSettings::overlap_limit.
  bool overlap_exceeded() const { return settings_.overlap_limit > 0 && totals_.max_overlap > settings_.overlap_limit; }
  /// The deepest contact of the last evaluation, for messages: "elements 12 and 40".
  std::string deepest_contact() const;
  Real overlap_limit() const { return settings_.overlap_limit; }

  /// Prepares the contact data of a model. `E` per global element (for the penalty),
  /// `mat` per global element into `materials`, `mass` lumped nodal masses.
  void setup(const Mesh& mesh, const joint::JointSet& js, const std::vector<Index>& elem_material,
             const std::vector<ContactMaterial>& materials, const std::vector<Real>& elem_E,
             const std::vector<Real>& node_mass, std::vector<Wall> walls, const ContactSettings& s);

  /// A distributed run's share: local node and element -> global, each local element's
  /// process, how many nodes (numbered first) are this process's own, and which local
  /// joints it owns (it books their released energy).
  struct ShareMap {
    std::vector<Index> node_global, elem_global;
    std::vector<int> elem_owner;
    Index own_nodes = 0;
    std::vector<char> joint_owned;
    int rank = 0;
  };
  /// This process's part of `whole` (set up on the whole model, not yet run): the data of
  /// the share's elements, nodes renumbered. Contact then needs set_exchange before a step.
  void take_share(const ContactSystem& whole, const ShareMap& map);
  void set_exchange(ContactExchange* ex) { ex_ = ex; }
  /// A distributed run's share of the contact work at the last rebuild: pairs evaluated
  /// here and counted here, elements and nodes lent here; and the most elements lent here at
  /// any rebuild so far (how the load moves with the pieces).
  struct ShareLoad {
    long evaluated = 0, counted = 0, lent_elements = 0, lent_nodes = 0, most_lent = 0;
  };
  ShareLoad share_load() const;

  /// Adds contact forces to f (3 x nodes) at positions x and velocities v; dt for the
  /// tangential increment. Updates the tangential history (call once per step). Broken
  /// joints whose elements have come to lie in different fragments are released (they
  /// stop acting: contact carries the pieces from then on) and listed in js.newly_released:
  /// their forces already summed into f are the caller's to take back
  /// (joint::remove_joint_forces).
  void add_forces(const Mesh& mesh, joint::JointSet& js, const Real* x, const Real* v, Real dt, Real* f);

  /// Kick and drift of the walls (free: from their contact force and gravity; prescribed:
  /// to the velocity of time t).
  void kick_walls(Real h, Real t, const Vec3& gravity);
  void drift_walls(Real h, const Vec3& gravity);
  /// Power of the prescribed walls on the model at the last force evaluation [W].
  Real wall_power() const { return wall_power_; }
  void add_wall_work(Real w) { totals_.wall_work += w; }
  Real wall_work() const { return totals_.wall_work; }

  /// Step of the contact springs: step_fraction x the stability limit 2 sqrt(m / (n kn)), m
  /// the smallest nodal mass of a candidate element, n = 4 simultaneous contacts per node.
  /// The default fraction is half, on purpose: an impact lasts only a few steps and the
  /// penalty's energy error grows as (w dt)^2 (two cubes colliding at the limit gained 5 %,
  /// at half of it 0.3 %). A contact that is loaded slowly and stays closed (a specimen
  /// between plates) needs no such margin and can take the whole limit, as long as its
  /// nodes carry no more than about n contact springs each (the limit assumes n).
  Real stable_dt(Index* element = nullptr) const;

  ContactTotals totals() const;
  /// Candidate pairs of the last build (element ids), and the contacts of one pair at x.
  const PairList& pairs() const { return pairs_; }
  void touches_of(Index ea, Index eb, const Real* x, std::vector<Touch>& out) const;
  Real radius(Index e) const { return radius_[e]; }
  /// Skeleton of element e at positions x.
  Poly skeleton_poly(Index e, const Real* x) const;
  const std::vector<Wall>& walls() const { return walls_; }
  std::vector<Wall>& walls() { return walls_; }
  /// Skeleton error for the first element whose radius empties it ("" when none).
  const std::string& setup_error() const { return setup_error_; }
  /// What changes during a run, for checkpoints (core/archive.hpp): candidates, pairs and
  /// their histories, the state of the last build, walls and the energy accumulators.
  /// Per-evaluation scratch (skeleton cache, records) is sized again on load.
  template <class Ar>
  void persist(Ar& ar) {
    ar.parts(walls_, "walls");
    ar(surface_, surface_list_, fragment_, born_offset_, watch_, x_build_, wall_build_, wall_q_build_, failed_seen_,
       built_, pairs_, wall_pairs_, history_.offset, history_.entry, skel_slot_, totals_, elastic_, wall_power_, fdamp_,
       fdamp_prev_, born_own_);
    // A distributed run's share also keeps the elements lent at the last build, as they were
    // numbered (the pairs name them), and who sends which of their nodes.
    if (ex_) {
      ar(elems_, elem_material_, radius_, kn_, elem_node_mass_, skel_off_, skel_w_, outer_faces_, gid_, owner_,
         lent_nodes_, take_, lend_, lent_boxes_.lo, lent_boxes_.hi, most_lent_);
      if (ar.loading()) lent_buffers();
    }
    if (ar.loading()) slots_from_map();
  }

 private:
  /// One touch evaluated: what the ordered gather adds to nodes, walls, ledger and history.
  struct TouchOut {
    Index ea, eb;  ///< eb < 0: wall -1 - eb
    Real Wa[8], Na[8], Wb[8], Nb[8];
    Vec3 force, fn, ft;  ///< force on A, its normal and tangential parts
    Vec3 dmp_n, dmp_t;   ///< their viscous parts
    Vec3 c;              ///< contact point (wall torque)
    Real elastic, slip_work, overlap_ratio;
    HistoryEntry hist;
    /// The couple of a faded touch (Touch::fade): per fade, the force on skeleton vertex a1
    /// of A (a0 gets its opposite) and on b1 of B; a wall gets its torque instead.
    int n_fades;
    int fade_a[3][2], fade_b[3][2];
    Vec3 fade_fa[3], fade_fb[3], fade_torque;
  };
  struct Elem {
    CellType type;
    int npe;
    Index conn[8];
    std::size_t tag;
  };

  void rebuild(const Mesh& mesh, joint::JointSet& js, const Real* x, const Real* v);
  bool needs_rebuild(const joint::JointSet& js, const Real* x) const;
  /// At the first build: Error if two pieces start with their skeletons crossed (a vertex
  /// of one inside the other), which no contact force can resolve.
  void refuse_crossed_skeletons(const Real* x) const;
  /// At the first build: Error if an element's skeleton starts behind a plane wall or inside a
  /// box wall beyond its contact radius (a body wholly inside a box wall had no contact at all).
  void refuse_skeletons_in_walls(const Real* x) const;
  LawParams pair_params(Index ea, Index eb, const Wall* w) const;
  /// Evaluates pair p (element pair or wall pair) at x, v into `out`.
  void evaluate_pair(Index p, const Real* x, const Real* v, Real dt, std::vector<Touch>& touches,
                     std::vector<TouchOut>& out);
  bool evaluate(Index ea, Index eb, const Wall* wall, const Touch& t, const Real* x, const Real* v, Real dt,
                Real offset, TouchOut& o, const SpringFrom& spring) const;
  void gather(const TouchOut& o, Real* f);
  void cache_skeletons(const Real* x);
  const Prepared& cached(Index e) const { return skel_cache_[skel_slot_[e]]; }
  std::vector<PairKey> pair_keys() const;
  /// Node n's three values in x (a local node) or in the lent nodes' `lent` array.
  const Real* at(const Real* x, const std::vector<Real>& lent, Index n) const {
    return n < n_local_nodes_ ? x + 3 * static_cast<std::size_t>(n)
                              : lent.data() + 3 * static_cast<std::size_t>(n - n_local_nodes_);
  }
  Vec3 pos(const Real* x, const std::vector<Real>& lent, Index n) const {
    const Real* p = at(x, lent, n);
    return {p[0], p[1], p[2]};
  }
  /// Whether this process counts the energy and wall force of a pair whose first element is
  /// ea: the owner of ea does (a one-process run counts every pair).
  bool counts(Index ea) const { return !ex_ || owner_[ea] == rank_; }

  // Distributed runs (contact_share.cpp).
  /// Elements lent by other processes: the distributed broad phase. Boxes (3 x 2 per share
  /// surface element, in surface_list_ order) of this process's surface elements.
  void borrow(const Boxes& own_boxes);
  /// Positions and velocities of the lent elements' nodes from their owners.
  void fetch_lent_nodes(const Real* x, const Real* v);
  /// The lent nodes' values and the messages sized from lent_nodes_, lend_ and take_.
  void lent_buffers();
  /// The counted wall forces, contacts and deepest overlap of all processes, added in the
  /// one-process order on every process.
  void reduce_step();
  /// Skeleton vertex k of element e as weights of the element's nodes (npe of them).
  const Real* skeleton_row(Index e, int k) const { return &skel_w_[skel_off_[e] + k * elems_[e].npe]; }

  bool enabled_ = false;
  ContactSettings settings_;
  std::vector<ContactMaterial> materials_;
  std::vector<Elem> elems_;
  std::vector<Index> elem_material_;
  std::vector<Real> radius_, kn_, elem_node_mass_;  ///< per global element
  std::vector<Index> skel_off_;                     ///< per element into skel_w_, -1: none
  std::vector<Real> skel_w_;
  std::vector<Index> outer_faces_;  ///< per element
  std::vector<char> surface_;       ///< per element: candidate
  std::vector<Index> surface_list_, fragment_;
  /// Per element pair: the overlap its skeletons already had when it became a candidate
  /// after the first build (a piece's split, a joint's failure: see rebuild; 0 for the
  /// others). That overlap is not an impact and must not push (it would create energy); it
  /// shrinks as the pair opens and is dropped when the pair leaves the list.
  std::vector<Real> born_offset_;
  std::vector<Wall> walls_;
  std::vector<Index> watch_;      ///< nodes of the candidate elements, ascending
  std::vector<Real> x_build_;     ///< their positions at the last build (3 per node)
  std::vector<Vec3> wall_build_;  ///< centres at the last build
  std::vector<Eigen::Quaternion<Real>> wall_q_build_;
  std::size_t failed_seen_ = 0;
  bool built_ = false;
  Real skin_ = 0;
  PairList pairs_;
  std::vector<std::pair<Index, Index>> wall_pairs_;  ///< (wall, element)
  GridBroadPhase grid_;
  PairHistory history_, history_next_;  ///< by index into pairs_ then wall_pairs_
  /// Per entry of history_, set in a step: no touch went on with its spring (mark_ended), so
  /// its spring energy is released (booked in entry order).
  std::vector<char> ended_;
  /// Per element: index into skel_cache_ (-1: in no pair). Only the elements some pair
  /// names have their skeleton computed each step: on the intact Brazilian disc, only the
  /// elements near its jaws, not its thousands of surface elements (issue 19).
  std::vector<Index> skel_slot_;
  std::vector<Index> skel_elems_;  ///< the elements with a slot, in slot order
  /// Their skeletons at this step, prepared for their pairs (about 1.9 kB each, against 200
  /// bytes for the bare skeleton: 12 triangle frames, of which a tetrahedron uses 4).
  std::vector<Prepared> skel_cache_;
  /// skel_elems_ and the cache's size from skel_slot_ (after a checkpoint is read).
  void slots_from_map();
  std::vector<std::vector<TouchOut>> arena_;  ///< per thread
  std::vector<int> rec_thread_;               ///< per pair: whose arena holds its records
  std::vector<Index> rec_off_, rec_n_;        ///< per pair: where, how many
  std::vector<Touch> touches_;                ///< scratch of the serial paths (rebuild)
  ContactTotals totals_;
  /// The pairs first found overlapping that this process counts (counts()); totals() gives
  /// all processes' (reduce_step).
  BornTotals born_own_;
  /// The element pairs with a joint between them (global numbers, first < second, sorted):
  /// what tells a split's overlap from an unseen one. A process's share keeps those with an
  /// element it owns.
  std::vector<PairKey> joined_;
  /// The touches of element e's skeleton A with wall wl.
  static void wall_touches(const Wall& wl, const Prepared& A, Real r, std::vector<Touch>& out);
  Real elastic_ = 0, wall_power_ = 0;
  /// Viscous contact forces on the nodes, this and the last evaluation: the dissipation is
  /// booked as their trapezoidal work over the drift, as the integrator books external work.
  std::vector<Real> fdamp_, fdamp_prev_;
  bool any_damping_ = false;  ///< some material has contact damping (else the arrays stay empty)
  std::string setup_error_;

  // Distributed runs: null ex_ is a one-process run, where every element and node is local.
  ContactExchange* ex_ = nullptr;
  int rank_ = 0;
  Index n_local_nodes_ = 0;       ///< nodes [0, n_local_nodes_) are the share's; then the lent ones
  Index own_nodes_ = 0;           ///< nodes [0, own_nodes_) are this process's own
  Index share_elems_ = 0;         ///< elements [0, share_elems_) are the share's; then the lent ones
  Index global_elems_ = 0;        ///< elements of the whole model (wall pairs' keys)
  std::size_t skel_w_share_ = 0;  ///< skel_w_ entries of the share's elements
  std::vector<Index> gid_;        ///< per element: global number (keys and order of pairs)
  std::vector<int> owner_;        ///< per element: its process
  std::vector<char> active_;      ///< per share element: own or touching an own node
  std::vector<Index> node_global_;
  std::vector<char> joint_owned_;
  std::vector<Index> lent_nodes_;         ///< global numbers of the lent nodes
  std::vector<Real> xl_, vl_;             ///< their positions and velocities (3 each)
  std::vector<std::vector<Index>> lend_;  ///< per process: local nodes sent to it each step
  std::vector<std::vector<Index>> take_;  ///< per process: lent nodes (index into lent_nodes_) it sends
  Boxes lent_boxes_;                      ///< of the lent elements, in their order
  long most_lent_ = 0;                    ///< the most elements lent here at a rebuild so far
  std::vector<std::vector<Real>> out_, in_;
  std::vector<Real> wall_rec_;  ///< this step's counted wall records: wall, element, force, torque
};

}  // namespace dspdem::contact
