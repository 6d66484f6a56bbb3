// Work on untrusted input done in a child process that cannot act outside itself: without
// capabilities, under a seccomp filter that stops it before it starts a program or a process,
// opens a file for writing, makes, removes, renames or changes a file, opens a socket or an
// IPC object, or signals, limits or schedules another process (install_filter in the .cpp has
// the list and its reasons); system calls newer than that list are answered ENOSYS. Its CPU
// time and memory are bounded, it runs OpenMP on one thread, and the parent kills it after a
// time limit. A gmsh .geo is a program (SystemCall, Save, Exit, a loop that never ends), and a
// case file is often someone else's: mesh/gmsh_reader runs gmsh here. What the work returns
// comes back through a pipe as bytes.
#pragma once
#include <functional>
#include <string>

namespace dspdem {

struct SandboxResult {
  enum class Status {
    Done,      ///< the work returned: `bytes` holds what it returned
    Failed,    ///< the work threw dspdem::Error or std::exception: `message` holds its text
    Refused,   ///< the filter stopped it: `message` names the system call ("" where it is not known)
    TimedOut,  ///< still running after the time limit: killed; `message` says so
    Ended,     ///< it ended otherwise (exit() inside the work, a crash, a signal): `message` says how
  };
  Status status = Status::Ended;
  std::string bytes;
  std::string message;
};

/// Runs `work` in a child process under the filter above, with `seconds` to finish; blocks
/// until it has. The child gets stdin, stdout and stderr (its log goes where ours does) and
/// no other file descriptor of ours; it dies with the parent, and leaves no core file.
/// Signals that end the parent (SIGINT, SIGTERM, SIGHUP) end the child as they come.
SandboxResult run_sandboxed(const std::function<std::string()>& work, double seconds);

}  // namespace dspdem
