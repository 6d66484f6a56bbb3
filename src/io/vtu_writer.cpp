#include "io/vtu_writer.hpp"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkIdTypeArray.h>
#include <vtkIntArray.h>
#if DSPDEM_HAVE_MPI
#include <vtkMPIController.h>
#endif
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLPUnstructuredGridWriter.h>
#include <vtkXMLUnstructuredGridWriter.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <filesystem>

#include "core/error.hpp"
#include "fem/linear_elastic.hpp"
#include "io/staging.hpp"
#include "joint/joint_forces.hpp"
#include "joint/joint_law.hpp"
#include "joint/joint_set.hpp"

namespace dspdem {

Real max_principal(const Real* s) {
  Mat3 m;
  m << s[0], s[3], s[5], s[3], s[1], s[4], s[5], s[4], s[2];
  Eigen::SelfAdjointEigenSolver<Mat3> es(m, Eigen::EigenvaluesOnly);
  return es.eigenvalues()(2);
}

namespace {
// Appended raw binary, zlib-compressed on request, through a temporary name. With pieces > 1,
// `path` is a .pvtu: this process writes its piece beside it (VTK names it path's stem
// _<piece>.vtu) and piece 0 the .pvtu, which lists them all (collective: VTK's MPI controller
// tells piece 0 which pieces were written); the staging folder keeps a run's half-written
// frame from replacing a whole one.
template <class Writer>
bool write_appended(Writer& w, vtkUnstructuredGrid* grid, const std::string& path, bool compress) {
  w.SetFileName(path.c_str());
  w.SetInputData(grid);
  w.SetDataModeToAppended();
  w.EncodeAppendedDataOff();
  if (compress) {
    // Level 1 (VTK's default is 5): frames of doubles shrink little more at higher levels
    // but take longer (26 frames of the Brazilian disc: 6 % smaller at 5, written in
    // 0.8-1.1 s more), and a frame is written while the other threads wait.
    w.SetCompressorTypeToZLib();
    w.SetCompressionLevel(1);
  } else
    w.SetCompressorTypeToNone();
  return w.Write() == 1;
}

void write_grid(vtkUnstructuredGrid* grid, const std::string& path, bool compress, int piece = 0, int pieces = 1) {
  if (pieces > 1) {
    vtkNew<vtkXMLPUnstructuredGridWriter> w;
#if DSPDEM_HAVE_MPI
    static vtkMPIController* controller = [] {
      auto* c = vtkMPIController::New();
      c->Initialize(nullptr, nullptr, 1);  // MPI is already running (par::init)
      return c;
    }();
    w->SetController(controller);
#else
    fail("internal: a frame in {} pieces from a build without MPI", pieces);
#endif
    w->SetNumberOfPieces(pieces);
    w->SetStartPiece(piece);
    w->SetEndPiece(piece);
    w->SetWriteSummaryFile(1);  // on every process: collective, and only process 0 writes it
    DSPDEM_CHECK(write_appended(*w, grid, path, compress), "could not write piece {} of '{}'", piece, path);
    return;
  }
  const std::string tmp = path + ".tmp.vtu";
  vtkNew<vtkXMLUnstructuredGridWriter> w;
  DSPDEM_CHECK(write_appended(*w, grid, tmp, compress), "could not write '{}'", tmp);
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
  // The cells written (all, or a piece's own) and their points, numbered in node order.
  std::vector<Index> cells;
  for (Index e = 0; e < mesh.n_elements(); ++e)
    if (!f.cell_owned || f.cell_owned[e]) cells.push_back(e);
  std::vector<vtkIdType> point_of;
  std::vector<Index> points;
  if (f.cell_owned) {
    point_of.assign(mesh.n_nodes(), -1);
    Index e0 = 0;
    for (const auto& b : mesh.blocks) {
      for (Index e = 0; e < b.size(); ++e)
        if (f.cell_owned[e0 + e])
          for (int i = 0; i < b.npe(); ++i) point_of[b.conn[static_cast<std::size_t>(e) * b.npe() + i]] = 0;
      e0 += b.size();
    }
    for (Index n = 0; n < mesh.n_nodes(); ++n)
      if (point_of[n] == 0) point_of[n] = static_cast<vtkIdType>(points.size()), points.push_back(n);
  } else {
    for (Index n = 0; n < mesh.n_nodes(); ++n) points.push_back(n);
  }
  auto pid = [&](Index n) { return f.cell_owned ? point_of[n] : static_cast<vtkIdType>(n); };
  const vtkIdType np = static_cast<vtkIdType>(points.size());
  vtkNew<vtkUnstructuredGrid> grid;
  vtkNew<vtkPoints> pts;
  pts->SetDataTypeToDouble();
  pts->SetNumberOfPoints(np);
  for (vtkIdType i = 0; i < np; ++i) {
    const std::size_t k = 3 * static_cast<std::size_t>(points[i]);
    pts->SetPoint(i, f.x[k], f.x[k + 1], f.x[k + 2]);
  }
  grid->SetPoints(pts);
  const vtkIdType ne = static_cast<vtkIdType>(cells.size());
  grid->Allocate(ne);
  {
    Index e0 = 0;
    for (const auto& b : mesh.blocks) {
      const int npe = b.npe();
      const int vtk_type = b.type == CellType::Tet4 ? 10 /*VTK_TETRA*/ : 12 /*VTK_HEXAHEDRON*/;
      vtkIdType ids[8];
      for (Index e = 0; e < b.size(); ++e) {
        if (f.cell_owned && !f.cell_owned[e0 + e]) continue;
        for (int i = 0; i < npe; ++i) ids[i] = pid(b.conn[static_cast<std::size_t>(e) * npe + i]);
        grid->InsertNextCell(vtk_type, npe, ids);
      }
      e0 += b.size();
    }
  }
  auto point_vector = [&](const char* name, const Real* a, const Real* minus) {
    auto arr = vec_array(name, np, 3);
    for (vtkIdType i = 0; i < np; ++i)
      for (int d = 0; d < 3; ++d) {
        const std::size_t k = 3 * static_cast<std::size_t>(points[i]) + d;
        arr->SetValue(3 * i + d, minus ? a[k] - minus[k] : a[k]);
      }
    grid->GetPointData()->AddArray(arr);
  };
  if (wants(f, "displacement")) point_vector("displacement", f.x, f.x0);
  if (wants(f, "velocity")) point_vector("velocity", f.v, nullptr);
  if (f.stress && wants(f, "stress")) {
    auto a = vec_array("stress", ne, 6);  // ParaView reads 6 components as a symmetric tensor
    for (vtkIdType i = 0; i < ne; ++i)
      for (int k = 0; k < 6; ++k) a->SetValue(6 * i + k, f.stress[6 * static_cast<std::size_t>(cells[i]) + k]);
    grid->GetCellData()->AddArray(a);
  }
  if (f.stress && wants(f, "von_mises")) {
    auto a = vec_array("von_mises", ne, 1);
    for (vtkIdType i = 0; i < ne; ++i) {
      const Real* s = f.stress + 6 * static_cast<std::size_t>(cells[i]);
      Mat3 m;
      m << s[0], s[3], s[5], s[3], s[1], s[4], s[5], s[4], s[2];
      a->SetValue(i, von_mises(m));
    }
    grid->GetCellData()->AddArray(a);
  }
  if (f.stress && wants(f, "max_principal")) {
    auto a = vec_array("max_principal", ne, 1);
    for (vtkIdType i = 0; i < ne; ++i) a->SetValue(i, max_principal(f.stress + 6 * static_cast<std::size_t>(cells[i])));
    grid->GetCellData()->AddArray(a);
  }
  auto int_array = [&](const char* name, auto&& value) {
    vtkNew<vtkIntArray> a;
    a->SetName(name);
    a->SetNumberOfTuples(ne);
    for (vtkIdType i = 0; i < ne; ++i) a->SetValue(i, value(cells[i]));
    grid->GetCellData()->AddArray(a);
  };
  if (f.body && wants(f, "body")) int_array("body", [&](Index e) { return f.body[e]; });
  if (f.fragment) int_array("fragment", [&](Index e) { return f.fragment[e]; });
  if (f.material && wants(f, "material")) int_array("material", [&](Index e) { return f.material[e]; });
  if (f.pieces > 1) int_array("rank", [&](Index) { return f.piece; });
  if (f.element_tag && wants(f, "element")) {
    vtkNew<vtkIdTypeArray> a;
    a->SetName("element");
    a->SetNumberOfTuples(ne);
    for (vtkIdType i = 0; i < ne; ++i) a->SetValue(i, static_cast<vtkIdType>(f.element_tag[cells[i]]));
    grid->GetCellData()->AddArray(a);
  }
  if (!f.wall_pose.empty()) {
    auto a = vec_array("wall_pose", static_cast<vtkIdType>(f.wall_pose.size() / 7), 7);
    for (std::size_t i = 0; i < f.wall_pose.size(); ++i) a->SetValue(static_cast<vtkIdType>(i), f.wall_pose[i]);
    grid->GetFieldData()->AddArray(a);
  }

  write_grid(grid, path, f.compress, f.piece, f.pieces);
}

void write_joints_vtu(const std::string& path, const joint::JointSet& js, const Real* x, const Real* x0, bool compress,
                      const std::vector<char>& owned, int piece, int pieces) {
  vtkNew<vtkUnstructuredGrid> grid;
  vtkNew<vtkPoints> pts;
  pts->SetDataTypeToDouble();
  vtkNew<vtkIntArray> state;
  state->SetName("state");
  vtkNew<vtkDoubleArray> damage, opening, slip;
  damage->SetName("damage"), opening->SetName("opening"), slip->SetName("slip");
  vtkNew<vtkDoubleArray> disp;
  disp->SetName("displacement");
  disp->SetNumberOfComponents(3);
  for (Index j = 0; j < js.size(); ++j) {
    if (!owned.empty() && !owned[j]) continue;
    const int npf = js.npf[j];
    vtkIdType ids[4];
    for (int k = 0; k < npf; ++k) {
      const Index a = js.a[4 * static_cast<std::size_t>(j) + k], b = js.b[4 * static_cast<std::size_t>(j) + k];
      ids[k] = pts->InsertNextPoint(0.5 * (x[3 * a] + x[3 * b]), 0.5 * (x[3 * a + 1] + x[3 * b + 1]),
                                    0.5 * (x[3 * a + 2] + x[3 * b + 2]));
      if (x0) {
        double u[3];
        for (int d = 0; d < 3; ++d) u[d] = 0.5 * ((x[3 * a + d] - x0[3 * a + d]) + (x[3 * b + d] - x0[3 * b + d]));
        disp->InsertNextTuple(u);
      }
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
  if (x0) grid->GetPointData()->AddArray(disp);
  write_grid(grid, path, compress, piece, pieces);
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
