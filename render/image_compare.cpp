#include "render/image_compare.hpp"

#include <png.h>
#include <vtkDataArray.h>
#include <vtkImageClip.h>
#include <vtkImageData.h>
#include <vtkImageDifference.h>
#include <vtkImageMirrorPad.h>
#include <vtkNew.h>
#include <vtkPointData.h>

#include <filesystem>
#include <fstream>
#include <vector>

#include "core/error.hpp"
#include "render/offscreen.hpp"

namespace dspdem::render {

namespace {
namespace fs = std::filesystem;
// The most pixels read: 16384 x 16384, what `render --size` draws at most (a montage of many
// panels is wider than that, but has fewer pixels).
constexpr double kMostPixels = 16384.0 * 16384.0;

// Reads with libpng's simplified API, which reports a damaged file as an error (VTK 9.1's
// reader crashed on a truncated or corrupt one: a double free in its error path), and gives
// every kind of PNG (grey, grey and alpha, RGB, RGBA, 16 bits) as 8-bit RGB, the one kind
// vtkImageDifference compares (on others it reported an error and the count was made up).
// Rows bottom-up, as VTK's images and its PNG writer have them.
vtkSmartPointer<vtkImageData> load(const std::string& path) {
  DSPDEM_CHECK(fs::exists(path), "image '{}' does not exist", path);
  DSPDEM_CHECK(!fs::is_directory(path), "image '{}' is a folder", path);
  png_image im{};
  im.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&im, path.c_str()))  // frees `im` itself on failure
    fail("image '{}' is not a readable PNG: {}", path, im.message);
  if (static_cast<double>(im.width) * im.height > kMostPixels) {
    const png_uint_32 w = im.width, h = im.height;
    png_image_free(&im);
    fail("image '{}' is {}x{} pixels, more than dspdem compares (16384 x 16384, as it draws at most)", path, w, h);
  }
  im.format = PNG_FORMAT_RGB;
  const int w = static_cast<int>(im.width), h = static_cast<int>(im.height);
  auto img = vtkSmartPointer<vtkImageData>::New();
  img->SetDimensions(w, h, 1);
  img->AllocateScalars(VTK_UNSIGNED_CHAR, 3);
  // Alpha composited onto black: without a background libpng composites onto what the buffer
  // held, which VTK does not clear. A negative row stride: the buffer holds the bottom row
  // first (the file's last row is VTK's first).
  const png_color black{0, 0, 0};
  if (!png_image_finish_read(&im, &black, img->GetScalarPointer(), -3 * w, nullptr))  // frees `im` on failure too
    fail("image '{}' is damaged or cut short: {}", path, im.message);
  return img;
}
}  // namespace

ImageDiff compare_png(const std::string& a, const std::string& b, const std::string& diff_png, int tol) {
  // The difference never replaces what it compares.
  if (!diff_png.empty()) {
    for (const std::string& in : {a, b})
      DSPDEM_CHECK(!fs::exists(in) || !fs::exists(diff_png) || !fs::equivalent(in, diff_png),
                   "the difference image '{}' would replace the image '{}' it compares; give --diff another file",
                   diff_png, in);
    DSPDEM_CHECK(!fs::is_directory(diff_png), "the difference image '{}' is a folder; give --diff a file's name",
                 diff_png);
    // A file there is replaced only when it is an image (an earlier difference): not a user's notes.
    if (fs::exists(diff_png)) {
      std::string head(8, '\0');
      std::ifstream(diff_png, std::ios::binary).read(head.data(), 8);
      DSPDEM_CHECK(head == "\x89PNG\r\n\x1a\n",
                   "the difference image '{}' would replace a file that is not a PNG image; give --diff another file",
                   diff_png);
    }
    const fs::path parent = fs::absolute(diff_png).parent_path();
    DSPDEM_CHECK(fs::is_directory(parent), "the difference image's folder '{}' does not exist", parent.string());
  }
  auto ia = load(a), ib = load(b);
  int da[3], db[3];
  ia->GetDimensions(da);
  ib->GetDimensions(db);
  DSPDEM_CHECK(da[0] == db[0] && da[1] == db[1], "images differ in size: '{}' is {}x{}, '{}' is {}x{}", a, da[0], da[1],
               b, db[0], db[1]);
  // vtkImageDifference lets a pixel match a neighbour up to two pixels away (AllowShift), and
  // leaves a two-pixel border it never compares (a probe's: a 2-pixel frame, 12 % of a 64 x 64
  // image, read as no change). The images are mirrored two pixels out first, so that every
  // pixel of theirs has its neighbours and is compared; the difference is cut back to them.
  constexpr int kPad = 2;
  auto padded = [&](vtkImageData* im) {
    vtkNew<vtkImageMirrorPad> pad;
    pad->SetInputData(im);
    pad->SetOutputWholeExtent(-kPad, da[0] - 1 + kPad, -kPad, da[1] - 1 + kPad, 0, 0);
    pad->Update();
    return vtkSmartPointer<vtkImageData>(pad->GetOutput());
  };
  vtkNew<vtkImageDifference> d;
  d->SetInputData(padded(ia));
  d->SetImageData(padded(ib));
  ia = ib = nullptr;  // the padded copies are what is compared: a 16384^2 image's memory once, not twice
  d->SetThreshold(tol);
  d->AllowShiftOn();
  d->AveragingOff();
  d->Update();
  vtkNew<vtkImageClip> clip;
  clip->SetInputConnection(d->GetOutputPort());
  clip->SetOutputWholeExtent(0, da[0] - 1, 0, da[1] - 1, 0, 0);
  clip->ClipDataOn();
  clip->Update();
  ImageDiff r;
  r.vtk_error = d->GetThresholdedError();
  r.width = da[0], r.height = da[1];
  vtkDataArray* px = clip->GetOutput()->GetPointData()->GetScalars();
  long changed = 0;
  for (vtkIdType i = 0; i < px->GetNumberOfTuples(); ++i) {
    bool diff = false;
    for (int c = 0; c < std::min(3, px->GetNumberOfComponents()); ++c) diff = diff || px->GetComponent(i, c) > 0;
    changed += diff;
  }
  r.changed_fraction = static_cast<double>(changed) / std::max<vtkIdType>(1, px->GetNumberOfTuples());
  if (!diff_png.empty()) write_png(clip->GetOutput(), diff_png);
  return r;
}

}  // namespace dspdem::render
