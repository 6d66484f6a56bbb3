// The disc's two ways of being loaded, as `--set` overrides of a case's [[walls]]: the
// paper's flat steel plates (60 mm wide, 20 mm thick, as rigid boxes) and the ISRM curved
// jaws (radius 1.5 R, arc +-30 deg). The study swaps one for the other; the stress check
// loads through plates, whose field is the point-load solution it compares with.
#pragma once
#include <string>
#include <vector>

#include "io/case_config.hpp"

namespace dspdem {

/// True when every wall of the case is a curved jaw.
bool loads_through_jaws(const CaseConfig& c);

/// Overrides that replace each jaw by a flat plate touching the disc where the jaw does,
/// moving as it does (same name, velocity, ramp, friction and stiffness).
std::vector<std::string> flat_plate_overrides(const CaseConfig& c);

/// Overrides that turn each wall into a curved jaw touching the disc at its load line.
std::vector<std::string> curved_jaw_overrides(const CaseConfig& c);

}  // namespace dspdem
