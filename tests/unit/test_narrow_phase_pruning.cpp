// The narrow phase skips the vertices and edges of one skeleton that a plane of the other
// bounds out of reach (narrow_phase.cpp: prepare's bulge, reach). That must change nothing:
// on random pairs of tetrahedra, warped hexahedra, inverted tetrahedra, slivers, needles and
// segments, at distances from interpenetrating to out of reach, and on aligned stacks where
// features sit on each other's region boundaries, the pruned search gives the same touches
// as the full one, to the bit and in the same order.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "contact/narrow_phase.hpp"

using namespace dspdem;
using namespace dspdem::contact;

namespace {

Mat3 random_rotation(std::mt19937& rng) {
  std::normal_distribution<Real> g(0, 1);
  return Mat3(Eigen::AngleAxis<Real>(std::uniform_real_distribution<Real>(0, M_PI)(rng),
                                     Vec3(g(rng), g(rng), g(rng)).normalized()));
}

// Reference cells with positive volume in the mesh's node order (outward triangles).
Poly tet(const Vec3& at, const Mat3& rot, Real size, Real jitter, std::mt19937& rng, bool inverted = false) {
  std::uniform_real_distribution<Real> u(-jitter, jitter);
  const Vec3 ref[4] = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
  Poly p;
  p.topo = &topology(Shape::Tet);
  for (int k = 0; k < 4; ++k)
    p.v[k] = at + size * (rot * (ref[k] - Vec3::Constant(0.25) + Vec3(u(rng), u(rng), u(rng))));
  if (inverted) std::swap(p.v[1], p.v[2]);  // negative volume: its triangles face inwards
  return p;
}

Poly hex(const Vec3& at, const Mat3& rot, Real size, Real jitter, std::mt19937& rng) {
  std::uniform_real_distribution<Real> u(-jitter, jitter);
  const Vec3 ref[8] = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0),
                       Vec3(0, 0, 1), Vec3(1, 0, 1), Vec3(1, 1, 1), Vec3(0, 1, 1)};
  Poly p;
  p.topo = &topology(Shape::Hex);
  for (int k = 0; k < 8; ++k)
    p.v[k] = at + size * (rot * (ref[k] - Vec3::Constant(0.5) + Vec3(u(rng), u(rng), u(rng))));
  return p;
}

// A tetrahedron squashed towards the plane through its centre normal to `axis` (a sliver at
// squash 1e-6 to 1e-9: its faces are nearly flat triangles, whose barycentric coordinates
// round off badly), or one vertex pulled onto the line of two others (a needle face).
Poly degenerate(const Vec3& at, const Mat3& rot, Real size, Real squash, bool needle, std::mt19937& rng) {
  Poly p = tet(at, rot, size, 0.2, rng);
  if (needle) {
    p.v[2] = p.v[0] + 0.5 * (p.v[1] - p.v[0]) + squash * size * (rot * Vec3::UnitZ());
    return p;
  }
  const Vec3 axis = rot * Vec3::UnitZ();
  for (int k = 0; k < 4; ++k) p.v[k] -= (1 - squash) * (p.v[k] - at).dot(axis) * axis;
  return p;
}

Poly segment(const Vec3& at, const Mat3& rot, Real length) {
  Poly p;
  p.topo = &topology(Shape::Segment);
  p.v[0] = at - 0.5 * length * (rot * Vec3::UnitX()), p.v[1] = at + 0.5 * length * (rot * Vec3::UnitX());
  return p;
}

// Every field of every touch, compared exactly; returns the number of touches.
std::size_t expect_same(const Poly& A, Real rA, const Poly& B, Real rB, const std::string& what) {
  std::vector<Touch> full, pruned;
  find_touches(A, rA, B, rB, full, false);
  find_touches(A, rA, B, rB, pruned, true);
  EXPECT_EQ(full.size(), pruned.size()) << what;
  if (full.size() != pruned.size()) return 0;
  for (std::size_t i = 0; i < full.size(); ++i) {
    const Touch &f = full[i], &p = pruned[i];
    EXPECT_TRUE(f.kind == p.kind && f.fa == p.fa && f.fb == p.fb && f.pa == p.pa && f.pb == p.pb && f.n == p.n &&
                f.d == p.d && f.weight == p.weight && f.ia == p.ia && f.ib == p.ib && f.wa == p.wa && f.wb == p.wb &&
                f.fade == p.fade && f.n_fades == p.n_fades)
        << what << ", touch " << i;
    for (int m = 0; m < f.n_fades; ++m)
      EXPECT_TRUE(f.fades[m].a0 == p.fades[m].a0 && f.fades[m].a1 == p.fades[m].a1 && f.fades[m].b0 == p.fades[m].b0 &&
                  f.fades[m].b1 == p.fades[m].b1 && f.fades[m].u == p.fades[m].u && f.fades[m].v == p.fades[m].v &&
                  f.fades[m].dw_ds == p.fades[m].dw_ds)
          << what << ", touch " << i << ", fade " << m;
  }
  return full.size();
}

}  // namespace

