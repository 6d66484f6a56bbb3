// Error handling. CHECK is always on and is for input and user errors: it throws
// dspdem::Error with a message that names what was wrong. DSPDEM_ASSERT is for internal
// invariants and compiles away in Release builds.
#pragma once
#include <fmt/format.h>

#include <cassert>
#include <stdexcept>
#include <string>

namespace dspdem {

/// A user-facing error: the message is printed as is and the program exits non-zero.
class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& what) : std::runtime_error(what) {}
};

/// Numerical trouble during a run (NaN, inversion, blow-up): carries where it happened.
class NumericalError : public Error {
 public:
  NumericalError(const std::string& what, long step, double time) : Error(what), step(step), time(time) {}
  long step;
  double time;
};

/// A run stopped by SIGINT/SIGTERM/SIGHUP: numerical state intact, the user asked to stop. Whatever
/// runs several cases (a study) stops too instead of starting the next one.
class Interrupted : public NumericalError {
 public:
  using NumericalError::NumericalError;
};

template <typename... Args>
[[noreturn]] void fail(fmt::format_string<Args...> f, Args&&... args) {
  throw Error(fmt::format(f, std::forward<Args>(args)...));
}

}  // namespace dspdem

#define DSPDEM_CHECK(cond, ...)               \
  do {                                        \
    if (!(cond)) ::dspdem::fail(__VA_ARGS__); \
  } while (0)

#define DSPDEM_ASSERT(cond) assert(cond)
