#include "contact/narrow_phase.hpp"

#include <algorithm>
#include <cmath>

#include "core/error.hpp"

namespace dspdem::contact {

namespace {

// Barycentric coordinates of the projection of p on triangle (a, b, c), and its unit normal.
struct TriProj {
  Real l0, l1, l2, d;  ///< d: signed distance along the outward normal
  Vec3 n;
};

TriFrame frame(const Vec3& a, const Vec3& b, const Vec3& c) {
  TriFrame f;
  f.a = a, f.e1 = b - a, f.e2 = c - a;
  const Vec3 nn = f.e1.cross(f.e2);
  const Real area2 = nn.norm();
  f.ok = area2 > 0;
  f.n = f.ok ? Vec3(nn / area2) : Vec3::UnitZ();
  f.d00 = f.e1.dot(f.e1), f.d01 = f.e1.dot(f.e2), f.d11 = f.e2.dot(f.e2);
  const Real den = f.d00 * f.d11 - f.d01 * f.d01;
  f.inv = den > 0 ? 1.0 / den : 0.0;
  return f;
}

TriProj project(const Vec3& p, const TriFrame& f) {
  if (!f.ok) return {-1, -1, -1, 0, Vec3::UnitZ()};
  const Vec3 v = p - f.a;
  const Real d20 = v.dot(f.e1), d21 = v.dot(f.e2);
  TriProj r;
  r.l1 = (f.d11 * d20 - f.d01 * d21) * f.inv;
  r.l2 = (f.d00 * d21 - f.d01 * d20) * f.inv;
  r.l0 = 1.0 - r.l1 - r.l2;
  r.d = v.dot(f.n);
  r.n = f.n;
  return r;
}

// A vertex defers to an edge-edge pair when one of its own edges points towards the
// contact, and edge-edge pairs need their closest points inside both edges; both tests are
// generous by this band (a fraction of the edge length), so that where aligned stacks sit,
// and rounding or a slightly warped face decides, a contact is never dropped by both: it
// may be found by both, and the two are blended into one (weigh below). The band must
// exceed the tilt of element edges under strain times gap/length (~1e-3 x 0.1).
constexpr Real kBand = 1e-3;

// Membership of the other skeleton's regions (face prism, edge span, vertex cone) is
// tested almost exactly: the nearest member wins, so regions may overlap by rounding but
// a wider margin would let a face keep a vertex that has already passed its edge (with the
// face's normal instead of the edge's: a kink in the force direction).
constexpr Real kSelect = 1e-9;

bool inside(const TriProj& t, int) { return t.l0 > -kSelect && t.l1 > -kSelect && t.l2 > -kSelect; }

// Position of p along the edge from a to b, as a fraction of its length. Every vertex and
// edge test below uses this one expression so that the regions meet without gaps.
Real along(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 e = b - a;
  const Real ee = e.squaredNorm();
  return ee > 0 ? (p - a).dot(e) / ee : 0.0;
}

// Normal from B to A for points that (nearly) coincide: fall back on the centres.
Vec3 separation(const Vec3& pa, const Vec3& pb, const Vec3& ca, const Vec3& cb, Real& d) {
  Vec3 n = pa - pb;
  d = n.norm();
  if (d > 1e-12 * (ca - cb).norm()) return n / d;
  n = ca - cb;
  d = 0;
  return n.normalized();
}

// Edges closer to parallel than kParallel2 (sin^2 of the angle) meet along a line: their
// contact is carried by the end points of the overlap (vertex-edge pairs from both sides),
// not by an edge-edge pair whose closest points run off to infinity as the angle vanishes.
// Edges farther from parallel than kCrossed2 meet at a point: the edge-edge pair carries
// it, and a vertex whose edge points towards the contact defers to that pair. Between the
// two, both are blended by the angle (edge_blend). A switch at one angle let an edge-edge
// pair appear with its full overlap, up to 2 J in one step in the sphere impact: crossed
// near their middles, the edges are closer than their end points by up to 27 um.
constexpr Real kParallel2 = 2.5e-3;  // 0.05 rad
constexpr Real kCrossed2 = 1e-2;     // 0.1 rad

// Vertex i of P against a point q of Q's edge along `dir`, when i is outside Q's face
// prisms: the vertex-edge pair's share. An edge of i that runs towards the two edges'
// crossing hands the contact to the edge-edge pair there: the share is 0 if that edge is
// crossed (its angle to `dir` past the blend), 1 - w in the blend band (with its fade added
// to t: indices on P as a0, a1, Q's edge as b0, b1) and 1 if it is nearly parallel. "Runs
// towards the crossing" is along(q) > band x sin^2: for two lines along(q) = s0 sin^2, s0 the
// crossing's place on the edge, so this is s0 > band, where the edge-edge pair (accepted from
// s0 > -band) still sits on the vertex and the two are one contact (weigh). The bare test
// along(q) > band handed over at s0 = band / sin^2, up to 0.4 of the edge in the blend band,
// where the two contacts are apart: a step of the force.
struct EdgeFades {  // what vertex_edge_share gives a vertex-edge touch: its fade and their gradients
  Real fade = 1;
  int n = 0;
  std::array<Touch::Fade, 3> f;
};
Real vertex_edge_share(const Poly& P, int i, const Vec3& q, Real band, const Vec3& dir, int q0, int q1, EdgeFades& t) {
  Real share = 1;
  Real w[3], dw[3];
  int n = 0;
  for (int k : P.topo->neighbours[i]) {  // three on tetrahedra and hexahedra: fades has room
    // An edge running away from q keeps nothing from this vertex, whatever its angle: the
    // test before the angle's, which costs more.
    const Real a = along(q, P.v[i], P.v[k]);
    if (a <= 0) continue;
    const Vec3 u = P.v[k] - P.v[i];
    const Real s2 = sin2_angle(u, dir);
    if (s2 <= kParallel2 || a <= band * s2) continue;
    if (s2 >= kCrossed2) return 0;
    const Blend b = edge_blend(s2);
    share *= 1 - b.w;
    DSPDEM_ASSERT(n < static_cast<int>(t.f.size()));
    t.f[n] = {i, k, q0, q1, u, dir, 0};
    w[n] = b.w, dw[n] = b.dw_ds, ++n;
  }
  // d share / d s_m = -w'_m times the other factors.
  for (int m = 0; m < n; ++m) {
    Real others = 1;
    for (int l = 0; l < n; ++l)
      if (l != m) others *= 1 - w[l];
    t.f[m].dw_ds = -dw[m] * others;
  }
  t.n = n;
  t.fade = share;
  return share;
}

// Is q in the vertex region of vertex i of P: no edge of i points towards q (up to `band`)?
bool in_vertex_cone(const Poly& P, int i, const Vec3& q, Real band) {
  for (int k : P.topo->neighbours[i])
    if (along(q, P.v[i], P.v[k]) > band) return false;
  return true;
}

// Does q project inside a face of P that contains vertex i (then a face pair owns it)?
bool in_face_of_vertex(const Poly& P, const Frames& fp, int i, const Vec3& q) {
  const Topology& t = *P.topo;
  for (std::size_t k = 0; k < t.tris.size(); ++k) {
    const auto& tr = t.tris[k];
    if (tr[0] != i && tr[1] != i && tr[2] != i) {
      // The other triangle of a split face also belongs to the face.
      bool face_has_i = false;
      for (int f : t.vertex_faces[i]) face_has_i |= f == t.tri_face[k];
      if (!face_has_i) continue;
    }
    const TriProj pr = project(q, fp[k]);
    if (inside(pr, t.tri_diag[k])) return true;
  }
  return false;
}

// Signed distances of P's vertices to the planes of Q's triangles: [vertex][triangle].
using PlaneDistances = std::array<std::array<Real, 12>, 8>;

// The distance past which a vertex or edge of P is skipped as out of reach of Q: R plus Q's
// bulge plus a margin. Q lies in every half-space d_k <= bulge (inside the hull of its
// vertices), so a point with d_k >= R + bulge + margin on the outer side of one plane is
// farther than R from every point of Q by the margin. The margin covers where the tests take
// a point of Q that is not quite in Q: a face or an edge accepts a projection up to kSelect
// of its size outside it (well-conditioned triangles only: prepare turns the pruning off
// against a flat one), and `size` bounds those sizes. The edge-edge test accepts closest
// points within kBand of the edges' ends, far more than the margin, but then clamps them onto
// the segments: that clamping is what makes skipping an edge exact. So a skipped feature is
// one the full tests would not have made a contact of.
Real reach(Real R, Real bulge_q, Real size) { return R + bulge_q + 1e-6 * (R + size); }

// Vertex i of P against the features of Q (VF, VE, VV from P's side). `flip` when P is B.
// Fills dist with P's vertices' signed distances to Q's planes; a vertex at `skip` or more on
// the outer side of one of them is out of reach of Q and passed over (see reach).
void vertex_against(const Prepared& PP, const Prepared& QP, Real R, Real skip, bool flip, PlaneDistances& dist,
                    std::vector<Touch>& out) {
  const Poly &P = PP.poly, &Q = QP.poly;
  const Frames &fp = PP.frames, &fq = QP.frames;
  const Topology& tq = *Q.topo;
  const Vec3 &cp = PP.centre, &cq = QP.centre;
  // Vertex ip of P against a point of Q combining Q's vertices iq with weights wq.
  auto emit = [&](Feature k_pa, Feature k_pb, int fp, int fq, const Vec3& pp, const Vec3& pq, const Vec3& n_qp, Real d,
                  int ip, std::array<int, 3> iq, std::array<Real, 3> wq, const EdgeFades* faded = nullptr) {
    // n_qp points from Q to P.
    Touch t{flip ? k_pb : k_pa, fp, fq, pp, pq, n_qp, d};
    t.ia = {ip, 0, 0}, t.wa = {1, 0, 0}, t.ib = iq, t.wb = wq;
    if (faded && faded->n > 0) {
      t.fade = faded->fade, t.n_fades = faded->n;
      std::copy_n(faded->f.begin(), faded->n, t.fades.begin());
    }
    if (flip) {
      std::swap(t.fa, t.fb), std::swap(t.pa, t.pb), std::swap(t.ia, t.ib), std::swap(t.wa, t.wb);
      t.n = -t.n;
      for (int m = 0; m < t.n_fades; ++m) {
        Touch::Fade& f = t.fades[m];
        std::swap(f.a0, f.b0), std::swap(f.a1, f.b1), std::swap(f.u, f.v);
      }
    }
    out.push_back(t);
  };
  // Each vertex of P makes at most one contact with Q, with the feature of Q nearest to it
  // (the face whose prism holds it, an edge whose span holds it, or a vertex whose region
  // holds it: over a convex skeleton the nearest of these is the closest point). Noise on
  // a region boundary (aligned stacks sit there) then cannot count it twice.
  for (int i = 0; i < P.topo->nv; ++i) {
    const Vec3& p = P.v[i];
    enum { None, Face, Edge, Vertex } kind = None;
    int feat = -1;
    Real best = INFINITY, edge_t = 0;
    TriProj bp{-1, -1, -1, 0, Vec3::UnitZ()};
    Real deepest = -INFINITY;  // for a vertex inside Q: the face it is least deep behind
    int deep_face = -1;
    TriProj dp{-1, -1, -1, 0, Vec3::UnitZ()};
    bool outside = tq.tris.empty();  // a segment (no faces) has no inside
    // The planes' distances first: a vertex out of reach needs no barycentric coordinates.
    Real farthest = -INFINITY;
    for (std::size_t k = 0; k < tq.tris.size(); ++k) {
      dist[i][k] = fq[k].ok ? (p - fq[k].a).dot(fq[k].n) : 0.0;
      farthest = std::max(farthest, dist[i][k]);
    }
    if (farthest >= skip) continue;
    for (std::size_t k = 0; k < tq.tris.size(); ++k) {
      const TriProj pr = project(p, fq[k]);
      outside |= pr.d > 0;
      if (!inside(pr, tq.tri_diag[k])) continue;
      if (pr.d > 0 && pr.d < best) kind = Face, feat = static_cast<int>(k), best = pr.d, bp = pr;
      if (pr.d <= 0 && pr.d > deepest) deepest = pr.d, deep_face = static_cast<int>(k), dp = pr;
    }
    if (!outside) {
      // Inside Q's skeleton (deep penetration): push out through the nearest face.
      if (deep_face >= 0 && deepest > -R)
        kind = Face, feat = deep_face, bp = dp, best = 0;
      else
        continue;
    } else {
      for (std::size_t e = 0; e < tq.edges.size(); ++e) {
        const Vec3 &a = Q.v[tq.edges[e][0]], &b = Q.v[tq.edges[e][1]];
        const Real t = along(p, a, b);
        if (!(t > -kSelect && along(p, b, a) > -kSelect)) continue;
        const Real dist = (p - (a + t * (b - a))).norm();
        if (dist < best) kind = Edge, feat = static_cast<int>(e), best = dist, edge_t = t;
      }
      for (int j = 0; j < tq.nv; ++j) {
        const Real dist = (p - Q.v[j]).norm();
        if (dist < best && in_vertex_cone(Q, j, p, kSelect)) kind = Vertex, feat = j, best = dist;
      }
    }
    if (kind == Face) {
      if (bp.d < R) {
        const auto& t = tq.tris[feat];
        emit(Feature::VF, Feature::FV, i, feat, p, Vec3(p - bp.d * bp.n), bp.n, bp.d, i, {t[0], t[1], t[2]},
             {bp.l0, bp.l1, bp.l2});
      }
    } else if (kind == Edge) {
      // Unless an edge of the vertex points towards the contact: that is an edge-edge pair.
      const Vec3 &a = Q.v[tq.edges[feat][0]], &b = Q.v[tq.edges[feat][1]];
      const Vec3 q = a + edge_t * (b - a);
      EdgeFades share;
      if (best < R && vertex_edge_share(P, i, q, kBand, b - a, tq.edges[feat][0], tq.edges[feat][1], share) > 0) {
        Real d;
        const Vec3 n = separation(p, q, cp, cq, d);
        emit(Feature::VE, Feature::EV, i, feat, p, q, n, d, i, {tq.edges[feat][0], tq.edges[feat][1], 0},
             {1 - edge_t, edge_t, 0}, &share);
      }
    } else if (kind == Vertex && !flip) {
      // Vertex-vertex (once: from A's side), each in the other's vertex region.
      const Vec3& q = Q.v[feat];
      if (best < R && in_vertex_cone(P, i, q, kBand) && !in_face_of_vertex(P, fp, i, q)) {
        Real d;
        const Vec3 n = separation(p, q, cp, cq, d);
        Touch t{Feature::VV, i, feat, p, q, n, d};
        t.ia = {i, 0, 0}, t.ib = {feat, 0, 0}, t.wb = {1, 0, 0};
        out.push_back(t);
      }
    }
  }
}

// Closest points of segments (a0, a1) and (b0, b1) when both lie strictly inside.
// s2_out: sin^2 of their angle.
bool edge_edge(const Vec3& a0, const Vec3& a1, const Vec3& b0, const Vec3& b1, Vec3& pa, Vec3& pb, Real& s_out,
               Real& t_out, Real& s2_out) {
  const Vec3 u = a1 - a0, v = b1 - b0, w = a0 - b0;
  const Real a = u.dot(u), b = u.dot(v), c = v.dot(v), d = u.dot(w), e = v.dot(w);
  const Real den = a * c - b * b;
  if (den <= kParallel2 * a * c) return false;  // (nearly) parallel: the end points carry it (VE, EV)
  s2_out = den / (a * c);
  const Real s = (b * e - c * d) / den, t = (a * e - b * d) / den;
  if (!(s > -kBand && s < 1 + kBand && t > -kBand && t < 1 + kBand)) return false;  // interior, up to the band
  // Accepted within the band, the closest points are those of the segments themselves
  // (clamped), not of their lines: where corners line up, two coplanar edges meet as lines
  // just past one edge's end, at distance 0 with a sideways normal, and the pair took the
  // full overlap (both radii) in one step (tests/robustness/test_hard_cases.cpp, a tiny
  // contact radius: 12 % energy gained, or the run stopped by the blow-up check).
  Real sc = std::clamp<Real>(s, 0, 1), tc = std::clamp<Real>(t, 0, 1);
  if (sc != s || tc != t) {
    tc = std::clamp<Real>((b * sc + e) / c, 0, 1);
    sc = std::clamp<Real>((b * tc - d) / a, 0, 1);
  }
  pa = a0 + sc * u, pb = b0 + tc * v;
  s_out = sc, t_out = tc;
  return true;
}

// Weights that make the pair's total force continuous where contacts split or merge. Two
// contacts of a pair closer than l = rA + rB are the same geometric contact seen through
// two feature pairs (an aligned corner is VV, VF, FV and EE at once; a slightly turned
// corner is two contacts a hair apart): each contact gets w_i = 1 / sum_j phi(|x_i - x_j|/l)
// with phi(0) = 1, phi(>= 1) = 0, so a cluster of coincident contacts counts once and
// contacts farther apart than l count fully, with a smooth blend in between.
//
// Faded touches (Touch::fade f) count by their fades, S_i = sum_j f_j phi_ij, and a cluster
// counts at most once: w_i = f_i / max(1, S_i). So a touch fading alone keeps its fade, a
// faded edge-edge pair on the vertex-edge pair it replaces shares one contact with it
// (weights w and 1 - w, or 1 / (1 + w) and w / (1 + w) before the vertex pair fades), and
// touches without fades get 1 / sum phi as before. Where S_i <= 1 the weight is the fade
// and its gradient (the couple) is exact. The share 1 / max(1, S_i) is kept apart
// (Touch::share): a change of it changes a loaded tangential spring's energy with no force to
// pay for it, so the spring's history is carried across such changes at constant energy
// (PairHistory::carry), and for the tangential springs the couple's dw_i / df_i = 1 / S_i is
// then the whole change. For the normal springs, whose overlap is geometry, not history, the
// share's change (the neighbours' fades in S_i, the touches' distances) has no force: where
// S_i > 1 their couple takes dw_i / df_i as 1 / S_i (it is (S_i - f_i) / S_i^2). That is the
// case of a crossing within band of the vertex whose pair it takes over (turned there through
// the blend, that pair does work of up to ln 2 of its energy, by a review's estimate; not
// measured), and of corners sliding apart (4.5e-4 of the stored energy in
// tests/verification/test_contact.cpp).
void weigh(std::vector<Touch>& out, std::size_t first, Real l) {
  auto phi = [](Real s2) { return s2 < 1 ? (1 - s2) * (1 - s2) : 0.0; };
  const Real inv_l2 = 1.0 / (l * l);
  for (std::size_t i = first; i < out.size(); ++i) {
    Real sum = 0;
    const Vec3 xi = out[i].pa + out[i].pb;
    for (std::size_t j = first; j < out.size(); ++j)
      sum += out[j].fade * phi(0.25 * (out[j].pa + out[j].pb - xi).squaredNorm() * inv_l2);
    const Real norm = std::max<Real>(1, sum);
    out[i].share = 1 / norm;
    out[i].weight = out[i].fade / norm;
    for (int m = 0; m < out[i].n_fades; ++m) out[i].fades[m].dw_ds /= norm;
  }
}
}  // namespace

Blend edge_blend(Real s) {
  if (s <= kParallel2) return {0, 0};
  if (s >= kCrossed2) return {1, 0};
  const Real h = kCrossed2 - kParallel2, x = (s - kParallel2) / h;
  return {x * x * (3 - 2 * x), 6 * x * (1 - x) / h};
}

Real sin2_angle(const Vec3& u, const Vec3& v, Vec3* ds_du, Vec3* ds_dv) {
  const Real uu = u.squaredNorm(), vv = v.squaredNorm(), c = u.dot(v);
  if (!(uu > 0 && vv > 0)) {
    if (ds_du) ds_du->setZero();
    if (ds_dv) ds_dv->setZero();
    return 0;
  }
  const Real g = -2 * c / (uu * vv);
  if (ds_du) *ds_du = g * (v - (c / uu) * u);
  if (ds_dv) *ds_dv = g * (u - (c / vv) * v);
  return 1 - c * c / (uu * vv);
}

void prepare(const Poly& p, Prepared& out) {
  out.poly = p;
  const auto& tris = p.topo->tris;
  for (std::size_t k = 0; k < tris.size(); ++k)
    out.frames[k] = frame(p.v[tris[k][0]], p.v[tris[k][1]], p.v[tris[k][2]]);
  out.lo = out.hi = p.v[0];
  for (int k = 1; k < p.topo->nv; ++k) out.lo = out.lo.cwiseMin(p.v[k]), out.hi = out.hi.cwiseMax(p.v[k]);
  out.centre = p.centre();
  out.bulge = 0;
  for (std::size_t k = 0; k < tris.size(); ++k) {
    const TriFrame& f = out.frames[k];
    // A collapsed triangle has no plane to bound by. A nearly flat one (sin^2 of its angle
    // under 1e-8) has barycentric coordinates that round off by more than kSelect, so that
    // the face test may take points well outside it (project's inv is even 0 once the
    // determinant cancels): no bound is trusted against such a skeleton.
    if (!f.ok || !(f.d00 * f.d11 - f.d01 * f.d01 > 1e-8 * f.d00 * f.d11)) {
      out.bulge = INFINITY;
      break;
    }
    for (int j = 0; j < p.topo->nv; ++j) out.bulge = std::max(out.bulge, (p.v[j] - f.a).dot(f.n));
  }
}

void find_touches(const Prepared& A, Real rA, const Poly& B, Real rB, std::vector<Touch>& out, bool prune) {
  const Real R = rA + rB;
  Vec3 lo = B.v[0], hi = B.v[0];
  for (int k = 1; k < B.topo->nv; ++k) lo = lo.cwiseMin(B.v[k]), hi = hi.cwiseMax(B.v[k]);
  if (((A.lo.array() - R) > hi.array()).any() || ((lo.array() - R) > A.hi.array()).any()) return;
  Prepared pb;
  prepare(B, pb);
  find_touches(A, rA, pb, rB, out, prune);
}

void find_touches(const Poly& A, Real rA, const Poly& B, Real rB, std::vector<Touch>& out, bool prune) {
  Prepared pa;
  prepare(A, pa);
  find_touches(pa, rA, B, rB, out, prune);
}

void find_touches(const Prepared& PA, Real rA, const Prepared& PB, Real rB, std::vector<Touch>& out, bool prune) {
  const Poly &A = PA.poly, &B = PB.poly;
  const Real R = rA + rB;
  const std::size_t first = out.size();
  // Most candidate pairs of the broad phase do not touch: their skeletons' boxes, grown by
  // R, are apart. Checking that first skips the feature enumeration for them.
  const Vec3 &alo = PA.lo, &ahi = PA.hi, &blo = PB.lo, &bhi = PB.hi;
  if (((alo.array() - R) > bhi.array()).any() || ((blo.array() - R) > ahi.array()).any()) return;
  // Most vertices and edges of a touching pair are out of reach of the other skeleton (a
  // tetrahedron resting on a face has one vertex and three edges away from it): a plane of
  // the other side bounds them away, and their feature tests are skipped.
  const Real size = (ahi.cwiseMax(bhi) - alo.cwiseMin(blo)).norm();
  const Real skip_a = prune ? reach(R, PB.bulge, size) : INFINITY;
  const Real skip_b = prune ? reach(R, PA.bulge, size) : INFINITY;
  PlaneDistances da, db;  // A's vertices to B's planes, B's to A's
  vertex_against(PA, PB, R, skip_a, false, da, out);
  vertex_against(PB, PA, R, skip_b, true, db, out);
  const Topology &ta = *A.topo, &tb = *B.topo;
  // An edge whose two ends lie past `skip` of one plane of the other skeleton is out of reach.
  auto far_edges = [](const Topology& t, const PlaneDistances& d, std::size_t planes, Real skip) {
    std::array<bool, 12> far{};
    for (std::size_t e = 0; e < t.edges.size(); ++e)
      for (std::size_t k = 0; k < planes && !far[e]; ++k)
        far[e] = std::min(d[t.edges[e][0]][k], d[t.edges[e][1]][k]) >= skip;
    return far;
  };
  const std::array<bool, 12> far_a = far_edges(ta, da, tb.tris.size(), skip_a);
  const std::array<bool, 12> far_b = far_edges(tb, db, ta.tris.size(), skip_b);
  const Vec3 &ca = PA.centre, &cb = PB.centre;
  for (std::size_t i = 0; i < ta.edges.size(); ++i) {
    if (far_a[i]) continue;
    const Vec3 &a0 = A.v[ta.edges[i][0]], &a1 = A.v[ta.edges[i][1]];
    const Vec3 elo = a0.cwiseMin(a1).array() - R, ehi = a0.cwiseMax(a1).array() + R;
    for (std::size_t j = 0; j < tb.edges.size(); ++j) {
      if (far_b[j]) continue;
      const Vec3 &b0 = B.v[tb.edges[j][0]], &b1 = B.v[tb.edges[j][1]];
      if ((b0.cwiseMax(b1).array() < elo.array()).any() || (b0.cwiseMin(b1).array() > ehi.array()).any()) continue;
      Vec3 pa, pb;
      Real s, t, s2;
      if (!edge_edge(A.v[ta.edges[i][0]], A.v[ta.edges[i][1]], B.v[tb.edges[j][0]], B.v[tb.edges[j][1]], pa, pb, s, t,
                     s2))
        continue;
      if ((pa - pb).squaredNorm() >= R * R) continue;
      Real d;
      Vec3 n = separation(pa, pb, ca, cb, d);
      // Crossing skeletons: the line of centres tells the side.
      if (d == 0) {
        n = (A.v[ta.edges[i][1]] - A.v[ta.edges[i][0]]).cross(B.v[tb.edges[j][1]] - B.v[tb.edges[j][0]]).normalized();
        if (n.dot(ca - cb) < 0) n = -n;
      }
      Touch tc{Feature::EE, static_cast<int>(i), static_cast<int>(j), pa, pb, n, d};
      tc.ia = {ta.edges[i][0], ta.edges[i][1], 0}, tc.wa = {1 - s, s, 0};
      tc.ib = {tb.edges[j][0], tb.edges[j][1], 0}, tc.wb = {1 - t, t, 0};
      if (s2 < kCrossed2) {  // blended with the end points' vertex-edge pairs
        const Blend bl = edge_blend(s2);
        tc.fade = bl.w, tc.n_fades = 1;
        tc.fades[0] = {ta.edges[i][0], ta.edges[i][1], tb.edges[j][0], tb.edges[j][1], a1 - a0, b1 - b0, bl.dw_ds};
      }
      out.push_back(tc);
    }
  }
  weigh(out, first, R);
}

void find_plane_touches(const Poly& A, Real rA, const Vec3& p, const Vec3& n, std::vector<Touch>& out) {
  const std::size_t first = out.size();
  for (int i = 0; i < A.topo->nv; ++i) {
    const Real d = (A.v[i] - p).dot(n);
    if (d < rA) {
      Touch t{Feature::VF, i, 0, A.v[i], Vec3(A.v[i] - d * n), n, d};
      t.ia = {i, 0, 0};
      out.push_back(t);
    }
  }
  weigh(out, first, rA);
}

void find_jaw_touches(const Poly& A, Real rA, const Vec3& p, const Vec3& a, const Vec3& side, Real R, Real cos_half,
                      std::vector<Touch>& out) {
  const std::size_t first = out.size();
  for (int i = 0; i < A.topo->nv; ++i) {
    const Vec3 r = A.v[i] - p;
    const Vec3 along = r.dot(a) * a, radial = r - along;
    const Real rho = radial.norm();
    if (!(rho > 0)) continue;
    const Vec3 u = radial / rho;
    if (u.dot(side) < cos_half) continue;
    const Real d = R - rho;
    if (d < rA) {
      Touch t{Feature::VF, i, 0, A.v[i], Vec3(p + along + R * u), Vec3(-u), d};
      t.ia = {i, 0, 0};
      out.push_back(t);
    }
  }
  weigh(out, first, rA);
}

}  // namespace dspdem::contact
