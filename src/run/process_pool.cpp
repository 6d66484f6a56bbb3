#include "run/process_pool.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <map>

#include "core/error.hpp"
#include "core/log.hpp"

extern char** environ;

namespace dspdem {

namespace {
pid_t start(const Job& j) {
  std::filesystem::create_directories(std::filesystem::absolute(j.log).parent_path());
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_addopen(&fa, STDOUT_FILENO, j.log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&fa, STDOUT_FILENO, STDERR_FILENO);
  std::vector<std::string> args = {"/proc/self/exe"};
  args.insert(args.end(), j.args.begin(), j.args.end());
  std::vector<char*> argv;
  for (auto& s : args) argv.push_back(s.data());
  argv.push_back(nullptr);
  pid_t pid = -1;
  const int rc = posix_spawn(&pid, "/proc/self/exe", &fa, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&fa);
  return rc == 0 ? pid : -1;
}
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
