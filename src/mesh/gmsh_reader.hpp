// Reads a mesh through the gmsh API: a .msh file (v2 or v4), or a .geo script that gmsh
// runs and meshes in 3D. Only tet4 and hex8 volume cells are accepted.
#pragma once
#include <string>

#include "mesh/mesh.hpp"

namespace dspdem {

/// Loads `path`; throws Error naming the file for anything unreadable or unsupported (the
/// text of a .msh file is checked first, its faults named by line: mesh/msh_check.hpp).
/// save_as: also write the model gmsh read (a .geo's mesh) as a .msh file there, through a
/// temporary name.
Mesh read_gmsh(const std::string& path, const std::string& save_as = "");

/// Converts the model currently loaded in the gmsh API into a Mesh (used by the reader
/// and by the generators in meshing/). `source` names the origin in messages.
Mesh mesh_from_gmsh_model(const std::string& source);

/// RAII guard for the gmsh library (it is a process-wide singleton).
class GmshSession {
 public:
  GmshSession();
  ~GmshSession();
  GmshSession(const GmshSession&) = delete;
  GmshSession& operator=(const GmshSession&) = delete;

 private:
  int omp_threads_;
};

}  // namespace dspdem
