// Image regression: vtkImageDifference with a one-pixel spatial tolerance.
//
// Metric: the fraction of pixels that still differ after two tolerances: each pixel is
// compared with the 3x3 neighbourhood of the same pixel in the other image (one-pixel
// shifts of edges and anti-aliasing cost nothing), and channel differences up to
// `channel_tolerance` (of 255) are ignored (VTK's vtkImageDifference does both). It reads
// as "0.3 % of the picture changed", independent of image size; a crack that moves by a
// few pixels recolours a band along its whole length and is far above noise. VTK's own
// summed "thresholded error" is reported beside it.
#pragma once
#include <string>

namespace dspdem::render {

struct ImageDiff {
  double changed_fraction = 0;  ///< fraction of pixels that differ after the tolerances
  double vtk_error = 0;         ///< vtkImageDifference::GetThresholdedError()
  int width = 0, height = 0;
};

/// Compares two PNG files; writes the difference image to `diff_png` if not empty.
/// Throws Error if a file is missing or the sizes differ.
ImageDiff compare_png(const std::string& a, const std::string& b, const std::string& diff_png = "",
                      int channel_tolerance = 16);

}  // namespace dspdem::render
