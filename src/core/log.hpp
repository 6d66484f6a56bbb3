// Minimal leveled logging to stderr. Quiet mode keeps CI logs short.
#pragma once
#include <fmt/format.h>

#include <cstdio>
#include <string>
#include <string_view>

namespace dspdem::log {

enum class Level { Quiet = 0, Info = 1, Debug = 2 };

/// `text` with its control bytes (but newline and tab) written as \xNN: messages carry names
/// and text from input files (a .geo's strings, gmsh's errors about them), whose escape
/// sequences would otherwise reach the terminal (retitle it, clear it, type into it).
std::string printable(std::string_view text);

Level level();
void set_level(Level l);

template <typename... Args>
void info(fmt::format_string<Args...> f, Args&&... args) {
  if (level() >= Level::Info) fmt::print(stderr, "{}\n", printable(fmt::format(f, std::forward<Args>(args)...)));
}

template <typename... Args>
void debug(fmt::format_string<Args...> f, Args&&... args) {
  if (level() >= Level::Debug) fmt::print(stderr, "{}\n", printable(fmt::format(f, std::forward<Args>(args)...)));
}

/// Off on the processes of a distributed run other than the first, which all say the same.
bool warnings();
void set_warnings(bool on);

/// Warnings are printed at every level: they say something the user should act on.
template <typename... Args>
void warn(fmt::format_string<Args...> f, Args&&... args) {
  if (warnings()) fmt::print(stderr, "warning: {}\n", printable(fmt::format(f, std::forward<Args>(args)...)));
}

}  // namespace dspdem::log
