// Montages: panels of equal size tiled into one image (e.g. the frames of several runs of a
// sweep at the same time, the paper's Fig. 22), with VTK's image append filters.
#pragma once
#include <vtkSmartPointer.h>

#include <vector>

class vtkImageData;

namespace dspdem::render {

/// Tiles `panels` row by row from the top left, `columns` per row; a short last row is
/// filled with white. Every panel must have the first one's size and components (Error
/// naming the panel otherwise).
vtkSmartPointer<vtkImageData> tile_images(const std::vector<vtkSmartPointer<vtkImageData>>& panels, int columns);

}  // namespace dspdem::render
