#include "render/image_compare.hpp"

#include <vtkDataArray.h>
#include <vtkImageData.h>
#include <vtkImageDifference.h>
#include <vtkNew.h>
#include <vtkPNGReader.h>
#include <vtkPointData.h>

#include <filesystem>

#include "core/error.hpp"
#include "render/offscreen.hpp"

namespace dspdem::render {

namespace {
vtkSmartPointer<vtkImageData> load(const std::string& path) {
  DSPDEM_CHECK(std::filesystem::exists(path), "image '{}' does not exist", path);
  vtkNew<vtkPNGReader> r;
  DSPDEM_CHECK(r->CanReadFile(path.c_str()), "image '{}' is not a readable PNG", path);
  r->SetFileName(path.c_str());
  r->Update();
  auto img = vtkSmartPointer<vtkImageData>::New();
  img->DeepCopy(r->GetOutput());
  return img;
}
}  // namespace

ImageDiff compare_png(const std::string& a, const std::string& b, const std::string& diff_png, int tol) {
  auto ia = load(a), ib = load(b);
  int da[3], db[3];
  ia->GetDimensions(da);
  ib->GetDimensions(db);
  DSPDEM_CHECK(da[0] == db[0] && da[1] == db[1], "images differ in size: '{}' is {}x{}, '{}' is {}x{}", a, da[0], da[1],
               b, db[0], db[1]);
  vtkNew<vtkImageDifference> d;
  d->SetInputData(ia);
  d->SetImageData(ib);
  d->SetThreshold(tol);
  d->AllowShiftOn();
  d->AveragingOff();
  d->Update();
  ImageDiff r;
  r.vtk_error = d->GetThresholdedError();
  r.width = da[0], r.height = da[1];
  vtkDataArray* px = d->GetOutput()->GetPointData()->GetScalars();
  long changed = 0;
  for (vtkIdType i = 0; i < px->GetNumberOfTuples(); ++i) {
    bool diff = false;
    for (int c = 0; c < std::min(3, px->GetNumberOfComponents()); ++c) diff = diff || px->GetComponent(i, c) > 0;
    changed += diff;
  }
  r.changed_fraction = static_cast<double>(changed) / std::max<vtkIdType>(1, px->GetNumberOfTuples());
  if (!diff_png.empty()) write_png(d->GetOutput(), diff_png);
  return r;
}

}  // namespace dspdem::render
