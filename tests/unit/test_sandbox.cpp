// core/sandbox: work run in a child process that the seccomp filter stops before it acts
// outside itself, and that is stopped after its time limit. Each way out is tried in the
// child, and the test looks for its trace outside (a file made, a file gone).
#include <fcntl.h>
#include <gtest/gtest.h>
#include <linux/capability.h>
#include <omp.h>
#include <signal.h>
#include <sys/ioctl.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/shm.h>
#include <sys/socket.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <thread>

#include "core/error.hpp"
#include "core/sandbox.hpp"

namespace {
namespace fs = std::filesystem;
using dspdem::run_sandboxed;
using Status = dspdem::SandboxResult::Status;

fs::path scratch() {
  const fs::path d = fs::temp_directory_path() / ("dspdem_sandbox_" + std::to_string(getpid()));
  fs::create_directories(d);
  return d;
}

// Expects `work` to be stopped, naming `call`.
void expect_refused(const std::function<std::string()>& work, const std::string& call) {
  const auto r = run_sandboxed(work, 30);
  EXPECT_EQ(r.status, Status::Refused) << r.message;
  EXPECT_EQ(r.message, call);
}

// A call made with every signal blocked (glibc's posix_spawn blocks them around its clone)
// is ended by the kernel, not by the handler that names it.
constexpr const char* kUnnamed = "";
}  // namespace

TEST(Sandbox, WorkComesBackWholeAndItsErrorsAsText) {
  // More than a pipe holds (64 KiB): the parent reads while the child writes.
  std::string big(5 << 20, '\0');
  for (std::size_t i = 0; i < big.size(); ++i) big[i] = static_cast<char>(i * 7919 % 251);
  const auto done = run_sandboxed([&] { return big; }, 30);
  ASSERT_EQ(done.status, Status::Done) << done.message;
  EXPECT_EQ(done.bytes, big);
  const auto empty = run_sandboxed([] { return std::string(); }, 30);
  EXPECT_EQ(empty.status, Status::Done);
  EXPECT_TRUE(empty.bytes.empty());
  const auto failed = run_sandboxed([]() -> std::string { dspdem::fail("no volume in {}", "x.geo"); }, 30);
  EXPECT_EQ(failed.status, Status::Failed);
  EXPECT_EQ(failed.message, "no volume in x.geo");
}

TEST(Sandbox, ReadsFilesAndRunsThreads) {
  const fs::path f = scratch() / "input.txt";
  std::ofstream(f) << "a mesh";
  const auto r = run_sandboxed(
      [&] {
        std::ifstream in(f);
        std::string s;
        std::getline(in, s);
        std::thread t([&] { s += " read"; });
        t.join();
        return s;
      },
      30);
  ASSERT_EQ(r.status, Status::Done) << r.message;
  EXPECT_EQ(r.bytes, "a mesh read");
}

TEST(Sandbox, OpenMPRunsOneThreadInTheChildAfterTheParentsTeam) {
  // The parent's OpenMP threads are not in the child (fork copies the calling thread only),
  // and libgomp's pool is not fork-safe: a team of two in the child after the parent's team
  // of two waited for them until the time limit (a review's reproduction). The sandbox sets
  // one thread; the region here asks for the default.
  int sum = 0;
#pragma omp parallel num_threads(2) reduction(+ : sum)
  sum += 1;
  ASSERT_GE(sum, 1);
  const auto r = run_sandboxed(
      [] {
        int n = 0;
#pragma omp parallel reduction(+ : n)
        n += 1;
        return std::to_string(n);
      },
      20);
  ASSERT_EQ(r.status, Status::Done) << r.message;
  EXPECT_EQ(r.bytes, "1");
}

TEST(Sandbox, StopsProgramsFilesSocketsAndSignalsToOthers) {
  const fs::path d = scratch();
  const fs::path made = d / "made", kept = d / "kept";
  std::ofstream(kept) << "keep me";
  // A program: system() starts a shell in a new process (clone without CLONE_THREAD).
  expect_refused(
      [&] {
        const int rc = std::system(("touch " + made.string()).c_str());
        return std::to_string(rc);
      },
      kUnnamed);
  expect_refused(
      [] {
        const pid_t pid = fork();
        if (pid == 0) _exit(0);
        return std::to_string(pid);
      },
      "clone");
  expect_refused(
      [] {
        char* argv[] = {const_cast<char*>("true"), nullptr};
        execv("/bin/true", argv);
        return std::string("exec returned");
      },
      "execve");
  // Files: written, emptied, removed, renamed, made.
  expect_refused([&] { return std::to_string(std::fopen(made.c_str(), "w") != nullptr); }, "openat");
  expect_refused([&] { return std::to_string(std::fopen(kept.c_str(), "r+") != nullptr); }, "openat");
  expect_refused([&] { return std::to_string(std::fopen(kept.c_str(), "a") != nullptr); }, "openat");
  expect_refused([&] { return std::to_string(unlink(kept.c_str())); }, "unlink");
  expect_refused([&] { return std::to_string(std::rename(kept.c_str(), made.c_str())); }, "rename");
  expect_refused([&] { return std::to_string(fs::create_directory(d / "dir")); }, "mkdir");
  expect_refused([&] { return std::to_string(truncate(kept.c_str(), 0)); }, "truncate");
  // A socket.
  expect_refused([] { return std::to_string(socket(AF_INET, SOCK_STREAM, 0)); }, "socket");
  // Another process (signal 0 asks only whether it is there: harmless, were it let through).
  expect_refused([] { return std::to_string(kill(getppid(), 0)); }, "kill");

  EXPECT_FALSE(fs::exists(made));
  EXPECT_FALSE(fs::exists(d / "dir"));
  std::ifstream in(kept);
  std::string s;
  std::getline(in, s);
  EXPECT_EQ(s, "keep me");
}

