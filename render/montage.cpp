#include "render/montage.hpp"

#include <vtkImageAppend.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkUnsignedCharArray.h>

#include <algorithm>

#include "core/error.hpp"

namespace dspdem::render {

namespace {
vtkSmartPointer<vtkImageData> white_like(vtkImageData* img) {
  auto w = vtkSmartPointer<vtkImageData>::New();
  w->SetDimensions(img->GetDimensions());
  w->AllocateScalars(VTK_UNSIGNED_CHAR, img->GetNumberOfScalarComponents());
  auto* a = vtkUnsignedCharArray::SafeDownCast(w->GetPointData()->GetScalars());
  std::fill(a->GetPointer(0), a->GetPointer(0) + a->GetNumberOfValues(), static_cast<unsigned char>(255));
  return w;
}
}  // namespace

vtkSmartPointer<vtkImageData> tile_images(const std::vector<vtkSmartPointer<vtkImageData>>& panels, int columns) {
  DSPDEM_CHECK(!panels.empty(), "montage: no panel to tile");
  DSPDEM_CHECK(columns > 0, "montage: {} columns", columns);
  int d0[3];
  panels[0]->GetDimensions(d0);
  const int nc = panels[0]->GetNumberOfScalarComponents();
  for (std::size_t i = 1; i < panels.size(); ++i) {
    int d[3];
    panels[i]->GetDimensions(d);
    DSPDEM_CHECK(d[0] == d0[0] && d[1] == d0[1] && panels[i]->GetNumberOfScalarComponents() == nc,
                 "montage: panel {} is {}x{} with {} components, panel 0 {}x{} with {}", i, d[0], d[1],
                 panels[i]->GetNumberOfScalarComponents(), d0[0], d0[1], nc);
    DSPDEM_CHECK(panels[i]->GetScalarType() == VTK_UNSIGNED_CHAR, "montage: panel {} is not an 8-bit image", i);
  }
  const std::size_t cols = static_cast<std::size_t>(columns);
  const std::size_t rows = (panels.size() + cols - 1) / cols;
  // Image y grows upwards: the bottom row goes first into the vertical append.
  vtkNew<vtkImageAppend> stack;
  stack->SetAppendAxis(1);
  std::vector<vtkSmartPointer<vtkImageAppend>> keep;
  for (std::size_t r = rows; r-- > 0;) {
    auto row = vtkSmartPointer<vtkImageAppend>::New();
    row->SetAppendAxis(0);
    for (std::size_t c = 0; c < cols; ++c) {
      const std::size_t i = r * cols + c;
      row->AddInputData(i < panels.size() ? panels[i] : white_like(panels[0]));
    }
    stack->AddInputConnection(row->GetOutputPort());
    keep.push_back(row);
  }
  stack->Update();
  auto out = vtkSmartPointer<vtkImageData>::New();
  out->DeepCopy(stack->GetOutput());
  return out;
}

}  // namespace dspdem::render
