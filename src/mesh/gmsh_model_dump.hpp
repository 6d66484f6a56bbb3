// The model loaded in the gmsh API as bytes and back: how a mesh read in a sandboxed child
// process (core/sandbox.hpp, mesh/gmsh_reader.cpp) comes to the parent, which loads it into
// its own gmsh to convert and to write it.
#pragma once
#include <string>
#include <utility>
#include <vector>

namespace dspdem {

/// The current gmsh model whole: every entity of dimension 0-3 with its nodes and elements,
/// the physical groups with their names, and the options that decide how gmsh writes it
/// (Mesh.SaveAll, Mesh.MshFileVersion, Mesh.Binary), which the file or script may have set.
std::string dump_gmsh_model();

/// gmsh options by name and value.
using GmshOptions = std::vector<std::pair<std::string, double>>;

/// Loads a dump_gmsh_model into the gmsh API as a new model of discrete entities with the same
/// tags, nodes and elements in the same order, so that mesh_from_gmsh_model reads the same
/// Mesh from it as from the model dumped. Throws Error naming `source` when the bytes are not
/// a whole dump: they come from a process that ran untrusted input. Returns the dumped write
/// options, for the caller to set around gmsh::write only: set for good, a script's
/// Mesh.MshFileVersion would go on to the generators' meshes.
GmshOptions load_gmsh_model(const std::string& bytes, const std::string& source);

}  // namespace dspdem
