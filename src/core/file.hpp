// Whole files read into memory, with the failure named. Written through a temporary and a
// rename is io/staging.hpp's write_file_atomic.
#pragma once
#include <optional>
#include <string>
#include <string_view>

namespace dspdem {

/// The bytes of the file at `path`. Error "cannot read <what> '<path>': <reason>" when it
/// cannot be opened or read to its end.
std::string read_file(const std::string& path, std::string_view what = "file");

/// The same, or nullopt where read_file fails (a file that is optional, or a guess).
std::optional<std::string> read_file_if(const std::string& path);

}  // namespace dspdem
