#include "render/series.hpp"

#include <vtkCallbackCommand.h>
#include <vtkExecutive.h>
#include <vtkNew.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLPUnstructuredGridReader.h>
#include <vtkXMLReader.h>
#include <vtkXMLUnstructuredGridReader.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <regex>

#include "core/error.hpp"
#include "core/file.hpp"

namespace dspdem::render {

namespace fs = std::filesystem;

std::vector<FrameRef> read_series(const std::string& run_dir, const std::string& collection) {
  const fs::path pvd = fs::path(run_dir) / collection;
  DSPDEM_CHECK(fs::exists(pvd), "'{}' not found: is '{}' the output folder of a dspdem run?", pvd.string(), run_dir);
  const std::string text = read_file(pvd.string(), "collection");
  std::vector<FrameRef> frames;
  const std::regex ds("<DataSet[^>]*timestep=\"([^\"]+)\"[^>]*file=\"([^\"]+)\"");
  for (auto it = std::sregex_iterator(text.begin(), text.end(), ds); it != std::sregex_iterator(); ++it) {
    FrameRef fr;
    // The whole text a finite number ("2.09e-05xyz" and "nan" were read as times).
    const std::string t = (*it)[1].str();
    char* end = nullptr;
    fr.time = std::strtod(t.c_str(), &end);
    DSPDEM_CHECK(!t.empty() && *end == '\0' && std::isfinite(fr.time), "'{}': timestep '{}' is not a number",
                 pvd.string(), t);
    fr.file = (fs::path(run_dir) / (*it)[2].str()).string();
    frames.push_back(fr);
  }
  DSPDEM_CHECK(!frames.empty(), "'{}' lists no frames", pvd.string());
  return frames;
}

namespace {
void on_error(vtkObject*, unsigned long, void* client, void* call) {
  *static_cast<std::string*>(client) += call ? static_cast<const char*>(call) : "error";
}
}  // namespace

vtkSmartPointer<vtkUnstructuredGrid> read_frame(const std::string& path) {
  DSPDEM_CHECK(fs::exists(path), "frame '{}' does not exist", path);
  std::string errors;
  vtkNew<vtkCallbackCommand> cb;
  cb->SetCallback(on_error);
  cb->SetClientData(&errors);
  // A distributed run's frame is a .pvtu naming one piece per process: read as one grid.
  vtkSmartPointer<vtkXMLReader> r;
  if (fs::path(path).extension() == ".pvtu")
    r = vtkSmartPointer<vtkXMLPUnstructuredGridReader>::New();
  else
    r = vtkSmartPointer<vtkXMLUnstructuredGridReader>::New();
  r->AddObserver(vtkCommand::ErrorEvent, cb);
  r->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, cb);
  r->SetFileName(path.c_str());
  r->Update();
  vtkUnstructuredGrid* g = vtkUnstructuredGrid::SafeDownCast(r->GetOutputDataObject(0));
  DSPDEM_CHECK(errors.empty() && g && g->GetNumberOfCells() > 0, "frame '{}' is truncated or unreadable{}", path,
               errors.empty() ? "" : ": " + errors.substr(0, 300));
  vtkSmartPointer<vtkUnstructuredGrid> out = vtkSmartPointer<vtkUnstructuredGrid>::New();
  out->ShallowCopy(g);
  return out;
}

}  // namespace dspdem::render
