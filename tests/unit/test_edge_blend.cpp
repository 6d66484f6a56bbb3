// The blend of nearly parallel and crossed edges (narrow_phase.hpp: edge_blend, sin2_angle)
// alone: its ends, its smoothness and the gradients the contact forces use.
#include <gtest/gtest.h>

#include <cmath>

#include "contact/narrow_phase.hpp"

using namespace dspdem;
using namespace dspdem::contact;

TEST(EdgeBlend, RisesSmoothlyFromParallelToCrossed) {
  // 0 up to sin^2 = 2.5e-3 (0.05 rad), 1 from 1e-2 (0.1 rad), with zero slope at both
  // ends (a C1 blend: no kink in the force where it starts or ends) and rising between.
  EXPECT_EQ(edge_blend(0).w, 0);
  EXPECT_EQ(edge_blend(2.5e-3).w, 0);
  EXPECT_EQ(edge_blend(1e-2).w, 1);
  EXPECT_EQ(edge_blend(0.5).w, 1);
  EXPECT_NEAR(edge_blend(2.5e-3 + 1e-12).dw_ds, 0, 1e-6);
  EXPECT_NEAR(edge_blend(1e-2 - 1e-12).dw_ds, 0, 1e-6);
  EXPECT_NEAR(edge_blend(6.25e-3).w, 0.5, 1e-15);  // the middle of the band
  Real prev = 0;
  for (Real s = 2.5e-3; s <= 1e-2; s += 1e-5) {
    const Blend b = edge_blend(s);
    EXPECT_GE(b.w, prev);
    prev = b.w;
    // Its derivative is that of its values: a central difference errs by h^2 |w'''| / 6 =
    // 2 h^2 / H^3 = 5e-8 (H = 7.5e-3 the band) plus round-off 1e-16 / h, on slopes up to 200.
    const Real h = 1e-7;
    if (s > 2.5e-3 + h && s < 1e-2 - h) {
      EXPECT_NEAR(b.dw_ds, (edge_blend(s + h).w - edge_blend(s - h).w) / (2 * h), 1e-6);
    }
  }
}

TEST(EdgeBlend, Sin2OfTheAngleAndItsGradients) {
  // sin^2 of the angle does not depend on the edges' lengths or directions, and its
  // gradients are those of its values (central differences: relative error ~h^2 = 1e-12,
  // against round-off 1e-16 / h = 1e-10 of the value's scale).
  const Vec3 u(0.02, 0.001, -0.0005), v(-0.015, 0.002, 0.0011);
  Vec3 gu, gv;
  const Real s = sin2_angle(u, v, &gu, &gv);
  const Real c = u.dot(v) / (u.norm() * v.norm());
  EXPECT_NEAR(s, 1 - c * c, 1e-15);
  EXPECT_NEAR(sin2_angle(-3 * u, 0.5 * v), s, 1e-15);
  for (int d = 0; d < 3; ++d) {
    const Real h = 1e-6 * u.norm();
    Vec3 e = Vec3::Zero();
    e(d) = h;
    const Real fd_u = (sin2_angle(u + e, v) - sin2_angle(u - e, v)) / (2 * h);
    const Real fd_v = (sin2_angle(u, v + e) - sin2_angle(u, v - e)) / (2 * h);
    EXPECT_NEAR(gu(d), fd_u, 1e-6 * gu.norm());
    EXPECT_NEAR(gv(d), fd_v, 1e-6 * gv.norm());
  }
  // No gradient along the edge itself (turning it is what changes the angle).
  EXPECT_NEAR(gu.dot(u), 0, 1e-12 * gu.norm() * u.norm());
  EXPECT_NEAR(gv.dot(v), 0, 1e-12 * gv.norm() * v.norm());
  // A degenerate edge has no angle.
  EXPECT_EQ(sin2_angle(Vec3::Zero(), v, &gu, &gv), 0);
  EXPECT_EQ(gu.norm(), 0);
}
