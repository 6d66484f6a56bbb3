// What a field looks like: display units, round ticks and scale-bar lengths, and fragment
// colours that differ between touching pieces (render/colormap.hpp); the walls' shapes.
#include <gtest/gtest.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkLookupTable.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkUnstructuredGrid.h>

#include <cmath>

#include "render/colormap.hpp"
#include "run/wall_shapes.hpp"

using namespace dspdem::render;

TEST(Colormap, StressesInMPaSignedOnesCentredDisplacementInMm) {
  EXPECT_FALSE(field_display("von_mises").is_signed);
  EXPECT_DOUBLE_EQ(field_display("von_mises").scale, 1e-6);
  EXPECT_TRUE(field_display("max_principal").is_signed);
  EXPECT_TRUE(field_display("sigma_xy").is_signed);
  EXPECT_NE(field_display("sigma_xy").title.find("[MPa]"), std::string::npos);
  EXPECT_DOUBLE_EQ(field_display("displacement").scale, 1e3);
  EXPECT_NE(field_display("displacement").title.find("[mm]"), std::string::npos);
}

TEST(Colormap, DivergingMapIsNeutralAtZeroAndViridisRunsDarkToLight) {
  vtkNew<vtkLookupTable> lut;
  fill_lookup_table(lut, true, -3, 3);
  double lo[3], mid[3], hi[3];
  lut->GetColor(-3, lo), lut->GetColor(0, mid), lut->GetColor(3, hi);
  EXPECT_GT(lo[2], lo[0]) << "negative end not blue";
  EXPECT_GT(hi[0], hi[2]) << "positive end not red";
  // Moreland's midpoint is a light grey (about 0.87 in every channel): no hue at zero.
  EXPECT_NEAR(mid[0], mid[2], 0.06);
  EXPECT_GT(mid[1], 0.8);
  fill_lookup_table(lut, false, 0, 1);
  auto luminance = [&](double v) {
    double c[3];
    lut->GetColor(v, c);
    return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
  };
  for (int i = 0; i < 10; ++i) EXPECT_LT(luminance(i / 10.0), luminance((i + 1) / 10.0)) << i;
}

TEST(Colormap, TicksAreRoundAndInsideTheRange) {
  EXPECT_EQ(nice_ticks(0, 17.6, 6), (std::vector<double>{0, 5, 10, 15}));
  EXPECT_EQ(nice_ticks(-3.5, 3.5, 6), (std::vector<double>{-3, -2, -1, 0, 1, 2, 3}));
  const auto t = nice_ticks(0.12, 0.47, 6);
  ASSERT_FALSE(t.empty());
  EXPECT_DOUBLE_EQ(t.front(), 0.15);
  EXPECT_DOUBLE_EQ(t.back(), 0.45);
  EXPECT_EQ(t.size(), 7u);
  EXPECT_TRUE(nice_ticks(1, 1, 5).empty());
  EXPECT_TRUE(nice_ticks(1e20, 1e20 * (1 + 1e-15), 6).empty()) << "a range a few ulps wide far from zero";
  EXPECT_DOUBLE_EQ(nice_length(0.037), 0.02);
  EXPECT_DOUBLE_EQ(nice_length(0.05), 0.05);
  EXPECT_DOUBLE_EQ(nice_length(9.99), 5);
  EXPECT_DOUBLE_EQ(nice_length(0), 0);
}

TEST(Colormap, TouchingPiecesDifferAndOthersKeepTheColourOfTheirRank) {
  // Pieces 0..24 by size; 20 colours. Without contacts every piece has rank % 20, so 0 and 20
  // share a colour; when they touch, 20 takes the first colour none of its larger neighbours has.
  std::vector<int> c = piece_colours(25, {}, 20);
  EXPECT_EQ(c[20], 0);
  c = piece_colours(25, {{20, 0}, {20, 1}, {3, 4}}, 20);
  EXPECT_EQ(c[0], 0);
  EXPECT_EQ(c[4], 4);  // no clash: its rank's colour
  EXPECT_EQ(c[20], 2);
  // A piece touching all 20 colours' pieces keeps its rank's colour (nothing is free).
  std::vector<std::pair<int, int>> all;
  for (int i = 0; i < 20; ++i) all.emplace_back(i, 21);
  EXPECT_EQ(piece_colours(22, all, 20)[21], 1);
}

// The walls drawn where a frame records them (run/wall_shapes.hpp): a box of half sizes
// (1, 2, 3) turned 90 degrees about z and moved to (10, 0, 0) spans x 8..12, y -1..1.
TEST(WallShapes, ABoxAndACylinderAtTheirRecordedPoses) {
  std::vector<dspdem::WallConfig> walls(2);
  walls[0].wall.type = dspdem::contact::Wall::Type::Box;
  walls[0].wall.half = dspdem::Vec3(1, 2, 3);
  walls[1].wall.type = dspdem::contact::Wall::Type::Cylinder;
  walls[1].wall.radius = 0.5, walls[1].wall.half_length = 2, walls[1].wall.axis0 = dspdem::Vec3::UnitZ();
  vtkNew<vtkUnstructuredGrid> frame;
  const double bounds[6] = {0, 1, 0, 1, 0, 1};
  EXPECT_EQ(dspdem::wall_surfaces(walls, frame, bounds), nullptr) << "no poses recorded: nothing to draw";
  vtkNew<vtkDoubleArray> pose;
  pose->SetName("wall_pose");
  pose->SetNumberOfComponents(7);
  const double s = std::sqrt(0.5);
  const double box[7] = {10, 0, 0, s, 0, 0, s};  // 90 degrees about z
  const double cyl[7] = {0, 0, -20, 1, 0, 0, 0};
  pose->InsertNextTuple(box);
  pose->InsertNextTuple(cyl);
  frame->GetFieldData()->AddArray(pose);
  const auto pd = dspdem::wall_surfaces(walls, frame, bounds);
  ASSERT_NE(pd, nullptr);
  double b[6];
  pd->GetBounds(b);
  // Points are single precision (VTK's sources) and the caps faceted (16 rings: the last
  // ring short of the pole by 0.5 (1 - sin(7 pi / 15)) = 2.7e-3).
  EXPECT_NEAR(b[0], -0.5, 1e-5);   // the cylinder's side
  EXPECT_NEAR(b[1], 12, 1e-5);     // the box: 10 + its y half size turned onto x
  EXPECT_NEAR(b[2], -1, 1e-5);     // the box's x half size turned onto y
  EXPECT_NEAR(b[4], -22.5, 5e-3);  // the cylinder's lower hemispherical end
  EXPECT_NEAR(b[5], 3, 1e-5);
}
