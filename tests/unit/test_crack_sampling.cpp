// Crack paths compared as polylines (report/crack_sampling): the distances the Galvez
// report and its regression test use, on cases with known answers.
#include <gtest/gtest.h>

#include "report/crack_sampling.hpp"

using namespace dspdem;
using namespace dspdem::report;

TEST(CrackSampling, DistancesBetweenPolylinesHaveTheirGeometricValues) {
  // Points are (along, across) = (y, x). A vertical path x = 0 and the same shifted by 3 mm:
  // mean and Hausdorff both 3 mm.
  const std::vector<std::pair<double, double>> a = {{0, 0}, {0.05, 0}, {0.1, 0}};
  std::vector<std::pair<double, double>> b = a;
  for (auto& p : b) p.second += 0.003;
  auto d = path_distance(a, b);
  EXPECT_NEAR(d.mean, 0.003, 1e-15);
  EXPECT_NEAR(d.hausdorff, 0.003, 1e-15);
  // A path that follows a up to y = 75 mm and then turns away by 10 mm at its end: mean over
  // its points 10/3 mm; Hausdorff 10 mm (a's last point is 9.3 mm from c's last segment:
  // distances are to the polyline, not only to its vertices).
  const std::vector<std::pair<double, double>> c = {{0, 0}, {0.075, 0}, {0.1, 0.01}};
  d = path_distance(c, a);
  EXPECT_NEAR(d.mean, 0.01 / 3, 1e-15);
  EXPECT_NEAR(d.hausdorff, 0.01, 1e-15);
  EXPECT_NEAR(path_distance(a, a).hausdorff, 0.0, 0.0);
}

TEST(CrackSampling, TraceAveragesEachSliceByArea) {
  // Two pieces per slice at x = 1 mm (area 3) and x = 5 mm (area 1): mean x = 2 mm; a piece
  // outside the range or rejected by the filter does not count.
  std::vector<CrackPiece> p = {
      {Vec3(0.001, 0.01, 0), 3.0}, {Vec3(0.005, 0.01, 0), 1.0}, {Vec3(0.5, 0.01, 0.02), 9.0}, {Vec3(0.0, 0.5, 0), 1.0}};
  auto keep = [](const Vec3& q, const void*) { return q(2) < 0.01; };
  const auto path = trace_path(p, 1, 0, 0.0, 0.1, 4, keep);
  ASSERT_EQ(path.size(), 1u);
  EXPECT_NEAR(path[0].first, 0.01, 1e-15);
  EXPECT_NEAR(path[0].second, 0.002, 1e-15);
}

TEST(CrackSampling, TraceByWidthFollowsTheOpenCrackBesideASoftenedBand) {
  // One slice: a crack 0.1 mm wide at x = 55 mm (area 1) beside a band of barely softened
  // joints, 1 um wide, spread over x = -20..40 mm (area 2 each). By area the mean lies in
  // the band (x = 13.0 mm, 42 mm from the crack); by area x width 5.5 mm from it (the band
  // keeps 12 % of the weight, at its mean x = 10 mm).
  std::vector<CrackPiece> p = {{Vec3(0.055, 0.14, 0), 1.0, Vec3::UnitX(), 1e-4}};
  for (int i = 0; i < 7; ++i) p.push_back({Vec3(-0.02 + 0.01 * i, 0.14, 0), 2.0, Vec3::UnitX(), 1e-6});
  const auto by_area = trace_path(p, 1, 0, 0.1, 0.15, 1);
  const auto by_width = trace_path(p, 1, 0, 0.1, 0.15, 1, nullptr, nullptr, PathWeight::AreaWidth);
  ASSERT_EQ(by_area.size(), 1u);
  ASSERT_EQ(by_width.size(), 1u);
  EXPECT_NEAR(by_area[0].second, (0.055 + 2 * 0.07) / 15.0, 1e-12);
  EXPECT_NEAR(by_width[0].second, (0.055 * 1e-4 + 0.01 * 1.4e-5) / 1.14e-4, 1e-12);
  // A slice whose pieces have no width (a frame without the arrays) is left out, not placed at 0.
  EXPECT_TRUE(
      trace_path({{Vec3(0.01, 0.12, 0), 1.0}}, 1, 0, 0.1, 0.15, 1, nullptr, nullptr, PathWeight::AreaWidth).empty());
}

