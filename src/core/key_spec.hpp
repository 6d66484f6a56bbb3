// The declaration of one case-file key: type, default, range, unit and documentation. Here
// rather than in io/ so that modules below io (the mesh generators) can declare their own
// parameters beside their code; io/case_schema gathers them all.
#pragma once

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

}  // namespace dspdem::schema
