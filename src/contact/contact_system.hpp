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
#pragma once
#include <cstdint>
#include <vector>

#include "contact/broad_phase.hpp"
#include "contact/contact_law.hpp"
#include "contact/contact_params.hpp"
#include "contact/narrow_phase.hpp"
#include "contact/pair_history.hpp"
#include "contact/skeleton.hpp"
#include "contact/walls.hpp"
#include "joint/joint_set.hpp"
#include "mesh/mesh.hpp"

namespace dspdem::contact {

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

  /// Adds contact forces to f (3 x nodes) at positions x and velocities v; dt for the
  /// tangential increment. Updates the tangential history (call once per step). Broken
  /// joints whose elements have come to lie in different fragments are released (they
  /// stop acting: contact carries the pieces from then on).
  void add_forces(const Mesh& mesh, joint::JointSet& js, const Real* x, const Real* v, Real dt, Real* f);

  /// Kick and drift of the walls (free: from their contact force and gravity; prescribed:
  /// to the velocity of time t).
  void kick_walls(Real h, Real t, const Vec3& gravity);
  void drift_walls(Real h, const Vec3& gravity);
  /// Power of the prescribed walls on the model at the last force evaluation [W].
  Real wall_power() const { return wall_power_; }
  void add_wall_work(Real w) { totals_.wall_work += w; }
  Real wall_work() const { return totals_.wall_work; }

  /// Step of the contact springs: sqrt(m / (n kn)), m the smallest nodal mass of a candidate
  /// element, n = 4 simultaneous contacts per node. That is half the stability limit
  /// 2 sqrt(m / (n kn)), on purpose: an impact lasts only a few steps and the penalty's
  /// energy error grows as (w dt)^2 (two cubes colliding at the limit gained 5 %, at half
  /// of it 0.3 %).
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
    ar(surface_, surface_list_, fragment_, fragment_prev_, born_offset_, watch_, x_build_, wall_build_, wall_q_build_,
       failed_seen_, built_, pairs_, wall_pairs_, history_.offset, history_.entry, skel_slot_, totals_, elastic_,
       wall_power_, fdamp_, fdamp_prev_);
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
  };
  struct Elem {
    CellType type;
    int npe;
    Index conn[8];
    std::size_t tag;
  };

  void rebuild(const Mesh& mesh, joint::JointSet& js, const Real* x);
  bool needs_rebuild(const joint::JointSet& js, const Real* x) const;
  /// At the first build: Error if two pieces start with their skeletons crossed (a vertex
  /// of one inside the other), which no contact force can resolve.
  void refuse_crossed_skeletons(const Real* x) const;
  LawParams pair_params(Index ea, Index eb, const Wall* w) const;
  /// Evaluates pair p (element pair or wall pair) at x, v into `out`.
  void evaluate_pair(Index p, const Real* x, const Real* v, Real dt, std::vector<Touch>& touches,
                     std::vector<TouchOut>& out);
  bool evaluate(Index p, Index ea, Index eb, const Wall* wall, const Touch& t, const Real* x, const Real* v, Real dt,
                Real offset, TouchOut& o) const;
  void gather(const TouchOut& o, Real* f);
  void cache_skeletons(const Real* x);
  const Poly& cached(Index e) const { return skel_cache_[skel_slot_[e]]; }
  std::vector<PairKey> pair_keys() const;

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
  std::vector<Index> surface_list_, fragment_, fragment_prev_;
  /// Per element pair: the overlap its skeletons already had when it became a candidate
  /// because its piece split (elements that met at an edge or a vertex of the crack; 0 for
  /// the others). That overlap is not an impact and must not push (it would create
  /// energy); it shrinks as the pair opens and is dropped when the pair leaves the list.
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
  /// Per element: index into skel_cache_ (-1: in no pair). Only the elements some pair
  /// names have their skeleton computed each step: on the intact Brazilian disc, only the
  /// elements near its jaws, not its thousands of surface elements (issue 19).
  std::vector<Index> skel_slot_;
  std::vector<Index> skel_elems_;  ///< the elements with a slot, in slot order
  std::vector<Poly> skel_cache_;   ///< their skeletons at this step
  /// skel_elems_ and the cache's size from skel_slot_ (after a checkpoint is read).
  void slots_from_map();
  std::vector<std::vector<TouchOut>> arena_;  ///< per thread
  std::vector<int> rec_thread_;               ///< per pair: whose arena holds its records
  std::vector<Index> rec_off_, rec_n_;        ///< per pair: where, how many
  std::vector<Touch> touches_;                ///< scratch of the serial paths (rebuild)
  ContactTotals totals_;
  Real elastic_ = 0, wall_power_ = 0;
  /// Viscous contact forces on the nodes, this and the last evaluation: the dissipation is
  /// booked as their trapezoidal work over the drift, as the integrator books external work.
  std::vector<Real> fdamp_, fdamp_prev_;
  bool any_damping_ = false;  ///< some material has contact damping (else the arrays stay empty)
  std::string setup_error_;
};

}  // namespace dspdem::contact
