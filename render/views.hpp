// The views a frame is drawn in:
//   stress    - a scalar field on the (optionally magnified) deformed bodies, fixed colour
//               range over the series, in MPa (mm for displacement) with round tick values;
//               viridis for magnitudes, cool-warm centred on zero for signed stresses;
//   fragments - every fragment (or, in runs without fragment data, every body) its own
//               colour by size rank: the largest piece palette[0], the next palette[1], ...
//               (ties by id, 20 colours then wrapping), kept while a piece keeps its rank,
//               unless a piece it touches has that colour: then the first colour none of
//               its neighbours has;
//   cracks    - broken joint faces over a translucent body (needs joint data in the run).
// Every view has the case name (or a montage panel's label), the simulated time and, when the
// displacement is magnified, by how much in the top-left corner and a scale bar in mm in the
// top-right (true for lengths in the view plane:
// front, back, top, side). Camera presets look at the first frame's bounds, so every frame
// of a series is framed the same and images can be compared pixel by pixel.
#pragma once
#include <vtkSmartPointer.h>

#include <array>
#include <string>
#include <vector>

class vtkUnstructuredGrid;
class vtkImageData;
class vtkPolyData;

namespace dspdem::render {

struct ViewOptions {
  std::string view = "stress";
  std::string field = "von_mises";  ///< von_mises, max_principal, sigma_xx ... sigma_xz, displacement
  double magnify = 1.0;             ///< displacement magnification for drawing
  bool auto_range = true;
  double range[2] = {0, 1};    ///< colour range [field unit]
  std::string camera = "iso";  ///< front, back, top, side, iso
  /// diagonal: the bounds' diagonal fits the image's shorter side, whatever the camera; box:
  /// for front, back, top and side, the face of the bounds seen fills the image with a 30 % margin.
  std::string fit = "diagonal";
  std::string cut = "none";  ///< none, x, y, z: keep the half below the mid-plane normal to it
  int width = 1280, height = 720;
  std::array<double, 3> background = {1.0, 1.0, 1.0};
  double bounds[6] = {0, 1, 0, 1, 0, 1};  ///< framing (first frame's bounds)
  std::string label;                      ///< written before the time in the corner (a montage panel's run)
  std::string title;                      ///< the case name, written there when there is no label
  bool edges = false;                     ///< element edges over the stress and fragments views
  bool scale_bar = true;
};

/// Fields the stress view can draw.
const std::vector<std::string>& stress_fields();

/// The per-cell values of `field` for a frame; throws Error naming the field and file if the
/// frame lacks it.
std::vector<double> field_values(vtkUnstructuredGrid* g, const std::string& field, const std::string& file);

/// Renders one frame in the given view and returns the image.
class FrameRenderer {
 public:
  explicit FrameRenderer(const ViewOptions& opt);
  ~FrameRenderer();
  /// `joints` (the run's joints dataset at this frame) is needed by the cracks view only;
  /// `walls` (the rigid walls' surfaces at this frame, run/wall_shapes.hpp), when given, are
  /// drawn translucent grey and never clipped by the cut.
  vtkSmartPointer<vtkImageData> render(vtkUnstructuredGrid* frame, double time, const std::string& file,
                                       vtkUnstructuredGrid* joints = nullptr, vtkPolyData* walls = nullptr);
  std::string gl_info() const;

 private:
  struct Impl;
  Impl* impl_;
};

}  // namespace dspdem::render
