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
}  // namespace dspdem::log
