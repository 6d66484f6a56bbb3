// The one place that sets up GL: an OSMesa core-profile (3.2) context rendered into by a
// vtkGenericOpenGLRenderWindow that does not own the context. Works with no X server and
// no DISPLAY. Failure to create the context is an Error with the reason, never a crash.
//
// GLEW (inside VTK) also tries to initialise its GLX extension entry points, which fails
// without an X display after the core GL functions have loaded; VTK reports that as
// "GLEW could not be initialized". We catch VTK errors with an observer on the window,
// drop exactly that message, and turn every other VTK error into an Error.
#pragma once
#include <vtkSmartPointer.h>

#include <memory>
#include <string>
#include <vector>

class vtkRenderWindow;
class vtkRenderer;
class vtkImageData;

namespace dspdem::render {

class OffscreenWindow {
 public:
  OffscreenWindow(int width, int height);
  ~OffscreenWindow();
  OffscreenWindow(const OffscreenWindow&) = delete;
  OffscreenWindow& operator=(const OffscreenWindow&) = delete;

  vtkRenderWindow* window();
  void add_renderer(vtkRenderer* r);
  /// Renders and returns the image (RGB); throws Error if VTK reported an error.
  vtkSmartPointer<vtkImageData> capture();
  /// Renders and writes a PNG through a temporary name.
  void write_png(const std::string& path);
  /// "OSMesa <GL version> (<renderer>), core profile": which GL path rendered.
  std::string gl_info() const;
  int width() const { return w_; }
  int height() const { return h_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  int w_, h_;
};

/// Writes an image as PNG through a temporary name and a rename.
void write_png(vtkImageData* image, const std::string& path);

}  // namespace dspdem::render
