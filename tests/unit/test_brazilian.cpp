// The analytic reference of the Brazilian-disc report (refdata/brazilian_analytic.md).
#include <gtest/gtest.h>

#include "post/brazilian.hpp"

using namespace dspdem;

TEST(Brazilian, PointLoadSolutionMatchesTheTabulatedValues) {
  // refdata table: sigma_yy / (2P/(pi D L)) = -3.000, -3.167, -3.762, -4.333, -5.250,
  // -10.111, -20.053 at y/D = 0, 0.1, 0.2, 0.25, 0.3, 0.4, 0.45 (printed to 3 decimals:
  // tolerance 5e-4); sigma_xx is the uniform 2P/(pi D L).
  const Real P = 33.0e3, D = 0.1427, L = 0.0713, s0 = post::splitting_stress(P, D, L);
  EXPECT_NEAR(s0, 2 * P / (M_PI * D * L), 1e-9 * s0);
  const double y[] = {0, 0.1, 0.2, 0.25, 0.3, 0.4, 0.45};
  const double ref[] = {-3.000, -3.167, -3.762, -4.333, -5.250, -10.111, -20.053};
  for (int i = 0; i < 7; ++i) {
    EXPECT_NEAR(post::sigma_yy_diameter(P, D, L, y[i] * D) / s0, ref[i], 5e-4) << "y/D = " << y[i];
    EXPECT_DOUBLE_EQ(post::sigma_xx_diameter(P, D, L, y[i] * D), s0);
  }
  // The paper's peak: 40.6 kN on D L = 0.0101759 m^2 is 2.54 MPa (refdata section 2).
  EXPECT_NEAR(post::splitting_stress(40.6e3, 1.0, 0.010175891) / 1e6, 2.54, 5e-3);
}

TEST(Brazilian, FullFieldIsTheDiameterSolutionOnTheAxisAndFreesTheRim) {
  const Real P = 33.0e3, D = 0.1427, L = 0.0713, R = D / 2, s0 = post::splitting_stress(P, D, L);
  for (double yd : {-0.45, -0.2, 0.0, 0.1, 0.3, 0.45}) {
    const auto s = post::point_load_stress(P, D, L, 0.0, yd * D);
    EXPECT_NEAR(s.xx, post::sigma_xx_diameter(P, D, L, yd * D), 1e-9 * s0);
    EXPECT_NEAR(s.yy, post::sigma_yy_diameter(P, D, L, yd * D), 1e-9 * s0);
    EXPECT_NEAR(s.xy, 0.0, 1e-9 * s0);
  }
  // Away from the load points the rim carries no traction: sigma . n = 0 (to round-off;
  // the two terms cancel from magnitudes ~ s0).
  for (double deg = 5; deg < 360; deg += 10) {
    const double a = deg * M_PI / 180, nx = std::cos(a), ny = std::sin(a);
    const auto s = post::point_load_stress(P, D, L, R * nx, R * ny);
    EXPECT_NEAR(s.xx * nx + s.xy * ny, 0.0, 1e-9 * s0) << deg;
    EXPECT_NEAR(s.xy * nx + s.yy * ny, 0.0, 1e-9 * s0) << deg;
  }
  // Along the horizontal diameter sigma_xx = s0 (D^2 - 4x^2)^2 / (D^2 + 4x^2)^2 (T&G 41).
  for (double xd : {0.1, 0.25, 0.4}) {
    const double x = xd * D, ref = s0 * std::pow((D * D - 4 * x * x) / (D * D + 4 * x * x), 2);
    EXPECT_NEAR(post::point_load_stress(P, D, L, x, 0.0).xx, ref, 1e-9 * s0) << xd;
  }
}

TEST(Brazilian, RelativeL2Error) {
  EXPECT_DOUBLE_EQ(post::relative_l2({1, 2, 3}, {1, 2, 3}), 0.0);
  EXPECT_NEAR(post::relative_l2({1.1, 2.2}, {1, 2}), 0.1, 1e-12);
}
