// Narrow phase between two spheropolyhedra (README M3, paper eq. 8): skeletons A
// and B (convex polytopes) dilated by spheres of radii rA and rB. Every pair of features
// closer than rA + rB is a contact; each geometric contact is counted once:
//
//   vertex-face (VF, FV): the vertex projects strictly inside the triangle and lies within
//     (-R, R) of its plane (R = rA + rB). No condition on the vertex's own side, so a face
//     resting on a face is held by all its corners and tilting it changes forces smoothly.
//   vertex-edge (VE, EV): the closest point is inside the edge, the vertex is outside the
//     prisms of the edge's two triangles (those belong to VF) and no edge of the vertex's
//     own polytope points towards the contact (that belongs to edge-edge).
//   edge-edge (EE): the closest points are inside both edges.
//   vertex-vertex (VV): each vertex lies in the other's vertex cone.
//
// Nearly parallel edges meet along a line, which the vertex-edge pairs of the overlap's end
// points carry; crossed edges meet at a point, which the edge-edge pair carries. Between
// 0.05 and 0.1 rad the two are blended (Touch::fade): each fades with the angle, and the
// fade's gradient is part of the force (a couple on the two edges), so the energy the blend
// moves between pairs is work done (exactly where the faded touches are not clustered with
// others: weigh in narrow_phase.cpp). A switch at one angle made the contact energy jump by
// up to 2 J in one step in the sphere impact (src/scenes/sphere_impact/REFERENCE.md).
//
// The conditions are complementary at every hand-over (VF->VE at the prism side, VE->VV at
// the edge end, VE->EE when the vertex's edge turns towards the contact), so the force is
// continuous as a vertex slides across a face onto an edge and off it. One exception: the
// VE test hands over where the crossing is band past the vertex (along > band sin^2), the
// VV test where along > band, so for crossed edges at small angles a vertex that VE
// dropped can come back as VV at the edge's end (not yet fixed).
#pragma once
#include <array>
#include <vector>

#include "contact/polytope.hpp"

namespace dspdem::contact {

enum class Feature : int { VV = 0, VE = 1, EV = 2, EE = 3, VF = 4, FV = 5 };

/// One contact: closest points pa on skeleton A and pb on skeleton B, unit normal n from B
/// to A, gap d = (pa - pb) . n (negative when the skeletons interpenetrate).
struct Touch {
  Feature kind;
  int fa, fb;  ///< feature index on A and on B (vertex, edge or triangle, by kind)
  Vec3 pa, pb, n;
  Real d;
  Real weight = 1;  ///< share of a cluster of coincident contacts times fade (see weigh in narrow_phase.cpp)
  Real share = 1;   ///< that share alone, 1 / max(1, S): the tangential history is carried by it (PairHistory::carry)
  /// pa and pb as combinations of skeleton vertices (up to 3, unused weights 0): the
  /// normal force is spread with these, which makes it the exact gradient of the overlap
  /// energy (the rotation of a face or edge included, by the envelope theorem).
  std::array<int, 3> ia{0, 0, 0}, ib{0, 0, 0};
  std::array<Real, 3> wa{1, 0, 0}, wb{0, 0, 0};
  /// The touch's share by the angle of an edge of A (skeleton vertices a0 -> a1, vector u)
  /// and one of B (b0 -> b1, v) in the blend band; `fade` multiplies `weight`. dw_ds is the
  /// derivative of `weight` with respect to s = sin^2 of their angle (through this touch's
  /// own fade; the cluster's other fades are held fixed, see weigh, and the tangential
  /// springs are carried at constant energy across the rest, PairHistory::carry): the force
  /// gets -E dw_ds ds/dx on the four vertices, E the touch's unweighted stored energy.
  struct Fade {
    int a0, a1, b0, b1;
    Vec3 u, v;
    Real dw_ds;
  };
  Real fade = 1;
  int n_fades = 0;
  std::array<Fade, 3> fades{};  ///< one per edge of a vertex (three on tetrahedra and hexahedra)
};

/// The blend of the line and point contacts of two edges at s = sin^2 of their angle: 0 up
/// to 2.5e-3 (0.05 rad), 1 from 1e-2 (0.1 rad), a smoothstep between; and its derivative.
struct Blend {
  Real w, dw_ds;
};
Blend edge_blend(Real s);
/// s = sin^2 of the angle of u and v, and its gradients with respect to u and to v.
Real sin2_angle(const Vec3& u, const Vec3& v, Vec3* ds_du = nullptr, Vec3* ds_dv = nullptr);

/// A triangle's frame: projecting a point on it then costs two dot products and a few
/// multiplications.
struct TriFrame {
  Vec3 a, e1, e2, n;  ///< first vertex, edges from it, unit normal (outward unless the element is inverted)
  Real d00, d01, d11, inv;
  bool ok;  ///< false for a collapsed triangle (no normal; n is then UnitZ)
};

/// The frames of a skeleton's triangles (12: a hexahedron's 6 faces split in two).
using Frames = std::array<TriFrame, 12>;

/// A skeleton with what every pair it is in needs of it alone: its triangles' frames, its
/// box, its centre and its bulge, how far its own vertices lie outside its triangles' planes
/// (0 for a convex skeleton up to rounding; more for a warped hexahedron face or an inverted
/// element; infinite where a triangle is collapsed or so flat that its barycentric
/// coordinates are not to be trusted, which turns the pruning off against it). Prepared once
/// per step, it is shared by the skeleton's pairs.
/// The box, centre and bulge stand before the frames, next to the vertices: a pair's first
/// test reads the boxes, and a tetrahedron's 4 frames of the 12 then follow in the same
/// stretch of memory instead of the box lying past 8 unused frames.
struct Prepared {
  Poly poly;
  Vec3 lo, hi, centre;
  Real bulge;
  Frames frames;
};
void prepare(const Poly& p, Prepared& out);

/// Appends the contacts between A (radius rA) and B (radius rB) to `out`. Contacts closer
/// than rA + rB to each other are blended (Touch::weight) so that one geometric contact
/// found through several feature pairs counts once and the total force stays continuous.
/// Vertices and edges that a plane of the other skeleton bounds out of reach are skipped;
/// `prune = false` runs every feature test instead (for tests: the result is the same to
/// the bit, see `reach` in narrow_phase.cpp for why).
void find_touches(const Prepared& A, Real rA, const Prepared& B, Real rB, std::vector<Touch>& out, bool prune = true);
/// The same for skeletons not prepared (prepares them, B once their boxes are in reach).
void find_touches(const Prepared& A, Real rA, const Poly& B, Real rB, std::vector<Touch>& out, bool prune = true);
void find_touches(const Poly& A, Real rA, const Poly& B, Real rB, std::vector<Touch>& out, bool prune = true);

/// Contacts of skeleton A with the half-space {x : (x - p) . n <= 0} (a rigid plane of
/// radius 0): one per vertex closer than rA (kind VF, fb = 0).
void find_plane_touches(const Poly& A, Real rA, const Vec3& p, const Vec3& n, std::vector<Touch>& out);

/// Contacts of skeleton A with a jaw: the region outside the cylinder of radius R about the
/// line through p along the unit vector a, within the arc whose half opening angle has
/// cosine cos_half about the unit direction `side` (normal to a). The distance to the
/// axis is convex, so its largest value on a skeleton is at a vertex: one touch per vertex
/// closer than rA to the cylinder (kind VF, fb = 0), normal towards the axis.
void find_jaw_touches(const Poly& A, Real rA, const Vec3& p, const Vec3& a, const Vec3& side, Real R, Real cos_half,
                      std::vector<Touch>& out);

}  // namespace dspdem::contact
