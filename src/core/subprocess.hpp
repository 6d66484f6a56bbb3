// Other programs started without a shell: the arguments go to the program as they are, so a
// path with spaces, quotes or parentheses (an ffmpeg filter) needs no quoting.
#pragma once
#include <sys/types.h>

#include <string>
#include <vector>

namespace dspdem {

struct SpawnOptions {
  std::string log;          ///< the child's stdout and stderr go into this file ("": ours)
  bool append_log = false;  ///< add to the log instead of replacing it
  /// In a process group of its own, so that a signal to ours (Ctrl-C at a terminal) does not
  /// reach it; the parent then passes it on (run_processes). Such a child, if it is dspdem,
  /// also gets a SIGTERM when the parent dies (stop_with_parent), a SIGKILL of it included.
  bool own_group = false;
};

/// Starts `program` (looked up on PATH when it has no '/') with `args`, its stdin /dev/null;
/// returns the pid, or -1 when it could not start.
pid_t spawn_program(const std::string& program, const std::vector<std::string>& args, const SpawnOptions& o = {});

/// The exit code of a child started by spawn_program, 128 + the signal that ended it, or -1.
int wait_program(pid_t pid);

/// spawn_program and wait_program together.
int run_program(const std::string& program, const std::vector<std::string>& args, const std::string& log);

/// In a child that spawn_program started with `own_group`: asks the kernel for a SIGTERM when
/// the parent dies, as when it passes a signal on (a dspdem run then writes its checkpoint);
/// if the parent has died already, the SIGTERM comes now. Nothing elsewhere. Called first
/// thing by dspdem's main; the variable that marks such a child is taken out of the
/// environment, so that what this child starts does not take it for its own.
void stop_with_parent();

/// The full path of `name` on PATH, or "" when it is not there.
std::string find_on_path(const std::string& name);

}  // namespace dspdem