TEST(Sandbox, IsStoppedAfterItsTimeLimit) {
  const auto t0 = std::chrono::steady_clock::now();
  const auto r = run_sandboxed(
      [] {
        for (;;) std::this_thread::sleep_for(std::chrono::seconds(1));
        return std::string();
      },
      0.3);
  const double took = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_EQ(r.status, Status::TimedOut);
  EXPECT_NE(r.message.find("0.3 s"), std::string::npos) << r.message;
  // Stopped at its limit, not when it would have ended (never): a generous bound for a
  // loaded CI machine.
  EXPECT_LT(took, 10.0);
}

TEST(Sandbox, AnExitOrACrashInsideIsReportedNotTakenForAResult) {
  const auto exited = run_sandboxed(
      []() -> std::string {
        std::fflush(nullptr);
        _exit(3);
      },
      30);
  EXPECT_EQ(exited.status, Status::Ended);
  EXPECT_NE(exited.message.find("exit status 3"), std::string::npos) << exited.message;
  // An exit with status 0 (gmsh's Exit command) is no result either.
  const auto zero = run_sandboxed([]() -> std::string { _exit(0); }, 30);
  EXPECT_EQ(zero.status, Status::Ended) << zero.message;
  // abort(): a failed assertion's end (a signal the sanitizers leave alone, unlike SIGSEGV).
  const auto crashed = run_sandboxed(
      []() -> std::string {
        std::abort();
        return "after the crash";
      },
      30);
  EXPECT_EQ(crashed.status, Status::Ended);
  EXPECT_NE(crashed.message.find("signal 6"), std::string::npos) << crashed.message;
}

TEST(Sandbox, StopsWhatAffectsOtherProcessesOrOutlivesTheParent) {
  // A review's reproductions, each harmless were it let through (signal 0, the parent's own
  // limit set to what it is, a private IPC key).
  expect_refused([] { return std::to_string(fcntl(STDERR_FILENO, F_SETOWN, getppid())); }, "fcntl");
  expect_refused(
      [] {
        struct rlimit now {};
        getrlimit(RLIMIT_NOFILE, &now);
        return std::to_string(prlimit(getppid(), RLIMIT_NOFILE, &now, nullptr));
      },
      "prlimit64");
  expect_refused([] { return std::to_string(prctl(PR_SET_PDEATHSIG, 0)); }, "prctl");
  expect_refused([] { return std::to_string(shmget(IPC_PRIVATE, 4096, IPC_CREAT | 0600)); }, "shmget");
  expect_refused([] { return std::to_string(setsid()); }, "setsid");
  expect_refused([] { return std::to_string(ioctl(STDERR_FILENO, TIOCSWINSZ, nullptr)); }, "ioctl");
  // A second review's: a bit above an int's 32 (which the kernel drops) got F_SETOWN and the
  // parent-death reset past; a priority for the process group (who = 0) reniced a sibling;
  // O_ASYNC on the terminal shared with the parent sent it SIGIO.
  expect_refused([] { return std::to_string(syscall(SYS_fcntl, STDERR_FILENO, (1L << 32) | F_SETOWN, getppid())); },
                 "fcntl");
  expect_refused([] { return std::to_string(syscall(SYS_prctl, (1L << 32) | PR_SET_PDEATHSIG, 0L, 0L, 0L, 0L)); },
                 "prctl");
  expect_refused([] { return std::to_string(setpriority(PRIO_PGRP, 0, 0)); }, "setpriority");
  expect_refused([] { return std::to_string(fcntl(STDERR_FILENO, F_SETFL, O_ASYNC)); }, "fcntl");
}

TEST(Sandbox, CallsNewerThanTheFilterAreNotImplementedAndCapabilitiesAreGone) {
  // fchmodat2 (452), which libseccomp 2.5.4 does not know: a review made a file mode 777
  // with it. Every number from 440 to 511 is answered ENOSYS.
  const fs::path f = scratch() / "mode";
  std::ofstream(f) << "x";
  fs::permissions(f, fs::perms::owner_read | fs::perms::owner_write);
  const auto r = run_sandboxed(
      [&] {
        const long rc = syscall(452, AT_FDCWD, f.c_str(), 0777, 0);
        return std::to_string(rc) + " " + std::to_string(rc < 0 ? errno : 0);
      },
      30);
  ASSERT_EQ(r.status, Status::Done) << r.message;
  EXPECT_EQ(r.bytes, "-1 " + std::to_string(ENOSYS));
  EXPECT_EQ(fs::status(f).permissions() & fs::perms::all, fs::perms::owner_read | fs::perms::owner_write);
  // No capability left (root's would let it past much that the list does not name).
  const auto caps = run_sandboxed(
      [] {
        __user_cap_header_struct head{_LINUX_CAPABILITY_VERSION_3, 0};
        __user_cap_data_struct data[_LINUX_CAPABILITY_U32S_3] = {};
        syscall(SYS_capget, &head, data);
        return std::to_string(data[0].effective | data[1].effective | data[0].permitted | data[1].permitted);
      },
      30);
  ASSERT_EQ(caps.status, Status::Done) << caps.message;
  EXPECT_EQ(caps.bytes, "0");
}
