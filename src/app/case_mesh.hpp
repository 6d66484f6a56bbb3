// The mesh of a case: read from its file, or made by its generator (cached).
#pragma once
#include "io/case_config.hpp"
#include "mesh/mesh.hpp"

namespace dspdem {

Mesh load_case_mesh(const CaseConfig& c);

}  // namespace dspdem
