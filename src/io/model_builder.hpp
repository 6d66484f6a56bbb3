// A case turned into a model: the mesh's groups matched to bodies, materials, joints,
// boundary conditions, walls and monitors. Lives in io/ because it reads the case format;
// the time layer only knows the Model.
#pragma once
#include "io/case_config.hpp"
#include "mesh/mesh.hpp"
#include "time/model.hpp"

namespace dspdem {

/// Builds the model from a case and a mesh. Throws Error naming the case key for groups or
/// bodies that do not match the mesh.
Model build_model(const CaseConfig& c, Mesh mesh);

}  // namespace dspdem
