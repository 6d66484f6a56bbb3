// The rigid walls as surfaces to draw: each wall's shape from the case, placed where a frame
// records it (field data `wall_pose`, io/vtu_writer.hpp). Boxes and cylinders (with their
// hemispherical ends) are closed surfaces, a jaw is its loading arc, a plane a square patch
// about the framed region; all only to be seen, not measured.
#pragma once
#include <vtkSmartPointer.h>

#include <vector>

#include "io/case_config.hpp"

class vtkPolyData;
class vtkDataSet;

namespace dspdem {

/// The walls of `walls` at the poses `frame` holds; null when it holds none, or not one per
/// wall (a run written before walls were recorded). `bounds`: the framing box (xmin xmax ymin
/// ymax zmin zmax), which sizes planes and the length of jaws.
vtkSmartPointer<vtkPolyData> wall_surfaces(const std::vector<WallConfig>& walls, vtkDataSet* frame,
                                           const double bounds[6]);

}  // namespace dspdem
