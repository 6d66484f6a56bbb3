#include "core/file.hpp"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "core/error.hpp"

namespace dspdem {

namespace {
// errno's reason when the stream failed, "" when it read the whole file.
std::optional<std::string> read(const std::string& path, std::string& out) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) return std::string("it is a folder");
  errno = 0;
  std::ifstream f(path, std::ios::binary);
  if (!f) return std::string(errno != 0 ? std::strerror(errno) : "it cannot be opened");
  out.assign(std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>());
  if (f.bad()) return std::string(errno != 0 ? std::strerror(errno) : "a read failed");
  return std::nullopt;
}
}  // namespace

std::string read_file(const std::string& path, std::string_view what) {
  std::string s;
  if (const auto why = read(path, s)) fail("cannot read {} '{}': {}", what, path, *why);
  return s;
}

std::optional<std::string> read_file_if(const std::string& path) {
  std::string s;
  if (read(path, s)) return std::nullopt;
  return s;
}

}  // namespace dspdem
