#include "core/log.hpp"

namespace dspdem::log {
namespace {
Level g_level = Level::Info;
bool g_warnings = true;
}  // namespace
bool warnings() { return g_warnings; }
void set_warnings(bool on) { g_warnings = on; }
Level level() { return g_level; }
void set_level(Level l) { g_level = l; }

std::string printable(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    const auto u = static_cast<unsigned char>(c);
    if ((u < 32 && c != '\n' && c != '\t') || u == 127)
      out += fmt::format("\\x{:02x}", u);
    else
      out += c;
  }
  return out;
}
}  // namespace dspdem::log
