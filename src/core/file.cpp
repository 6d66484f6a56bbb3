#include "core/file.hpp"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "core/error.hpp"

namespace dspdem {

namespace {
// The reason it cannot be read, or nullopt once `out` holds the whole file. Regular files
// only: a FIFO or a device would block or never end.
std::optional<std::string> read(const std::string& path, std::string& out) {
  std::error_code ec;
  const auto st = std::filesystem::status(path, ec);
  if (std::filesystem::is_directory(st)) return std::string("it is a folder");
  if (std::filesystem::exists(st) && !std::filesystem::is_regular_file(st))
    return std::string("it is not a regular file");
  errno = 0;
  std::ifstream f(path, std::ios::binary);
  if (!f) return std::string(errno != 0 ? std::strerror(errno) : "it cannot be opened");
  try {
    out.assign(std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>());
  } catch (const std::exception& e) {  // libstdc++'s filebuf throws on a read error
    return std::string(errno != 0 ? std::strerror(errno) : e.what());
  }
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
