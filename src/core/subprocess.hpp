// Other programs started without a shell: the arguments go to the program as they are, so a
// path with spaces, quotes or parentheses (an ffmpeg filter) needs no quoting.
#pragma once
#include <sys/types.h>

#include <string>
#include <vector>

namespace dspdem {

/// Starts `program` (looked up on PATH when it has no '/') with `args`, its stdin /dev/null, its
/// stdout and stderr into `log` ("" keeps ours); returns the pid, or -1 when it could not start.
/// `own_group`: in a process group of its own, so that a signal to ours (Ctrl-C at a terminal)
/// does not reach it; the parent then passes it on (run_processes).
pid_t spawn_program(const std::string& program, const std::vector<std::string>& args, const std::string& log,
                    bool own_group = false);

/// The exit code of a child started by spawn_program, 128 + the signal that ended it, or -1.
int wait_program(pid_t pid);

/// spawn_program and wait_program together.
int run_program(const std::string& program, const std::vector<std::string>& args, const std::string& log);

/// The full path of `name` on PATH, or "" when it is not there.
std::string find_on_path(const std::string& name);

}  // namespace dspdem
