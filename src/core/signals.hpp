// Signal handlers held for a scope: a run's stop at the end of the step, a sweep's passing a
// stop on to its jobs. The caller's actions come back afterwards, also when it throws.
#pragma once
#include <signal.h>

#include <initializer_list>
#include <vector>

namespace dspdem {

/// Puts `handler` on each of `signals` and keeps their earlier actions to put back. A
/// signal that was ignored stays ignored: `nohup` ignores SIGHUP, and a shell without job
/// control starts a background job with SIGINT ignored, so that a hang-up or a Ctrl-C meant
/// for the terminal's job does not stop it (POSIX programs keep to this, Python's SIGINT too).
class ScopedSignals {
 public:
  ScopedSignals(std::initializer_list<int> signals, void (*handler)(int));
  ~ScopedSignals() { restore(); }
  ScopedSignals(const ScopedSignals&) = delete;
  ScopedSignals& operator=(const ScopedSignals&) = delete;

  /// Puts the handler on again, where a library (gmsh) may have put in its own since;
  /// nothing after restore().
  void install();
  /// Puts the earlier actions back (once; the destructor then does nothing). A signal that
  /// comes after this goes to them: whoever checks its handler's flag does so afterwards.
  void restore();

 private:
  std::vector<int> signals_;
  std::vector<struct sigaction> old_;
  void (*handler_)(int);
  bool held_ = true;
};

}  // namespace dspdem
