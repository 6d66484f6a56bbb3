#include "render/envelope.hpp"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkCleanPolyData.h>
#include <vtkIdList.h>
#include <vtkNew.h>
#include <vtkPointData.h>
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
  // Each face's points, sorted, once: the key of the faces it coincides with.
  const vtkIdType n = pd->GetNumberOfCells();
  std::vector<std::vector<vtkIdType>> keys(static_cast<std::size_t>(n));
  std::map<std::vector<vtkIdType>, int> count;
  vtkNew<vtkIdList> ids;
  for (vtkIdType c = 0; c < n; ++c) {
    pd->GetCellPoints(c, ids);
    auto& k = keys[static_cast<std::size_t>(c)];
    k.assign(ids->begin(), ids->end());
    std::sort(k.begin(), k.end());
    ++count[k];
  }
  vtkNew<vtkCellArray> keep;
  auto out = vtkSmartPointer<vtkPolyData>::New();
  out->GetCellData()->CopyAllocate(pd->GetCellData());  // a face keeps its colour or field value
  for (vtkIdType c = 0; c < n; ++c)
    if (count[keys[static_cast<std::size_t>(c)]] == 1) {
      pd->GetCellPoints(c, ids);  // in the face's own order: its orientation
      out->GetCellData()->CopyData(pd->GetCellData(), c, keep->InsertNextCell(ids));
    }
  out->SetPoints(pd->GetPoints());
  out->GetPointData()->PassData(pd->GetPointData());
  out->SetPolys(keep);
  return out;
}

}  // namespace dspdem::render
