#include "run/process_pool.hpp"

#include <sys/wait.h>

#include <algorithm>
#include <map>

#include "core/error.hpp"
#include "core/log.hpp"
#include "core/subprocess.hpp"

namespace dspdem {

namespace {
pid_t start(const Job& j) { return spawn_program("/proc/self/exe", j.args, j.log); }
}  // namespace

std::vector<int> run_processes(const std::vector<Job>& list, int jobs) {
  DSPDEM_CHECK(jobs >= 1, "run_processes: {} jobs", jobs);
  std::vector<int> status(list.size(), -1);
  std::map<pid_t, std::size_t> running;
  std::size_t next = 0;
  while (next < list.size() || !running.empty()) {
    while (next < list.size() && static_cast<int>(running.size()) < jobs) {
      const pid_t pid = start(list[next]);
      if (pid < 0)
        log::warn("could not start job {} (log {})", next, list[next].log);
      else
        running[pid] = next;
      ++next;
    }
    if (running.empty()) continue;
    int st = 0;
    const pid_t pid = waitpid(-1, &st, 0);
    if (pid < 0) break;  // no child left (should not happen: we track them all)
    const auto it = running.find(pid);
    if (it == running.end()) continue;  // a child of someone else's (render workers wait for their own)
    status[it->second] = WIFEXITED(st) ? WEXITSTATUS(st) : WIFSIGNALED(st) ? 128 + WTERMSIG(st) : -1;
    running.erase(it);
  }
  return status;
}

}  // namespace dspdem
