// Zero-thickness joint (cohesive interface) elements between element faces, and their
// insertion into a mesh (node duplication).
#pragma once
#include <string>
#include <vector>

#include "core/types.hpp"
#include "joint/lean_point.hpp"
#include "mesh/mesh.hpp"

namespace dspdem::joint {

/// Integration of the tractions over a face (eq. 7). Gauss: the paper's (3 interior points
/// on triangles, 2x2 on quadrilaterals). Nodal (Newton-Cotes): the points are the face's
/// nodes, which uncouples the node pairs and removes the traction oscillations Gauss
/// integration shows with a stiff penalty (Schellekens & de Borst 1993, IJNME 36:43).
/// Quadrilateral weights are 1/4 either way (exact for parallelogram faces).
enum class Quadrature : char { Gauss = 0, Nodal = 1 };

/// All joints of a model. A joint ties face A of element ea (outward normal from A to B) to
/// the coincident face B of element eb; node k of side A and node k of side B were the
/// same node before insertion. Triangles (between tet4) and quadrilaterals (between hex8).
struct JointSet {
  std::vector<int> npf;       ///< nodes per face: 3 or 4
  std::vector<Index> a, b;    ///< 4 slots per joint (the 4th unused for triangles)
  std::vector<Index> ea, eb;  ///< element on each side (global ids)
  std::vector<Real> area0;    ///< reference area [m^2]
  std::vector<Index> param;   ///< index into params
  std::vector<CohesiveParams> params;
  std::vector<Quadrature> quadrature;  ///< parallel to params (empty: Gauss everywhere)
  // Per integration point (3 for triangles, 4 for quadrilaterals; 4 slots per joint): the
  // lean form while the point is elastic, the full state once it is not (lean_point.hpp).
  // Read a point through point_state, whichever form it is in.
  std::vector<LeanPoint> lean;
  std::vector<char> full;            ///< per point: 1 once state[] holds it
  std::vector<CohesiveState> state;  ///< valid where full is 1
  std::vector<JointStatus> status;   ///< per joint: Broken once any of its points fails
  /// Failed joints in the order they failed: their two faces (a, b) are new free surface,
  /// the list the contact stage consumes. Appended in joint order within a step.
  std::vector<Index> failed;
  std::vector<char> newly_failed;  ///< scratch: per joint, failed during the current update
  /// Per joint: released (no longer acts) because contact took over: its two elements are
  /// in different fragments. Energy still stored in it then is booked in released_energy.
  std::vector<char> released;
  Real released_energy = 0;
  std::vector<Index> newly_released;  ///< scratch: joints released by the current force evaluation (contact's)
  /// Per joint: closed (extrinsic insertion, joint/ties.hpp): its two sides are still one
  /// material, their node pairs tied, and the joint applies no force. Empty: none closed.
  std::vector<char> closed;
  /// Per point, 4 numbers (16 per joint): where its law started when its joint opened
  /// (extrinsic insertion), the opening and the slip's two components on the face's frame
  /// (FaceFrame; the 4th number unused) of the elastic traction the face carried then. The law
  /// runs on the face's jump plus this offset, so the traction is continuous at insertion
  /// (apply_offset). Empty: no extrinsic joints.
  std::vector<Real> offset;
  /// Derived from a and b, built by the first force evaluation (the topology never changes
  /// after insertion): for each node a joint touches, the force slots that add to it, in joint
  /// order. A joint keeps side A's forces only (12 numbers, 3 per node; side B's are exactly
  /// their opposite); a slot is 2 x its offset + side, and side B's nodes subtract. The forces
  /// are then gathered in parallel over nodes, each node's sum in the order of a serial loop
  /// over the joints.
  /// (Joints writing straight into per-node slots, so that the gather streams, measured 1.2x
  /// slower on the Brazilian disc: the scattered writes cost more than the gathered reads.)
  /// Only active joints are gathered: an extrinsic body's closed joints (most of its faces,
  /// most of the run) and released ones add nothing, and summing their zeros was a fifth of
  /// the extrinsic disc's step. The gather is rebuilt when the active set changes.
  std::vector<Index> gather_node, gather_ptr, gather_slot;
  Index gather_joints = -1;         ///< joint count the gather was built for (rebuilt when it changes)
  std::vector<char> gather_active;  ///< per joint: active when the gather was built
  Index size() const { return static_cast<Index>(npf.size()); }
  /// Point i (= 4 joint + g) as a full state, whichever form it is kept in.
  CohesiveState point_state(std::size_t i) const {
    return full[i] ? state[i] : full_state(params[param[i / 4]], lean[i]);
  }
  /// Point i in its full form, switched to it (for good) if it was lean.
  CohesiveState& full_point(std::size_t i) {
    if (!full[i]) state[i] = full_state(params[param[i / 4]], lean[i]), full[i] = 1;
    return state[i];
  }
  /// What changes during a run, for checkpoints (core/archive.hpp); the rest is built from
  /// the mesh and the case, and the gather from the joint count and the active set.
  template <class Ar>
  void persist(Ar& ar) {
    ar(lean, full, state, status, failed, released, released_energy, closed, offset);
  }
  /// Joint j applies no force: released, or closed.
  bool inactive(Index j) const { return released[j] || (!closed.empty() && closed[j]); }
  Quadrature rule(Index j) const { return quadrature.empty() ? Quadrature::Gauss : quadrature[param[j]]; }
};

/// An orthonormal frame of a face's plane (unit normal n) that turns with the face: e1 along
/// a line of the mid-surface perpendicular to n (FaceFrame::line), e2 = n x e1. A slip's
/// components on it do not change under a rigid rotation, and a broken point's friction,
/// stored on it, turns with its face.
struct FaceFrame {
  Vec3 e1, e2;
  /// The line e1 follows, from the mid-surface's nodes xm: on a triangle its edge from node 0
  /// to node 1, on a quadrilateral its diagonal from node 0 to node 2. Either is perpendicular
  /// to the kernel's normal by construction (the normal is their cross product with another
  /// edge or diagonal), and not zero on a face that has a normal.
  static Vec3 line(int npf, const Vec3* xm) { return npf == 3 ? Vec3(xm[1] - xm[0]) : Vec3(xm[2] - xm[0]); }
  FaceFrame(const Vec3& line, const Vec3& n) {
    e1 = line - line.dot(n) * n;  // the plane's part: rounding aside, the line itself
    const Real l = e1.norm();
    e1 = l > 0 ? Vec3(e1 * (1.0 / l)) : Vec3(n.unitOrthogonal());  // one division, not three
    e2 = n.cross(e1);
  }
  /// The slip sv (in the plane, of magnitude ds as the kernel measured it) as the laws take it.
  Slip slip(const Vec3& sv, Real ds) const { return {ds, sv.dot(e1), sv.dot(e2)}; }
  /// A vector of components (u, v) on the frame.
  Vec3 vector(Real u, Real v) const { return u * e1 + v * e2; }
};

/// The law's opening dn and slip vector sv at a point of an extrinsic joint: the face's own
/// plus the offset o (JointSet::offset) of its insertion, its slip given on the face's frame
/// (so it turns with the face, as the face's own slip does).
inline void apply_offset(const Real* o, const FaceFrame& f, Real& dn, Vec3& sv) {
  dn += o[0];
  sv += f.vector(o[1], o[2]);
}

/// Which faces get joints: interior faces whose two elements are both marked fracturable
/// and in the same body.
struct InsertionInput {
  std::vector<char> fracturable;  ///< per global element
  std::vector<Index> body;        ///< per global element
};

struct InsertionReport {
  Index joints = 0, tri = 0, quad = 0;
  Index nodes_before = 0, nodes_after = 0;
  std::vector<std::vector<Index>> copies;  ///< per original node, its new nodes
  /// Surface groups with faces that are not element faces (their faces keep stale node ids).
  std::vector<std::string> unmatched_face_groups;
  /// Nodes split into copies although no joint touches them: elements meeting only at an
  /// edge or vertex, or across a tet/hex interface. They are no longer connected.
  Index split_without_joint = 0;
};

/// Duplicates nodes so that jointed faces no longer share nodes, rewrites the mesh
/// (connectivity, coordinates, groups) and returns the joint topology (without params).
JointSet insert_joints(Mesh& mesh, const InsertionInput& in, InsertionReport* report = nullptr);

/// Outward faces of the cell types, as local node indices (gmsh ordering).
const std::vector<std::vector<int>>& cell_faces(CellType t);

}  // namespace dspdem::joint
