// The envelope every view draws (render/envelope.hpp): of a jointed body's surface, where each
// element has its own nodes, only the outer faces and the faces of opened cracks are left,
// with their colours and field values.
#include <gtest/gtest.h>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDataSetSurfaceFilter.h>
#include <vtkDoubleArray.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkUnstructuredGrid.h>

#include <array>
#include <cmath>
#include <random>

#include "render/envelope.hpp"

using dspdem::render::unmatched_faces;

namespace {
constexpr int kN = 4;         // cubes per side
constexpr double kH = 0.025;  // cube edge [m]

// kN^3 cubes of edge kH, each split into six tetrahedra round its diagonal (so up to 24
// element copies of a node meet at an interior node, as in a gmsh mesh), each tetrahedron
// with its own four nodes moved at random by up to 1e-6 kH (a joint's opening before it
// fails), and the layer of cubes above y = `crack_at` (in cubes) lifted by `lift`.
vtkSmartPointer<vtkPolyData> jointed_block_surface(int crack_at, double lift) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> jitter(-1e-6 * kH, 1e-6 * kH);
  vtkNew<vtkPoints> pts;
  vtkNew<vtkUnstructuredGrid> grid;
  grid->Allocate(6 * kN * kN * kN);
  // Cube corners by bits (x, y, z); the six tetrahedra share the diagonal 0-7.
  const int tets[6][4] = {{0, 1, 3, 7}, {0, 3, 2, 7}, {0, 2, 6, 7}, {0, 6, 4, 7}, {0, 4, 5, 7}, {0, 5, 1, 7}};
  for (int i = 0; i < kN; ++i)
    for (int j = 0; j < kN; ++j)
      for (int k = 0; k < kN; ++k)
        for (const auto& t : tets) {
          vtkIdType ids[4];
          for (int v = 0; v < 4; ++v) {
            const int c = t[v];
            const double y = (j + ((c >> 1) & 1)) * kH + (j >= crack_at ? lift : 0.0);
            ids[v] = pts->InsertNextPoint((i + (c & 1)) * kH + jitter(rng), y + jitter(rng),
                                          (k + ((c >> 2) & 1)) * kH + jitter(rng));
          }
          grid->InsertNextCell(VTK_TETRA, 4, ids);
        }
  grid->SetPoints(pts);
  vtkNew<vtkDataSetSurfaceFilter> surf;
  surf->SetInputData(grid);
  surf->Update();
  return surf->GetOutput();
}

double area(vtkPolyData* pd) {
  double a = 0;
  for (vtkIdType c = 0; c < pd->GetNumberOfCells(); ++c) {
    const vtkIdType* p = nullptr;
    vtkIdType n = 0;
    pd->GetCellPoints(c, n, p);
    std::array<double, 3> x[3];
    for (int v = 0; v < 3; ++v) pd->GetPoint(p[v], x[v].data());
    double u[3], w[3];
    for (int d = 0; d < 3; ++d) u[d] = x[1][d] - x[0][d], w[d] = x[2][d] - x[0][d];
    a += 0.5 * std::sqrt(std::pow(u[1] * w[2] - u[2] * w[1], 2) + std::pow(u[2] * w[0] - u[0] * w[2], 2) +
                         std::pow(u[0] * w[1] - u[1] * w[0], 2));
  }
  return a;
}
}  // namespace

TEST(Envelope, IntactJointedBlockLeavesOnlyItsOuterFaces) {
  const auto surface = jointed_block_surface(kN, 0.0);
  ASSERT_EQ(surface->GetNumberOfCells(), 4 * 6 * kN * kN * kN);  // every tetrahedron's faces
  const auto env = unmatched_faces(surface, 1e-4);
  // Two triangles per outer square; the area is the cube's to the jitter (1e-6 relative).
  EXPECT_EQ(env->GetNumberOfCells(), 6 * kN * kN * 2);
  EXPECT_NEAR(area(env), 6 * std::pow(kN * kH, 2), 1e-5 * 6 * std::pow(kN * kH, 2));
}

TEST(Envelope, AnOpenedCrackKeepsBothOfItsFaces) {
  // Lifted by 1e-3 of the diagonal, ten times the tolerance: the crack's faces stay apart.
  const double lift = 1e-3 * std::sqrt(3.0) * kN * kH;
  const auto env = unmatched_faces(jointed_block_surface(kN / 2, lift), 1e-4);
  EXPECT_EQ(env->GetNumberOfCells(), (6 + 2) * kN * kN * 2);
  // The outer faces and the crack's two: the lift opens a slot between the layers, it adds no face.
  const double expect = 8 * std::pow(kN * kH, 2);
  EXPECT_NEAR(area(env), expect, 1e-5 * expect);
}

TEST(Envelope, SameSurfaceGivesTheSameFacesInTheSameOrder) {
  const auto surface = jointed_block_surface(kN / 2, 1e-3);
  const auto a = unmatched_faces(surface, 1e-4), b = unmatched_faces(surface, 1e-4);
  ASSERT_EQ(a->GetNumberOfCells(), b->GetNumberOfCells());
  for (vtkIdType c = 0; c < a->GetNumberOfCells(); ++c) {
    const vtkIdType *pa = nullptr, *pb = nullptr;
    vtkIdType na = 0, nb = 0;
    a->GetCellPoints(c, na, pa);
    b->GetCellPoints(c, nb, pb);
    ASSERT_EQ(na, nb);
    for (vtkIdType v = 0; v < na; ++v) {
      double xa[3], xb[3];
      a->GetPoint(pa[v], xa);
      b->GetPoint(pb[v], xb);
      for (int d = 0; d < 3; ++d) ASSERT_EQ(xa[d], xb[d]) << "face " << c;
    }
  }
}

TEST(Envelope, AKeptFaceKeepsItsOwnColourAndFieldValue) {
  // The stress and fragments views colour faces by their cell data: a face left must carry
  // the value of the face it was, not its neighbour's or none. Each face's value is a sum
  // weighted over its centre's coordinates, which no two faces share.
  auto value_at_centre = [](vtkPolyData* pd, vtkIdType c) {
    double centre[3] = {0, 0, 0}, x[3];
    const vtkIdType* p = nullptr;
    vtkIdType n = 0;
    pd->GetCellPoints(c, n, p);
    for (vtkIdType v = 0; v < n; ++v) {
      pd->GetPoint(p[v], x);
      for (int d = 0; d < 3; ++d) centre[d] += x[d] / static_cast<double>(n);
    }
    return centre[0] + 10 * centre[1] + 100 * centre[2];
  };
  const auto surface = jointed_block_surface(kN / 2, 1e-3 * std::sqrt(3.0) * kN * kH);
  vtkNew<vtkDoubleArray> field;
  field->SetName("field");
  for (vtkIdType c = 0; c < surface->GetNumberOfCells(); ++c) field->InsertNextValue(value_at_centre(surface, c));
  surface->GetCellData()->AddArray(field);
  const auto env = unmatched_faces(surface, 1e-4);
  auto* kept = vtkDoubleArray::SafeDownCast(env->GetCellData()->GetArray("field"));
  ASSERT_NE(kept, nullptr) << "the faces lost their cell data";
  ASSERT_EQ(kept->GetNumberOfTuples(), env->GetNumberOfCells());
  // Merged points move a face by the jitter at most (1e-6 kH).
  for (vtkIdType c = 0; c < env->GetNumberOfCells(); ++c)
    EXPECT_NEAR(kept->GetValue(c), value_at_centre(env, c), 1e-3 * kH) << "face " << c;
}
