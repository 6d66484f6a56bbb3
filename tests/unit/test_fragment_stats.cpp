// Fragment statistics read back from a frame (report/fragment_stats), fragments over time
// from a run's fragments.csv (report/fragment_history) and the montage tiling
// (render/montage), on data whose answers are known by hand.
#include <gtest/gtest.h>
#include <unistd.h>
#include <vtkCellData.h>
#include <vtkDoubleArray.h>
#include <vtkImageData.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridWriter.h>

#include <filesystem>
#include <fstream>

#include "core/error.hpp"
#include "render/montage.hpp"
#include "report/fragment_history.hpp"
#include "report/fragment_stats.hpp"

namespace fs = std::filesystem;
using namespace dspdem;

namespace {
// Three cells: two unit-corner tets (volume 1/6 each, before deformation) in fragment 0,
// one unit cube in fragment 7 of the second material. The points are written displaced by
// u = (0.5 x, 0, 0): the volumes read must be the reference ones all the same.
fs::path write_frame(bool with_displacement = true) {
  vtkNew<vtkPoints> pts;
  const double X[][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0, 0, -1},  // tets
                         {2, 0, 0}, {3, 0, 0}, {3, 1, 0}, {2, 1, 0}, {2, 0, 1},
                         {3, 0, 1}, {3, 1, 1}, {2, 1, 1}};  // cube
  vtkNew<vtkDoubleArray> u;
  u->SetName("displacement");
  u->SetNumberOfComponents(3);
  for (const auto& p : X) {
    const double d[3] = {0.5 * p[0], 0, 0};
    pts->InsertNextPoint(p[0] + d[0], p[1], p[2]);
    u->InsertNextTuple(d);
  }
  vtkNew<vtkUnstructuredGrid> g;
  g->SetPoints(pts);
  const vtkIdType t1[] = {0, 1, 2, 3}, t2[] = {0, 2, 1, 4}, h[] = {5, 6, 7, 8, 9, 10, 11, 12};
  g->InsertNextCell(10, 4, t1);
  g->InsertNextCell(10, 4, t2);
  g->InsertNextCell(12, 8, h);
  if (with_displacement) g->GetPointData()->AddArray(u);
  vtkNew<vtkIntArray> frag, mat;
  frag->SetName("fragment"), mat->SetName("material");
  for (int v : {0, 0, 7}) frag->InsertNextValue(v);
  for (int v : {0, 0, 1}) mat->InsertNextValue(v);
  g->GetCellData()->AddArray(frag);
  g->GetCellData()->AddArray(mat);
  // Named by process: ctest runs this file's tests side by side (ctest -j2).
  const fs::path file = fs::temp_directory_path() / ((with_displacement ? "dspdem_frag_" : "dspdem_frag_nou_") +
                                                     std::to_string(::getpid()) + ".vtu");
  vtkNew<vtkXMLUnstructuredGridWriter> w;
  w->SetInputData(g);
  w->SetFileName(file.c_str());
  w->Write();
  return file;
}
}  // namespace

TEST(FragmentStats, MassesFromReferenceVolumesAndDensities) {
  const fs::path frame = write_frame();
  const auto s = report::fragment_stats(frame.string(), {3000.0, 100.0});
  fs::remove(frame);
  ASSERT_EQ(s.count(), 2);
  // Tets: 2 x 1/6 x 3000 = 1000 kg; cube: 1 x 100 = 100 kg (not 1.5 x 100, its deformed volume).
  EXPECT_NEAR(s.masses[0], 1000.0, 1e-9);
  EXPECT_NEAR(s.masses[1], 100.0, 1e-9);
  EXPECT_EQ(s.elements[0], 2);
  EXPECT_EQ(s.elements[1], 1);
  EXPECT_NEAR(s.total_mass, 1100.0, 1e-9);
  EXPECT_NEAR(s.largest_fraction(), 1000.0 / 1100.0, 1e-12);
  EXPECT_EQ(s.count_at_least(0.05), 2);
  EXPECT_EQ(s.count_at_least(0.5), 1);
  EXPECT_EQ(s.single_element(), 1);
  const auto d = report::cumulative_mass_distribution(s);
  ASSERT_EQ(d.size(), 2u);
  EXPECT_DOUBLE_EQ(d[0].first, 100.0);
  EXPECT_NEAR(d[0].second, 100.0 / 1100.0, 1e-12);
  EXPECT_DOUBLE_EQ(d[1].second, 1.0);
}

TEST(FragmentStats, RefusesAFrameWithoutWhatItNeedsNamingTheFile) {
  const std::string f = write_frame(false).string();
  try {
    report::fragment_stats(f, {3000.0, 100.0});
    FAIL() << "a frame without displacement was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(f), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("displacement"), std::string::npos) << e.what();
  }
  fs::remove(f);
  // A material index the case does not have.
  const fs::path frame = write_frame();
  EXPECT_THROW(report::fragment_stats(frame.string(), {3000.0}), Error);
  fs::remove(frame);
}

