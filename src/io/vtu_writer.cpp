#include "io/vtu_writer.hpp"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridWriter.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <filesystem>

#include "core/error.hpp"
#include "fem/linear_elastic.hpp"
#include "io/staging.hpp"
#include "joint/coupled_law.hpp"
#include "joint/joint_forces.hpp"
#include "joint/joint_set.hpp"

namespace dspdem {

Real max_principal(const Real* s) {
  Mat3 m;
  m << s[0], s[3], s[5], s[3], s[1], s[4], s[5], s[4], s[2];
  Eigen::SelfAdjointEigenSolver<Mat3> es(m, Eigen::EigenvaluesOnly);
  return es.eigenvalues()(2);
}

namespace {
// Appended raw binary, zlib-compressed on request, through a temporary name.
void write_grid(vtkUnstructuredGrid* grid, const std::string& path, bool compress) {
  const std::string tmp = path + ".tmp.vtu";
  vtkNew<vtkXMLUnstructuredGridWriter> w;
  w->SetFileName(tmp.c_str());
  w->SetInputData(grid);
  w->SetDataModeToAppended();
  w->EncodeAppendedDataOff();
  if (compress)
    w->SetCompressorTypeToZLib();
  else
    w->SetCompressorTypeToNone();
  DSPDEM_CHECK(w->Write() == 1, "could not write '{}'", tmp);
  std::filesystem::rename(tmp, path);
}

bool wants(const FrameData& f, const char* name) {
  return std::find(f.fields.begin(), f.fields.end(), name) != f.fields.end();
}

vtkNew<vtkDoubleArray> vec_array(const char* name, vtkIdType n, int nc) {
  vtkNew<vtkDoubleArray> a;
  a->SetName(name);
  a->SetNumberOfComponents(nc);
  a->SetNumberOfTuples(n);
  return a;
}
}  // namespace

void write_vtu(const std::string& path, const FrameData& f) {
  const Mesh& mesh = *f.mesh;
  const vtkIdType nn = mesh.n_nodes();
  vtkNew<vtkUnstructuredGrid> grid;
  vtkNew<vtkPoints> pts;
  pts->SetDataTypeToDouble();
  pts->SetNumberOfPoints(nn);
  for (vtkIdType i = 0; i < nn; ++i) pts->SetPoint(i, f.x[3 * i], f.x[3 * i + 1], f.x[3 * i + 2]);
  grid->SetPoints(pts);
  const vtkIdType ne = mesh.n_elements();
  grid->Allocate(ne);
  for (const auto& b : mesh.blocks) {
    const int npe = b.npe();
    const int vtk_type = b.type == CellType::Tet4 ? 10 /*VTK_TETRA*/ : 12 /*VTK_HEXAHEDRON*/;
    vtkIdType ids[8];
    for (Index e = 0; e < b.size(); ++e) {
      for (int i = 0; i < npe; ++i) ids[i] = b.conn[static_cast<std::size_t>(e) * npe + i];
      grid->InsertNextCell(vtk_type, npe, ids);
    }
  }
  if (wants(f, "displacement")) {
    auto a = vec_array("displacement", nn, 3);
    for (vtkIdType i = 0; i < 3 * nn; ++i) a->SetValue(i, f.x[i] - f.x0[i]);
    grid->GetPointData()->AddArray(a);
  }
  if (wants(f, "velocity")) {
    auto a = vec_array("velocity", nn, 3);
    for (vtkIdType i = 0; i < 3 * nn; ++i) a->SetValue(i, f.v[i]);
    grid->GetPointData()->AddArray(a);
  }
  if (f.stress && wants(f, "stress")) {
    auto a = vec_array("stress", ne, 6);  // ParaView reads 6 components as a symmetric tensor
    for (vtkIdType i = 0; i < 6 * ne; ++i) a->SetValue(i, f.stress[i]);
    grid->GetCellData()->AddArray(a);
  }
  if (f.stress && wants(f, "von_mises")) {
    auto a = vec_array("von_mises", ne, 1);
    for (vtkIdType e = 0; e < ne; ++e) {
      const Real* s = f.stress + 6 * e;
      Mat3 m;
      m << s[0], s[3], s[5], s[3], s[1], s[4], s[5], s[4], s[2];
      a->SetValue(e, von_mises(m));
    }
    grid->GetCellData()->AddArray(a);
  }
  if (f.stress && wants(f, "max_principal")) {
    auto a = vec_array("max_principal", ne, 1);
    for (vtkIdType e = 0; e < ne; ++e) a->SetValue(e, max_principal(f.stress + 6 * e));
    grid->GetCellData()->AddArray(a);
  }
  auto int_array = [&](const char* name, const Index* src) {
    vtkNew<vtkIntArray> a;
    a->SetName(name);
    a->SetNumberOfTuples(ne);
    for (vtkIdType e = 0; e < ne; ++e) a->SetValue(e, src[e]);
    grid->GetCellData()->AddArray(a);
  };
  if (f.body && wants(f, "body")) int_array("body", f.body);
  if (f.fragment) int_array("fragment", f.fragment);
  if (f.material && wants(f, "material")) int_array("material", f.material);
  if (!f.wall_pose.empty()) {
    auto a = vec_array("wall_pose", static_cast<vtkIdType>(f.wall_pose.size() / 7), 7);
    for (std::size_t i = 0; i < f.wall_pose.size(); ++i) a->SetValue(static_cast<vtkIdType>(i), f.wall_pose[i]);
    grid->GetFieldData()->AddArray(a);
  }

  write_grid(grid, path, f.compress);
}

void write_joints_vtu(const std::string& path, const joint::JointSet& js, const Real* x, bool compress) {
  vtkNew<vtkUnstructuredGrid> grid;
  vtkNew<vtkPoints> pts;
  pts->SetDataTypeToDouble();
  vtkNew<vtkIntArray> state;
  state->SetName("state");
  vtkNew<vtkDoubleArray> damage, opening, slip;
  damage->SetName("damage"), opening->SetName("opening"), slip->SetName("slip");
  for (Index j = 0; j < js.size(); ++j) {
    const int npf = js.npf[j];
    vtkIdType ids[4];
    for (int k = 0; k < npf; ++k) {
      const Index a = js.a[4 * static_cast<std::size_t>(j) + k], b = js.b[4 * static_cast<std::size_t>(j) + k];
      ids[k] = pts->InsertNextPoint(0.5 * (x[3 * a] + x[3 * b]), 0.5 * (x[3 * a + 1] + x[3 * b + 1]),
                                    0.5 * (x[3 * a + 2] + x[3 * b + 2]));
    }
    grid->InsertNextCell(npf == 3 ? 5 /*VTK_TRIANGLE*/ : 9 /*VTK_QUAD*/, npf, ids);
    const joint::CohesiveParams& p = js.params[js.param[j]];
    double N[4][4], w[4];
    const int ng = joint::face_quadrature(npf, js.rule(j), N, w);
    Real d = 0, dn = 0, ds = 0;
    for (int g = 0; g < ng; ++g) {
      const joint::CohesiveState s = js.point_state(4 * static_cast<std::size_t>(j) + g);
      d = std::max(d, joint::damage_index(p, s));
      dn += s.dn / ng, ds += s.ds / ng;
    }
    state->InsertNextValue(static_cast<int>(js.status[j]));
    damage->InsertNextValue(d);
    opening->InsertNextValue(dn);
    slip->InsertNextValue(ds);
  }
  grid->SetPoints(pts);
  grid->GetCellData()->AddArray(state);
  grid->GetCellData()->AddArray(damage);
  grid->GetCellData()->AddArray(opening);
  grid->GetCellData()->AddArray(slip);
  write_grid(grid, path, compress);
}

void write_pvd(const std::string& path, const std::vector<std::pair<double, std::string>>& frames) {
  std::string s =
      "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n  "
      "<Collection>\n";
  for (const auto& [t, file] : frames)
    s += fmt::format("    <DataSet timestep=\"{:.17g}\" group=\"\" part=\"0\" file=\"{}\"/>\n", t, file);
  s += "  </Collection>\n</VTKFile>\n";
  write_file_atomic(path, s);
}

}  // namespace dspdem
