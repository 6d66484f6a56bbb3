#include "render/envelope.hpp"

#include <vtkCellArray.h>
#include <vtkCleanPolyData.h>
#include <vtkIdList.h>
#include <vtkNew.h>
#include <vtkPolyData.h>

#include <algorithm>
#include <map>
#include <vector>

namespace dspdem::render {

vtkSmartPointer<vtkPolyData> unmatched_faces(vtkPolyData* surface, double tolerance) {
  // vtkCleanPolyData, not vtkStaticCleanPolyData. With a tolerance, VTK 9.1's static one
  // merges a cluster of points into whichever its threads (TBB in Debian's build) reach first,
  // so two renders of a frame differed by a pixel (4 of 31 frames of the sphere at 7.5 m/s),
  // and it left some pairs of an intact sphere's interior faces unmatched, a star of
  // translucent faces at its centre. The incremental one merges in point order.
  vtkNew<vtkCleanPolyData> clean;
  clean->SetInputData(surface);
  clean->SetTolerance(tolerance);
  clean->Update();
  vtkPolyData* pd = clean->GetOutput();
  std::map<std::vector<vtkIdType>, int> count;
  vtkNew<vtkIdList> ids;
  auto key = [&](vtkIdType c) {
    pd->GetCellPoints(c, ids);
    std::vector<vtkIdType> k(ids->begin(), ids->end());
    std::sort(k.begin(), k.end());
    return k;
  };
  for (vtkIdType c = 0; c < pd->GetNumberOfCells(); ++c) ++count[key(c)];
  vtkNew<vtkCellArray> keep;
  for (vtkIdType c = 0; c < pd->GetNumberOfCells(); ++c)
    if (count[key(c)] == 1) keep->InsertNextCell(ids);  // key() left c's points in ids
  auto out = vtkSmartPointer<vtkPolyData>::New();
  out->SetPoints(pd->GetPoints());
  out->SetPolys(keep);
  return out;
}

}  // namespace dspdem::render
