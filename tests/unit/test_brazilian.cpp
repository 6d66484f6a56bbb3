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

TEST(Brazilian, RelativeL2Error) {
  EXPECT_DOUBLE_EQ(post::relative_l2({1, 2, 3}, {1, 2, 3}), 0.0);
  EXPECT_NEAR(post::relative_l2({1.1, 2.2}, {1, 2}), 0.1, 1e-12);
}