TEST(NarrowPhasePruning, RandomPairsGiveTheFullSearchsTouches) {
  std::mt19937 rng(20261128);
  std::uniform_real_distribution<Real> unit(0, 1);
  std::normal_distribution<Real> g(0, 1);
  const Real size = 0.01;
  std::size_t touches = 0, touching_pairs = 0;
  for (int n = 0; n < 28000; ++n) {
    // tet, tet, hex, inverted tet, segment, sliver, needle
    const int kind_a = n % 7, kind_b = (n / 7) % 7;
    auto make = [&](int kind, const Vec3& at) {
      const Mat3 rot = random_rotation(rng);
      const Real squash = std::pow(10.0, -9 + 3 * unit(rng));
      if (kind <= 1) return tet(at, rot, size, 0.2, rng);
      if (kind == 2) return hex(at, rot, size, 0.05, rng);  // warped faces: a bulge of up to ~1e-3 m
      if (kind == 3) return tet(at, rot, size, 0.2, rng, true);
      if (kind == 5) return degenerate(at, rot, size, squash, false, rng);
      if (kind == 6) return degenerate(at, rot, size, squash, true, rng);
      return segment(at, rot, 2 * size);
    };
    // Centres from coincident to 1.5 sizes apart: from deep overlap to out of reach.
    const Vec3 offset = 1.5 * size * unit(rng) * Vec3(g(rng), g(rng), g(rng)).normalized();
    const Poly A = make(kind_a, Vec3::Zero()), B = make(kind_b, offset);
    // Radii from 1e-3 to 0.3 of the size (the cases use 0.1-0.3 of the inradius).
    const Real rA = size * std::pow(10.0, -3 + 2.5 * unit(rng)), rB = size * std::pow(10.0, -3 + 2.5 * unit(rng));
    const std::size_t k = expect_same(A, rA, B, rB, "random pair " + std::to_string(n));
    touches += k, touching_pairs += k > 0;
  }
  // The draw must reach the cases that matter: many touching pairs, not only far ones.
  EXPECT_GT(touching_pairs, 4000u);
  EXPECT_GT(touches, 20000u);
}

TEST(NarrowPhasePruning, AlignedStacksGiveTheFullSearchsTouches) {
  // Cubes face to face, edge to edge and corner to corner, slightly turned or shifted, where
  // vertices sit on each other's face prisms, edge spans and vertex cones (the blends and
  // the cluster weights all act there).
  std::mt19937 rng(7);
  std::uniform_real_distribution<Real> small(-1e-4, 1e-4);
  const Real a = 0.01, r = 0.001;
  std::size_t touches = 0;
  const Vec3 dirs[] = {Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(1, 1, 1), Vec3(1, 0.5, 0)};
  for (int n = 0; n < 2000; ++n) {
    const Vec3 d = dirs[n % 4];
    const Real gap = (n / 4 % 5 - 2) * 0.5 * r;  // from overlapping by r to apart by r
    const Mat3 turn(Eigen::AngleAxis<Real>(std::abs(small(rng)) * (n % 3), Vec3(0, 0, 1)));
    const Poly A = hex(Vec3::Zero(), Mat3::Identity(), a, 0, rng);
    const Vec3 at = a * d + gap * d.normalized() + Vec3(small(rng), small(rng), 0) * (n % 2);
    const Poly B = hex(at, turn, a, 0, rng);
    touches += expect_same(A, r, B, r, "stack " + std::to_string(n));
    // The same with the cubes' corner tetrahedra (a corner and its three neighbours): A's at
    // (1, 0, 0), B's at its (0, 0, 0).
    Poly ta, tb;
    ta.topo = tb.topo = &topology(Shape::Tet);
    const int ca[4] = {1, 0, 2, 5}, cb[4] = {0, 1, 3, 4};
    for (int k = 0; k < 4; ++k) ta.v[k] = A.v[ca[k]], tb.v[k] = B.v[cb[k]];
    if ((ta.v[1] - ta.v[0]).cross(ta.v[2] - ta.v[0]).dot(ta.v[3] - ta.v[0]) < 0) std::swap(ta.v[1], ta.v[2]);
    if ((tb.v[1] - tb.v[0]).cross(tb.v[2] - tb.v[0]).dot(tb.v[3] - tb.v[0]) < 0) std::swap(tb.v[1], tb.v[2]);
    touches += expect_same(ta, r, tb, r, "tet stack " + std::to_string(n));
  }
  EXPECT_GT(touches, 2000u);
}
