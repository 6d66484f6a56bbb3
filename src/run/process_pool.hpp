// Runs of a sweep as separate dspdem processes, at most `jobs` at a time: each variant is
// its own process with its own run folder and log, so a crash or a numerical failure in
// one cannot take the others down, and `-t 1` per process uses the cores without OpenMP
// threads waiting on each other.
#pragma once
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

namespace dspdem {

struct Job {
  std::vector<std::string> args;  ///< arguments after the program (this same dspdem binary)
  std::string log;                ///< file for the process's stdout and stderr
  bool append_log = false;        ///< add to `log` (a run continued from its checkpoint)
};

/// Starts the jobs in order, keeping at most `jobs` (>= 1) running; returns each one's exit
/// status (the code, or 128 + the signal that ended it; -1 if it could not be started).
/// Each job runs in a process group of its own. Each SIGINT, SIGTERM or SIGHUP to this process
/// meanwhile (one this process was started with ignored stays ignored; a hang-up after the
/// first signal does not count again) is passed on as one SIGTERM to each running job's group
/// (a dspdem run writes its checkpoint at the first, once its set-up is done, and exits at once
/// at the second), no further job is started, and once the running ones have ended Interrupted
/// is thrown, saying how many were stopped and how many never started. If this process dies, a
/// SIGKILL included, each job (not what the job started in turn) gets a SIGTERM
/// (stop_with_parent). The kernel sends that when the thread that started the job ends: call
/// this from a thread that outlives the jobs (the main thread does). `on_end`, if given, is
/// called with a job's index and status as each one ends, in this process, stopped or not.
std::vector<int> run_processes(const std::vector<Job>& list, int jobs,
                               const std::function<void(std::size_t, int)>& on_end = nullptr);

}  // namespace dspdem
