// The rotation of the polar decomposition (fem/polar.hpp) against F = Q S built from a known
// rotation Q and a known symmetric positive definite stretch S: the decomposition is unique,
// so R must be Q. Stretches from 1e-6 (an elastic rock) to 0.3 (far past any the solver
// meets), rotations of any angle.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "fem/polar.hpp"

using namespace dspdem;

namespace {
Mat3 random_rotation(std::mt19937& rng) {
  std::uniform_real_distribution<Real> u(-1.0, 1.0);
  const Vec3 axis = Vec3(u(rng), u(rng), u(rng)).normalized();
  return Eigen::AngleAxis<Real>(M_PI * u(rng), axis).toRotationMatrix();
}
// I + eps x (a random symmetric matrix of entries in [-1, 1]): positive definite for eps < 1/3.
Mat3 random_stretch(std::mt19937& rng, Real eps) {
  std::uniform_real_distribution<Real> u(-1.0, 1.0);
  Mat3 A;
  for (int i = 0; i < 3; ++i)
    for (int j = i; j < 3; ++j) A(i, j) = A(j, i) = u(rng);
  return Mat3::Identity() + eps * A;
}
}  // namespace

// R is Q to 1e-14 (max entry) up to a stretch of 1e-2, to 1e-13 at 0.3. Why: Q, S and F are
// each rounded (1e-16 per entry), and the first Newton step adds the rounding of F's inverse,
// about cond(F) x 1e-16: near 1 up to a stretch of 1e-2, up to 19 at 0.3 (S's eigenvalues
// 1 -+ 0.3 x 3); later steps invert matrices ever nearer a rotation. The old stopping rule
// met the same bounds.
TEST(Polar, RecoversTheRotationOfAKnownDecomposition) {
  std::mt19937 rng(7);
  for (Real eps : {1e-6, 1e-4, 1e-2, 0.3})
    for (int k = 0; k < 200; ++k) {
      const Mat3 Q = random_rotation(rng), S = random_stretch(rng, eps);
      Mat3 R;
      ASSERT_TRUE(polar_rotation(Q * S, R));
      EXPECT_LT((R - Q).cwiseAbs().maxCoeff(), eps > 0.1 ? 1e-13 : 1e-14) << "stretch " << eps << ", sample " << k;
      EXPECT_LT((R.transpose() * R - Mat3::Identity()).cwiseAbs().maxCoeff(), 1e-14);
      EXPECT_GT(R.determinant(), 0.0);
    }
}

// The stopping rule's point: an elastic element (stretch under 1e-4, as a rock's strains)
// takes two steps, the third of the old rule having moved R by rounding only (after one step
// the error is about 9 x (3e-5 x 3)^2 / 2 = 4e-9, under the rule's 1e-8; stopping after one
// would need a stretch under 1e-2 of these). Larger stretches take more, quadratic
// convergence bounding them: a singular value of S from 0.4 to 1.6 (a stretch of 0.2) is
// within 1e-8 of 1 after five steps, so the sixth stops.
TEST(Polar, TakesTwoStepsOnAnElasticElement) {
  std::mt19937 rng(11);
  for (Real eps : {1e-6, 1e-5, 3e-5})
    for (int k = 0; k < 200; ++k) {
      Mat3 R;
      int it = 0;
      ASSERT_TRUE(polar_rotation(random_rotation(rng) * random_stretch(rng, eps), R, &it));
      EXPECT_EQ(it, 2) << "stretch " << eps << ", sample " << k;
    }
  for (int k = 0; k < 200; ++k) {
    Mat3 R;
    int it = 0;
    ASSERT_TRUE(polar_rotation(random_rotation(rng) * random_stretch(rng, 0.2), R, &it));
    EXPECT_LE(it, 6) << "sample " << k;
  }
}

TEST(Polar, RefusesAnInvertedOrCollapsedElement) {
  Mat3 R;
  EXPECT_FALSE(polar_rotation(Mat3(Eigen::Vector3d(1, 1, -1).asDiagonal()), R));  // a reflection
  EXPECT_FALSE(polar_rotation(Mat3(Eigen::Vector3d(1, 1, 0).asDiagonal()), R));   // flattened
  EXPECT_TRUE(polar_rotation(Mat3::Identity(), R));
  EXPECT_EQ(R, Mat3::Identity());
}
