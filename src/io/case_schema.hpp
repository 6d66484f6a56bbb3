// Declarations of every case-file key: type, default, range, unit and documentation.
// The reader validates against this table, and `dspdem keys` prints it.
#pragma once
#include <string>
#include <vector>

namespace dspdem::schema {

enum class Type { Real, Int, Bool, String, Vec3, StringList };

struct Key {
  const char* section;  ///< "time", "materials.<name>", "bodies[]" ...
  const char* key;
  Type type;
  const char* def;  ///< default as written in TOML; nullptr = required; "auto" = derived
  double lo, hi;    ///< numeric range
  bool lo_open, hi_open;
  const char* unit;
  const char* choices;  ///< "a|b|c" for strings, or nullptr
  const char* doc;
};

/// Every key of the case file.
const std::vector<Key>& keys();
/// Sections that may appear (as written in keys(): "materials.<name>" matches any name).
const std::vector<const char*>& sections();
/// The range as text, e.g. "> 0", "(-1, 0.5)", or "" when unbounded.
std::string range_text(const Key& k);
const char* type_name(Type t);

}  // namespace dspdem::schema