// Fragments over time (report/fragment_history), as every run writes them: per frame the
// count and the largest pieces by rank.
namespace {
fs::path write_fragments_csv(const std::string& body) {
  const fs::path file = fs::temp_directory_path() / ("dspdem_fragcsv_" + std::to_string(::getpid()) + ".csv");
  std::ofstream(file) << "frame,time,count,rank,id,mass,elements,x,y,z\n" << body;
  return file;
}
}  // namespace

TEST(FragmentHistory, ReadsEachFramesCountAndLargestPiecesInOrder) {
  const fs::path f = write_fragments_csv(
      "0,0,1,1,5,10,40,0,0,0\n"
      "1,2.5e-05,3,1,5,7,28,0.1,0.2,0.3\n"
      "1,2.5e-05,3,2,9,2.5,10,1,2,3\n"
      "1,2.5e-05,3,3,4,0.5,2,0,0,0\n");
  const auto h = report::fragment_history(f.string());
  fs::remove(f);
  ASSERT_EQ(h.size(), 2u);
  EXPECT_EQ(h[0].frame, 0);
  EXPECT_EQ(h[0].count, 1);
  EXPECT_DOUBLE_EQ(h[0].mass(0), 10.0);
  EXPECT_DOUBLE_EQ(h[0].mass(1), 0.0);  // not listed: none
  EXPECT_DOUBLE_EQ(h[1].time, 2.5e-5);
  EXPECT_EQ(h[1].count, 3);
  ASSERT_EQ(h[1].largest.size(), 3u);
  EXPECT_DOUBLE_EQ(h[1].mass(1), 2.5);
  EXPECT_EQ(h[1].largest[1].elements, 10);
  EXPECT_DOUBLE_EQ(h[1].largest[1].z, 3.0);
  EXPECT_EQ(h[1].count_at_least(1.0), 2);  // 7 and 2.5 kg, not 0.5
  EXPECT_EQ(h[1].count_at_least(2.5), 2);  // at least: the bound itself counts
}

TEST(FragmentHistory, RefusesFramesOrRanksOutOfOrderNamingFileAndRow) {
  // A frame listing rank 2 before rank 1, and two runs' files joined (frame 0 again after
  // frame 1): either way a piece would be read into the wrong frame.
  const std::pair<const char*, const char*> bad[] = {
      {"0,0,1,1,5,10,40,0,0,0\n1,2.5e-05,2,2,9,2.5,10,0,0,0\n", "data row 2"},
      {"0,0,1,1,5,10,40,0,0,0\n1,2.5e-05,1,1,5,10,40,0,0,0\n0,0,1,1,5,10,40,0,0,0\n", "data row 3"}};
  for (const auto& [body, row] : bad) {
    const fs::path f = write_fragments_csv(body);
    std::string what;
    try {
      report::fragment_history(f.string());
    } catch (const Error& e) {
      what = e.what();
    }
    fs::remove(f);
    EXPECT_NE(what.find(f.string()), std::string::npos) << "not refused, or the file not named: " << what;
    EXPECT_NE(what.find(row), std::string::npos) << what;
  }
  EXPECT_THROW(report::fragment_history((fs::temp_directory_path() / "dspdem_no_such_fragments.csv").string()), Error);
}

namespace {
vtkSmartPointer<vtkImageData> solid(int w, int h, unsigned char v) {
  auto img = vtkSmartPointer<vtkImageData>::New();
  img->SetDimensions(w, h, 1);
  img->AllocateScalars(VTK_UNSIGNED_CHAR, 3);
  auto* p = static_cast<unsigned char*>(img->GetScalarPointer());
  std::fill(p, p + 3 * w * h, v);
  return img;
}
unsigned char at(vtkImageData* img, int x, int y) {
  return *static_cast<unsigned char*>(img->GetScalarPointer(x, y, 0));
}
}  // namespace

TEST(Montage, TilesRowByRowFromTheTopLeftAndFillsTheLastRow) {
  // Panels 10, 20, 30 in two columns: row 0 = (10, 20), row 1 = (30, white).
  const auto m = render::tile_images({solid(4, 3, 10), solid(4, 3, 20), solid(4, 3, 30)}, 2);
  int d[3];
  m->GetDimensions(d);
  EXPECT_EQ(d[0], 8);
  EXPECT_EQ(d[1], 6);
  // Image y grows upwards: the top row is y = 3..5.
  EXPECT_EQ(at(m, 0, 5), 10);
  EXPECT_EQ(at(m, 7, 5), 20);
  EXPECT_EQ(at(m, 0, 0), 30);
  EXPECT_EQ(at(m, 7, 0), 255);
  EXPECT_THROW(render::tile_images({solid(4, 3, 10), solid(5, 3, 20)}, 2), Error);
  EXPECT_THROW(render::tile_images({}, 2), Error);
}
