// `dspdem mesh CASE.toml [--out DIR]`: writes DIR/<case>.msh and DIR/quality.json.
#pragma once
#include <string>

#include "io/case_config.hpp"

namespace dspdem {

int mesh_command(const CaseConfig& c, const std::string& out_dir);

}  // namespace dspdem
