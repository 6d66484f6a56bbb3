#include "core/sandbox.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <linux/capability.h>
#include <omp.h>
#include <poll.h>
#include <sched.h>
#include <seccomp.h>
#include <signal.h>
#include <sys/ioctl.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/syscall.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <climits>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <system_error>

namespace dspdem {

namespace {
// The child writes its result on this descriptor (the pipe's end, moved there), and nothing
// else of ours stays open in it.
constexpr int kResultFd = 3;
// The child's exit status when the filter stopped it (the SIGSYS handler's).
constexpr int kRefusedExit = 117;
constexpr char kDone = 'D', kFailed = 'F', kRefused = 'R';
// Longer limits are taken as this (115 days), which the clock's ticks hold.
constexpr double kMostSeconds = 1e7;
constexpr scmp_datum_t kIoprioWhoProcess = 1;  // linux/ioprio.h, not in glibc's headers

bool write_all(int fd, const char* p, std::size_t n) {
  while (n > 0) {
    const ssize_t w = write(fd, p, n);
    if (w < 0 && errno == EINTR) continue;
    if (w <= 0) return false;
    p += w;
    n -= static_cast<std::size_t>(w);
  }
  return true;
}

// The filter's action on a call it stops is a SIGSYS here, with the call's number: the call
// has not run, and the handler reports it and ends the child. Only async-signal-safe calls.
extern "C" void on_refused_call(int, siginfo_t* si, void*) {
  char msg[1 + sizeof(int)];
  msg[0] = kRefused;
  const int nr = si->si_syscall;
  std::memcpy(msg + 1, &nr, sizeof nr);
  const ssize_t w = write(kResultFd, msg, sizeof msg);
  (void)w;
  _exit(kRefusedExit);
}

// What the child may not do. A list of what it may not do, not of what it may: the work is a
// library (gmsh) whose calls are not ours to list, and an allow-list that missed one (a new
// glibc's, the sanitizers') would stop good input. On it: programs and processes; files
// written, made, removed or changed; sockets and other programs' IPC objects; signals,
// limits and scheduling of other processes; io_uring (whose operations the filter would not
// see); namespaces, mounts and what only root may do (its capabilities are dropped too);
// the terminal; and every system call newer than this list (numbers 440-511, the same on
// every architecture since Linux 5.1: file_setattr, of 2025, is 469, and x86-64's table stops
// below 512, where its x32 entries begin), answered "not implemented", as glibc expects of an
// older kernel: a deny-list cannot name calls that did not exist when it was written (a
// review turned a file to mode 777 with fchmodat2, 452, which libseccomp 2.5.4 does not
// know). Not on to 1023: each rule adds to the child's set-up (the sandbox's own cost, a child
// that returns nothing, was 28 ms with them and 17 ms without; session 109).
bool install_filter(std::string& why) {
  scmp_filter_ctx ctx = seccomp_init(SCMP_ACT_ALLOW);  // also sets no_new_privs
  if (!ctx) {
    why = "seccomp_init failed";
    return false;
  }
  int rc = 0;
  auto stop = [&](int nr, unsigned n = 0, scmp_arg_cmp a = {}) {
    if (rc == 0)
      rc = n == 0 ? seccomp_rule_add(ctx, SCMP_ACT_TRAP, nr, 0) : seccomp_rule_add(ctx, SCMP_ACT_TRAP, nr, 1, a);
  };
  for (int nr :
       {// programs, processes, other processes' memory
        SCMP_SYS(execve), SCMP_SYS(execveat), SCMP_SYS(fork), SCMP_SYS(vfork), SCMP_SYS(ptrace),
        SCMP_SYS(process_vm_writev), SCMP_SYS(process_vm_readv), SCMP_SYS(kcmp), SCMP_SYS(setsid), SCMP_SYS(setpgid),
        // sockets, IPC objects shared with other programs
        SCMP_SYS(socket), SCMP_SYS(socketpair), SCMP_SYS(shmget), SCMP_SYS(shmat), SCMP_SYS(shmctl), SCMP_SYS(msgget),
        SCMP_SYS(msgsnd), SCMP_SYS(msgrcv), SCMP_SYS(msgctl), SCMP_SYS(semget), SCMP_SYS(semop), SCMP_SYS(semtimedop),
        SCMP_SYS(semctl), SCMP_SYS(mq_open), SCMP_SYS(mq_unlink), SCMP_SYS(mq_timedsend), SCMP_SYS(mq_timedreceive),
        SCMP_SYS(mq_notify), SCMP_SYS(mq_getsetattr), SCMP_SYS(io_uring_setup), SCMP_SYS(io_uring_enter),
        SCMP_SYS(io_uring_register),
        // files and folders made, removed, renamed or changed
        SCMP_SYS(creat), SCMP_SYS(unlink), SCMP_SYS(unlinkat), SCMP_SYS(rename), SCMP_SYS(renameat),
        SCMP_SYS(renameat2), SCMP_SYS(mkdir), SCMP_SYS(mkdirat), SCMP_SYS(rmdir), SCMP_SYS(link), SCMP_SYS(linkat),
        SCMP_SYS(symlink), SCMP_SYS(symlinkat), SCMP_SYS(mknod), SCMP_SYS(mknodat), SCMP_SYS(chmod), SCMP_SYS(fchmod),
        SCMP_SYS(fchmodat), SCMP_SYS(chown), SCMP_SYS(fchown), SCMP_SYS(lchown), SCMP_SYS(fchownat), SCMP_SYS(truncate),
        SCMP_SYS(ftruncate), SCMP_SYS(fallocate), SCMP_SYS(utime), SCMP_SYS(utimes), SCMP_SYS(utimensat),
        SCMP_SYS(futimesat), SCMP_SYS(setxattr), SCMP_SYS(lsetxattr), SCMP_SYS(fsetxattr), SCMP_SYS(removexattr),
        SCMP_SYS(lremovexattr), SCMP_SYS(fremovexattr), SCMP_SYS(copy_file_range), SCMP_SYS(name_to_handle_at),
        SCMP_SYS(open_by_handle_at), SCMP_SYS(fanotify_init), SCMP_SYS(fanotify_mark), SCMP_SYS(acct),
        // namespaces, mounts and the system
        SCMP_SYS(mount), SCMP_SYS(umount2), SCMP_SYS(open_tree), SCMP_SYS(move_mount), SCMP_SYS(fsopen),
        SCMP_SYS(fsconfig), SCMP_SYS(fsmount), SCMP_SYS(fspick), SCMP_SYS(unshare), SCMP_SYS(setns), SCMP_SYS(chroot),
        SCMP_SYS(pivot_root), SCMP_SYS(bpf), SCMP_SYS(perf_event_open), SCMP_SYS(userfaultfd), SCMP_SYS(keyctl),
        SCMP_SYS(add_key), SCMP_SYS(request_key), SCMP_SYS(init_module), SCMP_SYS(finit_module),
        SCMP_SYS(delete_module), SCMP_SYS(kexec_load), SCMP_SYS(kexec_file_load), SCMP_SYS(reboot), SCMP_SYS(swapon),
        SCMP_SYS(swapoff), SCMP_SYS(iopl), SCMP_SYS(ioperm), SCMP_SYS(sethostname), SCMP_SYS(setdomainname),
        SCMP_SYS(settimeofday), SCMP_SYS(clock_settime), SCMP_SYS(clock_adjtime), SCMP_SYS(adjtimex),
        SCMP_SYS(quotactl), SCMP_SYS(syslog), SCMP_SYS(vhangup), SCMP_SYS(migrate_pages), SCMP_SYS(move_pages),
        // other processes by descriptor or thread id
        SCMP_SYS(pidfd_open), SCMP_SYS(pidfd_getfd), SCMP_SYS(pidfd_send_signal), SCMP_SYS(tkill)})
    stop(nr);
  // Threads are the work's own (gmsh, OpenMP, the sanitizers); a clone without CLONE_THREAD
  // is a new process. clone3 passes its flags in memory, which the filter cannot read: it
  // is answered "not implemented", and glibc then uses clone.
  stop(SCMP_SYS(clone), 1, SCMP_A0(SCMP_CMP_MASKED_EQ, CLONE_THREAD, 0));
  for (int nr : {SCMP_SYS(clone3), SCMP_SYS(openat2)})
    if (rc == 0) rc = seccomp_rule_add(ctx, SCMP_ACT_ERRNO(ENOSYS), nr, 0);
  for (int nr = 440; nr < 512 && rc == 0; ++nr) rc = seccomp_rule_add(ctx, SCMP_ACT_ERRNO(ENOSYS), nr, 0);
  // Files open for reading only: each flag that writes, creates or empties is stopped.
  for (unsigned flag : {unsigned(O_WRONLY), unsigned(O_RDWR), unsigned(O_CREAT), unsigned(O_TRUNC)}) {
    stop(SCMP_SYS(open), 1, SCMP_A1(SCMP_CMP_MASKED_EQ, flag, flag));
    stop(SCMP_SYS(openat), 1, SCMP_A2(SCMP_CMP_MASKED_EQ, flag, flag));
  }
  // Signals to itself only (abort() and raise() signal their own process), also the SIGIO
  // that a descriptor's owner gets (F_SETOWN: a review killed another process with it).
  const auto self = static_cast<scmp_datum_t>(getpid());
  stop(SCMP_SYS(kill), 1, SCMP_A0(SCMP_CMP_NE, self));
  stop(SCMP_SYS(tgkill), 1, SCMP_A0(SCMP_CMP_NE, self));
  stop(SCMP_SYS(rt_sigqueueinfo), 1, SCMP_A0(SCMP_CMP_NE, self));
  stop(SCMP_SYS(rt_tgsigqueueinfo), 1, SCMP_A0(SCMP_CMP_NE, self));
  // (The kernel reads an int argument's low 32 bits: the rules compare those only, or a value
  // with a bit set above them would pass. F_SETFL too: O_ASYNC on the terminal the parent
  // shares made it send the parent SIGIO, and O_NONBLOCK would stay on the parent's output.)
  for (int cmd : {F_SETOWN, F_SETOWN_EX, F_SETSIG, F_SETLEASE, F_SETFL})
    stop(SCMP_SYS(fcntl), 1, SCMP_A1(SCMP_CMP_MASKED_EQ, 0xffffffffu, static_cast<scmp_datum_t>(cmd)));
  // Limits and scheduling of itself only (pid 0), and its own end with the parent kept.
  stop(SCMP_SYS(prlimit64), 1, SCMP_A0(SCMP_CMP_NE, 0));
  // who = 0 is itself for a process only (which = PRIO_PROCESS, IOPRIO_WHO_PROCESS): for a
  // process group or a user it is all of them (a review reniced a sibling process).
  stop(SCMP_SYS(setpriority), 1, SCMP_A0(SCMP_CMP_NE, PRIO_PROCESS));
  stop(SCMP_SYS(setpriority), 1, SCMP_A1(SCMP_CMP_NE, 0));
  stop(SCMP_SYS(ioprio_set), 1, SCMP_A0(SCMP_CMP_NE, kIoprioWhoProcess));
  stop(SCMP_SYS(ioprio_set), 1, SCMP_A1(SCMP_CMP_NE, 0));
  for (int nr :
       {SCMP_SYS(sched_setaffinity), SCMP_SYS(sched_setscheduler), SCMP_SYS(sched_setparam), SCMP_SYS(sched_setattr)})
    stop(nr, 1, SCMP_A0(SCMP_CMP_NE, 0));
  stop(SCMP_SYS(prctl), 1, SCMP_A0(SCMP_CMP_MASKED_EQ, 0xffffffffu, PR_SET_PDEATHSIG));
  // The terminal: typing into its input, its settings, its size (a SIGWINCH to its jobs), and
  // signals or non-blocking output on descriptors shared with the parent.
  for (unsigned long req :
       {TIOCSTI,  TIOCLINUX, TIOCSWINSZ, TCSETS,    TCSETSW,     TCSETSF,  TCSETA, TCSETAW, TCSETAF,  TIOCSCTTY,
        TIOCCONS, TIOCSPGRP, TIOCSETD,   TIOCNOTTY, TIOCVHANGUP, TIOCSBRK, TCFLSH, TCXONC,  FIOASYNC, FIONBIO})
    stop(SCMP_SYS(ioctl), 1, SCMP_A1(SCMP_CMP_MASKED_EQ, 0xffffffffu, req));
  if (rc == 0) rc = seccomp_load(ctx);
  seccomp_release(ctx);
  if (rc != 0) why = fmt::format("the seccomp filter could not be set: {}", std::strerror(-rc));
  return rc == 0;
}

// Root's capabilities (CI runs as root) go first: mounts, modules, raw I/O and the rest that
// the list above may not name all fail then too.
bool drop_capabilities(std::string& why) {
  __user_cap_header_struct head{_LINUX_CAPABILITY_VERSION_3, 0};
  __user_cap_data_struct none[_LINUX_CAPABILITY_U32S_3] = {};
  if (syscall(SYS_capset, &head, none) != 0) {
    why = fmt::format("its capabilities could not be dropped: {}", std::strerror(errno));
    return false;
  }
  prctl(PR_CAP_AMBIENT, PR_CAP_AMBIENT_CLEAR_ALL, 0, 0, 0);
  return true;
}

// Every descriptor of ours but the result's closed (MPI's sockets, files being written).
// close_range came with Linux 5.9; before, one at a time.
void close_other_descriptors() {
  if (close_range(kResultFd + 1, ~0U, 0) == 0) return;
  struct rlimit lim {};
  getrlimit(RLIMIT_NOFILE, &lim);
  const rlim_t hi = lim.rlim_max == RLIM_INFINITY ? (1u << 20) : std::min<rlim_t>(lim.rlim_max, 1u << 20);
  for (rlim_t fd = kResultFd + 1; fd < hi; ++fd) close(static_cast<int>(fd));
}

[[noreturn]] void child(int result_fd, pid_t parent, double seconds, const sigset_t& mask,
                        const std::function<std::string()>& work) {
  // With the parent: a SIGKILL when it ends, and at once if it has ended already.
  prctl(PR_SET_PDEATHSIG, SIGKILL);
  if (getppid() != parent) _exit(1);
  // The parent's handlers would speak for the parent (a run's stop message); the signal that
  // ends it ends the child too. One that the parent ignores (nohup) stays ignored.
  for (int sig : {SIGINT, SIGTERM, SIGHUP, SIGPIPE}) {
    struct sigaction old {};
    sigaction(sig, nullptr, &old);
    if (old.sa_handler != SIG_IGN) signal(sig, SIG_DFL);
  }
  sigprocmask(SIG_SETMASK, &mask, nullptr);  // blocked by the parent around fork: see there
  if (result_fd != kResultFd) dup2(result_fd, kResultFd);
  close_other_descriptors();
  const int null_in = open("/dev/null", O_RDONLY);  // no terminal's input
  if (null_in >= 0 && null_in != STDIN_FILENO) {
    dup2(null_in, STDIN_FILENO);
    close(null_in);
  }
  const struct rlimit no_core {};
  setrlimit(RLIMIT_CORE, &no_core);
  // CPU time as a second bound, should the parent's kill not come: twice the wall limit, as
  // two threads may spend.
  if (seconds < kMostSeconds) {
    const auto cpu = static_cast<rlim_t>(2 * seconds + 10);
    const struct rlimit lim { cpu, cpu };
    setrlimit(RLIMIT_CPU, &lim);
  }
  // Memory: at most the machine's, so that a script's list of 1e10 numbers fails in the child
  // instead of taking the machine (a probe's). Not in a sanitized build, whose shadow memory
  // counts in it.
#ifndef DSPDEM_SANITIZED
  const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGESIZE);
  if (pages > 0 && page > 0) {
    const auto ram = static_cast<rlim_t>(pages) * static_cast<rlim_t>(page);
    const struct rlimit mem { ram, ram };
    setrlimit(RLIMIT_DATA, &mem);
  }
#endif
  // One OpenMP thread: libgomp's pool is not fork-safe, and a team of two in the child
  // waited for the parent's threads, which fork does not copy (a review's reproduction).
  omp_set_num_threads(1);
  struct sigaction act {};
  act.sa_sigaction = on_refused_call;
  act.sa_flags = SA_SIGINFO;
  sigemptyset(&act.sa_mask);
  sigaction(SIGSYS, &act, nullptr);
  sigset_t sys;
  sigemptyset(&sys);
  sigaddset(&sys, SIGSYS);
  sigprocmask(SIG_UNBLOCK, &sys, nullptr);

