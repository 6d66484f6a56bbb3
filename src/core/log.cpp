#include "core/log.hpp"

namespace dspdem::log {
namespace {
Level g_level = Level::Info;
}
Level level() { return g_level; }
void set_level(Level l) { g_level = l; }
}  // namespace dspdem::log
