#include "run/process_pool.hpp"

#include <fmt/format.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <csignal>
#include <map>

#include "core/error.hpp"
#include "core/log.hpp"
#include "core/signals.hpp"
#include "core/subprocess.hpp"

namespace dspdem {

namespace {
pid_t start(const Job& j) {
  return spawn_program("/proc/self/exe", j.args, {.log = j.log, .append_log = j.append_log, .own_group = true});
}

volatile std::sig_atomic_t g_signal = 0, g_signals = 0;
// A hang-up after the first signal is not passed on again: a closing terminal's job gets
// one from the kernel and one from its shell, and a second SIGTERM would stop the runs before
// their checkpoints.
extern "C" void on_stop(int sig) {
  if (sig == SIGHUP && g_signals > 0) return;
  g_signal = sig;
  g_signals = g_signals + 1;
}

}  // namespace

std::vector<int> run_processes(const std::vector<Job>& list, int jobs,
                               const std::function<void(std::size_t, int)>& on_end) {
  DSPDEM_CHECK(jobs >= 1, "run_processes: {} jobs", jobs);
  std::vector<int> status(list.size(), -1);
  std::map<pid_t, std::size_t> running;
  std::size_t next = 0;
  // SIGINT, SIGTERM and SIGHUP count only while the pool runs.
  g_signal = 0;
  g_signals = 0;
  ScopedSignals signals({SIGINT, SIGTERM, SIGHUP}, on_stop);
  int passed_on = 0;  // signals passed on so far
  std::size_t stopped = 0;
  while ((next < list.size() && g_signal == 0) || !running.empty()) {
    while (g_signal == 0 && next < list.size() && static_cast<int>(running.size()) < jobs) {
      const pid_t pid = start(list[next]);
      if (pid < 0)
        log::warn("could not start job {} (log {})", next, list[next].log);
      else
        running[pid] = next;
      ++next;
    }
    // Each signal passed on as one SIGTERM to each running job's group (the job and whatever
    // it started, a report's render workers say): a dspdem run writes its checkpoint at the
    // first and exits at once at the second, as when it is run alone.
    if (g_signals > passed_on) {
      if (passed_on == 0) stopped = running.size();
      for (const auto& [pid, i] : running) kill(-pid, SIGTERM);
      passed_on = g_signals;
    }
    if (running.empty()) continue;
    // Polled, so that a signal between the check above and the wait is seen within 50 ms
    // rather than when the next job happens to end.
    int st = 0;
    const pid_t pid = waitpid(-1, &st, WNOHANG);
    if (pid == 0 || (pid < 0 && errno == EINTR)) {
      usleep(50000);
      continue;
    }
    if (pid < 0) break;  // no child left (should not happen: we track them all)
    const auto it = running.find(pid);
    if (it == running.end()) continue;  // a child of someone else's (render workers wait for their own)
    status[it->second] = WIFEXITED(st) ? WEXITSTATUS(st) : WIFSIGNALED(st) ? 128 + WTERMSIG(st) : -1;
    const std::size_t ended = it->second;
    running.erase(it);
    if (on_end) on_end(ended, status[ended]);
  }
  // The caller's handlers back before the last look at the flag: a signal that came after
  // the loop's last look still stops the caller (exit 5), rather than being lost.
  signals.restore();
  if (g_signal != 0)
    throw Interrupted(fmt::format("{}: {} job(s) stopped, {} not started",
                                  g_signal == SIGINT    ? "SIGINT"
                                  : g_signal == SIGTERM ? "SIGTERM"
                                                        : "SIGHUP",
                                  stopped, list.size() - next),
                      0, 0.0);
  return status;
}

}  // namespace dspdem
