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
  for (std::size_t i = 0; i < text.size(); ++i) {
    const auto u = static_cast<unsigned char>(text[i]);
    // C1 controls too (U+0080-U+009F, UTF-8 C2 80-9F: CSI among them, which some terminals act on).
    const bool c1 = u == 0xc2 && i + 1 < text.size() && static_cast<unsigned char>(text[i + 1]) >= 0x80 &&
                    static_cast<unsigned char>(text[i + 1]) <= 0x9f;
    if (c1) {
      out += fmt::format("\\u{:04x}", static_cast<unsigned char>(text[++i]));
    } else if ((u < 32 && u != '\n' && u != '\t') || u == 127) {
      out += fmt::format("\\x{:02x}", u);
    } else {
      out += text[i];
    }
  }
  return out;
}
}  // namespace dspdem::log
