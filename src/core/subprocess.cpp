#include "core/subprocess.hpp"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>
#include <string_view>

extern char** environ;

namespace dspdem {

namespace {
constexpr const char* kParentVariable = "DSPDEM_STOP_WITH_PARENT";
}

pid_t spawn_program(const std::string& program, const std::vector<std::string>& args, const SpawnOptions& o) {
  const std::string& log = o.log;
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  // No stdin: a child that reads the terminal (ffmpeg does) would stop a background job.
  posix_spawn_file_actions_addopen(&fa, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  if (!log.empty()) {
    std::error_code ec;  // a log folder that cannot be made shows up as the open failing
    std::filesystem::create_directories(std::filesystem::absolute(log).parent_path(), ec);
    posix_spawn_file_actions_addopen(&fa, STDOUT_FILENO, log.c_str(),
                                     O_WRONLY | O_CREAT | (o.append_log ? O_APPEND : O_TRUNC), 0644);
    posix_spawn_file_actions_adddup2(&fa, STDOUT_FILENO, STDERR_FILENO);
  }
  std::vector<std::string> all = {program};
  all.insert(all.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& s : all) argv.push_back(s.data());
  argv.push_back(nullptr);
  // Not the MPI launcher's variables: a child (a sweep's run, a render worker) must not take
  // itself for a process of its parent's MPI job (par/mpi_world.cpp looks for them).
  std::vector<char*> env;
  for (char** e = environ; *e; ++e) {
    const std::string_view v(*e);
    if (v.rfind("OMPI_", 0) != 0 && v.rfind("PMIX_", 0) != 0 && v.rfind("PMI_", 0) != 0 &&
        v.rfind(kParentVariable, 0) != 0)
      env.push_back(*e);
  }
  std::string parent = std::string(kParentVariable) + "=" + std::to_string(getpid());
  if (o.own_group) env.push_back(parent.data());
  env.push_back(nullptr);
  posix_spawnattr_t at;
  posix_spawnattr_init(&at);
  if (o.own_group) {
    posix_spawnattr_setflags(&at, POSIX_SPAWN_SETPGROUP);
    posix_spawnattr_setpgroup(&at, 0);  // a new group, led by the child
  }
  pid_t pid = -1;
  const int rc = posix_spawnp(&pid, program.c_str(), &fa, &at, argv.data(), env.data());
  posix_spawnattr_destroy(&at);
  posix_spawn_file_actions_destroy(&fa);
  return rc == 0 ? pid : -1;
}

int wait_program(pid_t pid) {
  if (pid < 0) return -1;
  int st = 0;
  if (waitpid(pid, &st, 0) != pid) return -1;
  return WIFEXITED(st) ? WEXITSTATUS(st) : WIFSIGNALED(st) ? 128 + WTERMSIG(st) : -1;
}

int run_program(const std::string& program, const std::vector<std::string>& args, const std::string& log) {
  return wait_program(spawn_program(program, args, {.log = log}));
}

void stop_with_parent() {
  const char* v = std::getenv(kParentVariable);
  if (v == nullptr) return;
  const long parent = std::strtol(v, nullptr, 10);
  unsetenv(kParentVariable);
  prctl(PR_SET_PDEATHSIG, SIGTERM);
  // Its death before the line above sent nothing; we have been handed on to another parent.
  if (static_cast<long>(getppid()) != parent) kill(getpid(), SIGTERM);
}

std::string find_on_path(const std::string& name) {
  const char* path = std::getenv("PATH");
  std::stringstream dirs(path ? path : "");
  for (std::string d; std::getline(dirs, d, ':');) {
    const std::filesystem::path p = std::filesystem::path(d.empty() ? "." : d) / name;
    if (access(p.c_str(), X_OK) == 0 && std::filesystem::is_regular_file(p)) return p.string();
  }
  return "";
}

}  // namespace dspdem
