// Reading a run's frames: run.pvd (times and files) and the VTU frames.
#pragma once
#include <vtkSmartPointer.h>

#include <string>
#include <vector>

class vtkUnstructuredGrid;

namespace dspdem::render {

struct FrameRef {
  double time = 0;
  std::string file;  ///< absolute path of the .vtu
};

/// Frames listed in RUN_DIR/<collection> (run.pvd, or joints.pvd for the joints dataset);
/// throws Error naming the file if it is missing or empty.
std::vector<FrameRef> read_series(const std::string& run_dir, const std::string& collection = "run.pvd");

/// Reads one frame; a missing, truncated or unreadable file is an Error naming it.
vtkSmartPointer<vtkUnstructuredGrid> read_frame(const std::string& path);

}  // namespace dspdem::render
