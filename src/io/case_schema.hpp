// Declarations of every case-file key: type, default, range, unit and documentation.
// The reader validates against this table, and `dspdem keys` prints it.
#pragma once
#include <string>
#include <vector>

#include "core/key_spec.hpp"

namespace dspdem::schema {

/// Every key of the case file.
const std::vector<Key>& keys();
/// Sections that may appear (as written in keys(): "materials.<name>" matches any name).
const std::vector<const char*>& sections();
/// The range as text, e.g. "> 0", "(-1, 0.5)", or "" when unbounded.
std::string range_text(const Key& k);
const char* type_name(Type t);

}  // namespace dspdem::schema
