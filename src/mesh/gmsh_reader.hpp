// Reads a mesh through the gmsh API: a .msh file (v2 or v4), or a .geo script that gmsh
// runs and meshes in 3D. Only tet4 and hex8 volume cells are accepted.
#pragma once
#include <string>

#include "mesh/gmsh_model_data.hpp"
#include "mesh/mesh.hpp"

namespace dspdem {

/// Seconds gmsh may take to read a mesh file or to run and mesh a .geo, by default ([mesh]
/// time_limit): minutes more than the shipped cases' meshes take, and a script that never
/// ends still ends.
constexpr double kMeshTimeLimit = 600;

/// Loads `path`; throws Error naming the file for anything unreadable or unsupported (the
/// text of a .msh file is checked first, its faults named by line: mesh/msh_check.hpp).
/// save_as: also write the model gmsh read (a .geo's mesh) as a .msh file there, through a
/// temporary name. gmsh reads the file in a child process that cannot start programs, write
/// files or open sockets (core/sandbox.hpp), stopped with an Error after `time_limit` seconds.
Mesh read_gmsh(const std::string& path, const std::string& save_as = "", double time_limit = kMeshTimeLimit);

/// read_gmsh without its checks of the text: gmsh opens the file in the sandbox at once.
/// For tests of the sandbox, with scripts that the checks would refuse first.
Mesh read_gmsh_unchecked(const std::string& path, const std::string& save_as = "", double time_limit = kMeshTimeLimit);

/// Converts a gmsh model's arrays into a Mesh; `source` names the origin in messages.
Mesh mesh_from_model_data(const GmshModelData& model, const std::string& source);

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
