// The mesh of a case: read from its file, or made by its generator (cached).
#pragma once
#include "io/case_config.hpp"
#include "mesh/mesh.hpp"
#include "meshing/generator.hpp"

namespace dspdem {

Mesh load_case_mesh(const CaseConfig& c);

/// The case's generator name and parameters, as the meshing library takes them.
meshing::Params generator_params(const CaseConfig& c);

}  // namespace dspdem