  std::string out, why;
  char status = kFailed;
  if (!drop_capabilities(why) || !install_filter(why)) {
    out = why;
  } else {
    try {
      out = work();
      status = kDone;
    } catch (const std::exception& e) {
      out = e.what();
    } catch (...) {
      out = "an unknown exception";
    }
  }
  const bool sent = write_all(kResultFd, &status, 1) && write_all(kResultFd, out.data(), out.size());
  _exit(sent ? 0 : 1);
}

std::string how_it_ended(int st) {
  if (WIFSIGNALED(st)) {
    const int sig = WTERMSIG(st);
    return fmt::format("signal {}, {}", sig, strsignal(sig));
  }
  if (WIFEXITED(st)) return fmt::format("exit status {} and no result", WEXITSTATUS(st));
  return "no result";
}

// Kills the child and reaps it (its status is not wanted then: it was stopped).
void stop_child(pid_t pid) {
  kill(pid, SIGKILL);
  while (waitpid(pid, nullptr, 0) < 0 && errno == EINTR) {
  }
}
}  // namespace

SandboxResult run_sandboxed(const std::function<std::string()>& work, double seconds) {
  using Clock = std::chrono::steady_clock;
  seconds = std::clamp(seconds, 0.0, kMostSeconds);  // inf would overflow the clock's ticks
  SandboxResult res;
  int fds[2];
  if (pipe2(fds, O_CLOEXEC) != 0) {
    res.status = SandboxResult::Status::Failed;
    res.message = fmt::format("cannot make a pipe: {}", std::strerror(errno));
    return res;
  }
  const pid_t parent = getpid();
  // Signals blocked across fork until the child has put its own handlers in: a Ctrl-C to the
  // process group in between would run the parent's handler in the child (its stop message
  // printed twice).
  sigset_t all, mask;
  sigfillset(&all);
  pthread_sigmask(SIG_BLOCK, &all, &mask);
  const pid_t pid = fork();
  if (pid != 0) pthread_sigmask(SIG_SETMASK, &mask, nullptr);
  if (pid < 0) {
    close(fds[0]);
    close(fds[1]);
    res.status = SandboxResult::Status::Failed;
    res.message = fmt::format("cannot start a process: {}", std::strerror(errno));
    return res;
  }
  if (pid == 0) {
    if (fds[0] != kResultFd) close(fds[0]);
    child(fds[1], parent, seconds, mask, work);
  }
  close(fds[1]);

  const auto deadline =
      Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(seconds));
  auto ms_left = [&] {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()).count();
    return static_cast<int>(std::clamp<long long>(left, 0, INT_MAX));
  };
  std::string got;
  bool late = false;
  char buf[1 << 16];
  // Should the parent fail here (memory for a result larger than it can hold), the child is
  // not left blocked on a pipe nobody reads.
  try {
    for (;;) {
      const int wait_ms = ms_left();
      if (wait_ms == 0) {
        late = true;
        break;
      }
      pollfd p{fds[0], POLLIN, 0};
      const int r = poll(&p, 1, wait_ms);
      if (r < 0 && errno == EINTR) continue;
      if (r < 0) throw std::system_error(errno, std::generic_category(), "poll");  // not a spin
      if (r == 0) continue;  // the deadline is checked again above
      const ssize_t n = read(fds[0], buf, sizeof buf);
      if (n < 0 && (errno == EINTR || errno == EAGAIN)) continue;
      if (n <= 0) break;  // the end: the child has closed its end, as when it ends
      got.append(buf, static_cast<std::size_t>(n));
    }
  } catch (...) {
    close(fds[0]);
    stop_child(pid);
    throw;
  }
  close(fds[0]);
  int st = 0;
  if (!late) {
    // Its end is closed: it is ending. Still bounded by the deadline, should it go on: the
    // wait is a poll of the process's descriptor (Linux 5.3), else short sleeps.
    const int pidfd = static_cast<int>(syscall(SYS_pidfd_open, pid, 0));
    for (;;) {
      const pid_t w = waitpid(pid, &st, WNOHANG);
      if (w == pid) break;
      if (w < 0 && errno == EINTR) continue;
      if (w < 0) break;
      const int wait_ms = ms_left();
      if (wait_ms == 0) {
        late = true;
        break;
      }
      pollfd p{pidfd, POLLIN, 0};
      if (pidfd >= 0)
        poll(&p, 1, wait_ms);
      else
        poll(nullptr, 0, std::min(wait_ms, 1));
    }
    if (pidfd >= 0) close(pidfd);
  }
  if (late) {
    stop_child(pid);
    res.status = SandboxResult::Status::TimedOut;
    res.message = fmt::format("did not finish within {:g} s and was stopped", seconds);
    return res;
  }
  // (Two threads stopped at once each write their call: the first is named.)
  if (WIFEXITED(st) && WEXITSTATUS(st) == kRefusedExit && got.size() >= 1 + sizeof(int) && got[0] == kRefused) {
    int nr = 0;
    std::memcpy(&nr, got.data() + 1, sizeof nr);
    char* name = seccomp_syscall_resolve_num_arch(SCMP_ARCH_NATIVE, nr);
    res.status = SandboxResult::Status::Refused;
    res.message = name ? name : fmt::format("system call {}", nr);
    std::free(name);
    return res;
  }
  if (WIFEXITED(st) && WEXITSTATUS(st) == 0 && !got.empty() && (got[0] == kDone || got[0] == kFailed)) {
    const bool done = got[0] == kDone;
    res.status = done ? SandboxResult::Status::Done : SandboxResult::Status::Failed;
    got.erase(0, 1);  // in place: the result may be most of the memory
    (done ? res.bytes : res.message) = std::move(got);
    return res;
  }
  // The kernel ends it with SIGSYS itself when the call came with signals blocked (glibc's
  // posix_spawn, system() blocks them all around its clone): which call is not known then.
  if (WIFSIGNALED(st) && WTERMSIG(st) == SIGSYS) {
    res.status = SandboxResult::Status::Refused;
    res.message.clear();
    return res;
  }
  res.status = SandboxResult::Status::Ended;
  res.message = how_it_ended(st);
  return res;
}

}  // namespace dspdem
