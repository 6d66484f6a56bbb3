// Image regression: vtkImageDifference with a one-pixel spatial tolerance.
//
// Metric: for each pixel, the smallest colour difference to the 3x3 neighbourhood of the
// same pixel in the other image (so one-pixel shifts of edges and anti-aliasing cost
// nothing), channel differences below `channel_tolerance` (of 255) ignored, averaged over
// the image: VTK's "thresholded error". A crack that moves by a few pixels changes whole
// bands of pixels to another fragment colour and raises it far above noise.
#pragma once
#include <string>

namespace dspdem::render {

struct ImageDiff {
  double error = 0;  ///< thresholded error (mean per-pixel difference after tolerances)
  int width = 0, height = 0;
};

/// Compares two PNG files; writes the difference image to `diff_png` if not empty.
/// Throws Error if a file is missing or the sizes differ.
ImageDiff compare_png(const std::string& a, const std::string& b, const std::string& diff_png = "",
                      int channel_tolerance = 16);

}  // namespace dspdem::render
