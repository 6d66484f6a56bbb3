#include "render/offscreen.hpp"

#include <GL/osmesa.h>
#include <vtkCallbackCommand.h>
#include <vtkCommand.h>
#include <vtkGenericOpenGLRenderWindow.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPNGWriter.h>
#include <vtkRenderer.h>
#include <vtkWindowToImageFilter.h>

#include <filesystem>

#include "core/error.hpp"

namespace dspdem::render {

struct OffscreenWindow::Impl {
  OSMesaContext ctx = nullptr;
  std::vector<unsigned char> buffer;
  vtkNew<vtkGenericOpenGLRenderWindow> win;
  vtkNew<vtkCallbackCommand> on_error;
  std::string errors;
  std::string gl_version, gl_renderer;
};

namespace {
void error_observer(vtkObject*, unsigned long, void* client, void* call) {
  auto* impl = static_cast<std::string*>(client);
  const std::string msg = call ? static_cast<const char*>(call) : "";
  // Expected without X: GLEW's GLX part fails after the core GL entry points are loaded.
  if (msg.find("GLEW could not be initialized") != std::string::npos) return;
  *impl += msg;
}
}  // namespace

OffscreenWindow::OffscreenWindow(int width, int height) : impl_(std::make_unique<Impl>()), w_(width), h_(height) {
  DSPDEM_CHECK(width > 0 && height > 0 && width <= 16384 && height <= 16384, "image size {}x{} is not valid", width,
               height);
  const int attribs[] = {OSMESA_FORMAT,
                         OSMESA_RGBA,
                         OSMESA_DEPTH_BITS,
                         24,
                         OSMESA_STENCIL_BITS,
                         8,
                         OSMESA_PROFILE,
                         OSMESA_CORE_PROFILE,
                         OSMESA_CONTEXT_MAJOR_VERSION,
                         3,
                         OSMESA_CONTEXT_MINOR_VERSION,
                         2,
                         0};
  impl_->ctx = OSMesaCreateContextAttribs(attribs, nullptr);
  DSPDEM_CHECK(impl_->ctx != nullptr,
               "off-screen rendering: OSMesa could not create an OpenGL 3.2 core-profile context (is libosmesa6 "
               "installed, with the gallium llvmpipe driver?)");
  impl_->buffer.assign(static_cast<std::size_t>(width) * height * 4, 0);
  DSPDEM_CHECK(OSMesaMakeCurrent(impl_->ctx, impl_->buffer.data(), GL_UNSIGNED_BYTE, width, height),
               "off-screen rendering: OSMesaMakeCurrent failed for a {}x{} buffer", width, height);
  impl_->on_error->SetCallback(error_observer);
  impl_->on_error->SetClientData(&impl_->errors);
  vtkGenericOpenGLRenderWindow* w = impl_->win;
  w->AddObserver(vtkCommand::ErrorEvent, impl_->on_error);
  w->SetOwnContext(false);
  w->SetIsDirect(true);
  w->SetSupportsOpenGL(true);
  w->SetIsCurrent(true);
  w->SetReadyForRendering(true);
  w->SetMapped(true);
  w->SetOffScreenRendering(true);
  w->SetSize(width, height);
  w->SetMultiSamples(0);  // identical images run to run
  w->InitializeFromCurrentContext();
  const GLubyte* v = glGetString(GL_VERSION);
  const GLubyte* r = glGetString(GL_RENDERER);
  impl_->gl_version = v ? reinterpret_cast<const char*>(v) : "?";
  impl_->gl_renderer = r ? reinterpret_cast<const char*>(r) : "?";
  DSPDEM_CHECK(impl_->errors.empty(), "off-screen rendering: VTK could not use the OSMesa context: {}", impl_->errors);
}

OffscreenWindow::~OffscreenWindow() {
  impl_->win->Finalize();
  if (impl_->ctx) OSMesaDestroyContext(impl_->ctx);
}

vtkRenderWindow* OffscreenWindow::window() { return impl_->win; }

void OffscreenWindow::add_renderer(vtkRenderer* r) { impl_->win->AddRenderer(r); }

std::string OffscreenWindow::gl_info() const {
  return "OSMesa off-screen, OpenGL " + impl_->gl_version + ", renderer " + impl_->gl_renderer;
}

vtkSmartPointer<vtkImageData> OffscreenWindow::capture() {
  impl_->win->Render();
  vtkNew<vtkWindowToImageFilter> w2i;
  w2i->SetInput(impl_->win);
  w2i->SetInputBufferTypeToRGB();
  w2i->ReadFrontBufferOff();
  w2i->Update();
  DSPDEM_CHECK(impl_->errors.empty(), "rendering failed: {}", impl_->errors);
  vtkSmartPointer<vtkImageData> img = vtkSmartPointer<vtkImageData>::New();
  img->DeepCopy(w2i->GetOutput());
  return img;
}

void OffscreenWindow::write_png(const std::string& path) { render::write_png(capture(), path); }

void write_png(vtkImageData* image, const std::string& path) {
  const std::string tmp = path + ".tmp.png";
  vtkNew<vtkPNGWriter> w;
  w->SetFileName(tmp.c_str());
  w->SetInputData(image);
  w->Write();
  DSPDEM_CHECK(w->GetErrorCode() == 0 && std::filesystem::exists(tmp), "could not write image '{}'", tmp);
  std::filesystem::rename(tmp, path);
}

}  // namespace dspdem::render