TEST(CrackSampling, ReachIsTheAreaQuantileOfTheCountedJointsAlongADirection) {
  // Joints at heights 10, 20, 30, 40 mm above an origin at y = -0.1 (areas 4, 3, 2, 1), the
  // one at 30 mm not broken. Broken area 8: half of it lies at or below 10 mm, 7/8 at or
  // below 20 mm, all of it at or below 40 mm.
  const std::vector<CrackPiece> where = {{Vec3(0.3, -0.09, 0), 4.0},
                                         {Vec3(-0.2, -0.08, 0.1), 3.0},
                                         {Vec3(0.0, -0.07, 0), 2.0},
                                         {Vec3(0.0, -0.06, -0.2), 1.0}};
  const std::vector<int> states = {2, 2, 1, 2};
  const Vec3 o(0, -0.1, 0);
  auto r = crack_reach(where, states, o, Vec3::UnitY(), 0.5);
  EXPECT_DOUBLE_EQ(r.area, 8.0);
  EXPECT_NEAR(r.at_quantile, 0.01, 1e-15);
  EXPECT_NEAR(r.furthest, 0.04, 1e-15);
  EXPECT_NEAR(crack_reach(where, states, o, Vec3::UnitY(), 0.875).at_quantile, 0.02, 1e-15);
  EXPECT_NEAR(crack_reach(where, states, o, Vec3::UnitY(), 0.9).at_quantile, 0.04, 1e-15);
  EXPECT_NEAR(crack_reach(where, states, o, Vec3::UnitY(), 1.0).at_quantile, 0.04, 1e-15);
  // Softening joints counted too (min_state 1): the one at 30 mm joins.
  r = crack_reach(where, states, o, Vec3::UnitY(), 0.9, 1);
  EXPECT_DOUBLE_EQ(r.area, 10.0);
  EXPECT_NEAR(r.at_quantile, 0.03, 1e-15);
  // Along -y from y = 0 the order turns round: the joint at 40 mm (area 1) comes first at
  // s = 60 mm, then 20 mm (area 3) at 80 mm, which takes the half of 8 (1 + 3 = 4).
  r = crack_reach(where, states, Vec3(0, 0, 0), -Vec3::UnitY(), 0.5);
  EXPECT_NEAR(r.at_quantile, 0.08, 1e-15);
  EXPECT_NEAR(r.furthest, 0.09, 1e-15);
  // Nothing broken: all zero, not the position of a joint.
  r = crack_reach(where, {0, 1, 0, 0}, o, Vec3::UnitY(), 0.5);
  EXPECT_EQ(r.area, 0.0);
  EXPECT_EQ(r.at_quantile, 0.0);
  EXPECT_EQ(r.furthest, 0.0);
  // Positions and states of different joint sets, or a quantile outside (0, 1]: an error.
  EXPECT_THROW(crack_reach(where, {2, 2}, o, Vec3::UnitY(), 0.5), std::exception);
  EXPECT_THROW(crack_reach(where, states, o, Vec3::UnitY(), 0.0), std::exception);
  EXPECT_THROW(crack_reach(where, states, o, Vec3::UnitY(), 1.5), std::exception);
}

TEST(CrackSampling, JointsCountedByBandOfHeight) {
  // Four joints at heights 0.25, 0.5, 0.75 and 1 (binary fractions, so the edges are met
  // exactly), states 2, 2, 1, 2, in bands 0-0.375, 0.375-0.75 and 0.75-1: a joint on an inner
  // edge (0.75) falls in the band above it, one on the top edge (1) in the last band; joints
  // outside every band are in none.
  const std::vector<CrackPiece> where = {
      {Vec3(0.3, 0.25, 0), 4.0}, {Vec3(-0.2, 0.5, 0.1), 3.0}, {Vec3(0, 0.75, 0), 2.0}, {Vec3(0, 1.0, -0.2), 1.0}};
  const std::vector<int> states = {2, 2, 1, 2};
  const Vec3 o = Vec3::Zero(), up = Vec3::UnitY();
  const std::vector<double> edges = {0.0, 0.375, 0.75, 1.0};
  EXPECT_EQ(count_by_band(where, states, o, up, edges), (std::vector<long>{1, 1, 1}));
  EXPECT_EQ(count_by_band(where, states, o, up, edges, 1), (std::vector<long>{1, 1, 2}));
  EXPECT_EQ(count_by_band(where, states, o, up, edges, 0), (std::vector<long>{1, 1, 2}));
  EXPECT_EQ(count_by_band(where, states, o, up, {0.375, 0.875}), (std::vector<long>{1}))
      << "0.25 below the first edge and 1 above the last are outside (0.75 is not broken)";
  EXPECT_THROW(count_by_band(where, {2, 2}, o, up, edges), std::exception);
  EXPECT_THROW(count_by_band(where, states, o, up, {0.75, 0.25}), std::exception);
  EXPECT_THROW(count_by_band(where, states, o, up, {0.75}), std::exception);
}
