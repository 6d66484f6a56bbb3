// A gmsh model's mesh as plain arrays, as gmsh's API gives them: what mesh_from_model_data
// converts into a Mesh, and how a mesh read in the sandboxed child process (core/sandbox.hpp,
// mesh/gmsh_reader.cpp) comes to the parent, as bytes through a pipe.
#pragma once
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

namespace dspdem {

/// One model entity: its own nodes (not its boundary's) and its elements by type.
struct GmshEntity {
  int dim = 0, tag = 0;
  std::vector<std::size_t> node_tags;
  std::vector<double> coord;                                    ///< 3 per node
  std::vector<int> types;                                       ///< gmsh element types
  std::vector<std::vector<std::size_t>> elem_tags, elem_nodes;  ///< per type
};

struct GmshPhysical {
  int dim = 0, tag = 0;
  std::string name;
  std::vector<int> entities;
};

/// gmsh options by name and value.
using GmshOptions = std::vector<std::pair<std::string, double>>;

struct GmshModelData {
  std::vector<GmshEntity> entities;  ///< by dimension, then as gmsh lists them
  std::vector<GmshPhysical> physicals;
  /// Options that decide how gmsh writes the model (Mesh.SaveAll, Mesh.MshFileVersion,
  /// Mesh.Binary), which the file or script may have set.
  GmshOptions write_options;
};

/// The model loaded in the gmsh API, whole.
GmshModelData gmsh_model_data();

/// As bytes and back. from_bytes throws Error naming `source` when the bytes are not a whole
/// to_bytes: they come from a process that ran untrusted input, and every count is checked
/// against the bytes left before anything is made for it.
std::string to_bytes(const GmshModelData& m);
GmshModelData from_bytes(const std::string& bytes, const std::string& source);

/// Loads `m` into the gmsh API as a new model of discrete entities with the same tags, nodes
/// and elements in the same order (for gmsh to write it). Its write options are not set: set
/// for good, a script's Mesh.MshFileVersion would go on to the generators' meshes.
void load_into_gmsh(const GmshModelData& m);

}  // namespace dspdem
