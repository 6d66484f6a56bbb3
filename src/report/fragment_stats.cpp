#include "report/fragment_stats.hpp"

#include <vtkCellData.h>
#include <vtkCellSizeFilter.h>
#include <vtkDataArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkUnstructuredGrid.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <numeric>

#include "core/error.hpp"
#include "render/series.hpp"

namespace dspdem::report {

int FragmentStats::count_at_least(double fraction) const {
  return static_cast<int>(
      std::count_if(masses.begin(), masses.end(), [&](double m) { return m >= fraction * total_mass; }));
}

int FragmentStats::single_element() const { return static_cast<int>(std::count(elements.begin(), elements.end(), 1)); }

FragmentStats fragment_stats(const std::string& frame_vtu, const std::vector<double>& density_by_material) {
  vtkSmartPointer<vtkUnstructuredGrid> g = render::read_frame(frame_vtu);
  vtkDataArray* frag = g->GetCellData()->GetArray("fragment");
  vtkDataArray* mat = g->GetCellData()->GetArray("material");
  vtkDataArray* disp = g->GetPointData()->GetArray("displacement");
  DSPDEM_CHECK(frag, "frame '{}' has no 'fragment' cell field: fragment statistics need a run with joints", frame_vtu);
  DSPDEM_CHECK(mat && disp, "frame '{}' lacks the '{}' field that fragment statistics need (add it to [output] fields)",
               frame_vtu, mat ? "displacement" : "material");
  // Volumes in the reference configuration: mass does not change as elements deform.
  vtkNew<vtkPoints> ref;
  ref->SetDataTypeToDouble();
  ref->SetNumberOfPoints(g->GetNumberOfPoints());
  for (vtkIdType i = 0; i < g->GetNumberOfPoints(); ++i) {
    double p[3], u[3];
    g->GetPoint(i, p);
    disp->GetTuple(i, u);
    ref->SetPoint(i, p[0] - u[0], p[1] - u[1], p[2] - u[2]);
  }
  vtkNew<vtkUnstructuredGrid> rg;
  rg->ShallowCopy(g);
  rg->SetPoints(ref);
  vtkNew<vtkCellSizeFilter> size;
  size->SetInputData(rg);
  size->SetComputeVertexCount(false), size->SetComputeLength(false), size->SetComputeArea(false);
  size->SetComputeVolume(true), size->SetComputeSum(false);
  size->Update();
  vtkDataArray* vol = vtkDataSet::SafeDownCast(size->GetOutput())->GetCellData()->GetArray("Volume");
  DSPDEM_CHECK(vol, "frame '{}': VTK computed no cell volumes", frame_vtu);

  std::map<long, std::pair<double, int>> by_id;  // fragment id -> (mass, elements)
  for (vtkIdType e = 0; e < g->GetNumberOfCells(); ++e) {
    const auto m = static_cast<long>(mat->GetTuple1(e));
    DSPDEM_CHECK(m >= 0 && static_cast<std::size_t>(m) < density_by_material.size(),
                 "frame '{}' cell {}: material {} is not one of the case's {} materials", frame_vtu, e, m,
                 density_by_material.size());
    auto& f = by_id[static_cast<long>(frag->GetTuple1(e))];
    f.first += std::abs(vol->GetTuple1(e)) * density_by_material[static_cast<std::size_t>(m)];
    f.second += 1;
  }
  std::vector<std::pair<double, int>> pieces;
  for (const auto& [id, f] : by_id) pieces.push_back(f);
  // Largest first; ties by element count then as found (ids ascending): deterministic.
  std::stable_sort(pieces.begin(), pieces.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
  FragmentStats s;
  for (const auto& [m, n] : pieces) s.masses.push_back(m), s.elements.push_back(n), s.total_mass += m;
  return s;
}

std::vector<std::pair<double, double>> cumulative_mass_distribution(const FragmentStats& s) {
  std::vector<std::pair<double, double>> out;
  double acc = 0;
  for (auto it = s.masses.rbegin(); it != s.masses.rend(); ++it) {
    acc += *it;
    out.emplace_back(*it, s.total_mass > 0 ? acc / s.total_mass : 0.0);
  }
  if (!out.empty()) out.back().second = 1.0;  // exactly, whatever the rounding of the sum
  return out;
}

void write_mass_distribution_csv(const std::string& path, const FragmentStats& s,
                                 const std::pair<std::string, std::string>& columns) {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream f(tmp);
    DSPDEM_CHECK(f.good(), "cannot write '{}'", tmp);
    f << columns.first << ',' << columns.second << '\n';
    for (const auto& [m, c] : cumulative_mass_distribution(s)) f << fmt::format("{:.8g},{:.8g}\n", m, c);
    DSPDEM_CHECK(f.good(), "cannot write '{}'", tmp);
  }
  std::filesystem::rename(tmp, path);
}

}  // namespace dspdem::report
