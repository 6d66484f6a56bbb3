// core/signals: ScopedSignals holds its handler for a scope and puts the caller's actions back;
// a signal that was ignored stays ignored (nohup's SIGHUP, a background job's SIGINT).
#include <gtest/gtest.h>
#include <signal.h>

#include <csignal>

#include "core/signals.hpp"

namespace {
volatile std::sig_atomic_t g_seen = 0;
extern "C" void count(int) { g_seen = g_seen + 1; }
extern "C" void other(int) {}

void (*handler_of(int sig))(int) {
  struct sigaction now {};
  sigaction(sig, nullptr, &now);
  return now.sa_handler;
}
}  // namespace

TEST(ScopedSignals, HoldsItsHandlerAndPutsTheCallersBack) {
  signal(SIGUSR1, other);
  g_seen = 0;
  {
    dspdem::ScopedSignals s({SIGUSR1, SIGUSR2}, count);
    EXPECT_EQ(handler_of(SIGUSR1), &count);
    raise(SIGUSR1);
    raise(SIGUSR2);
    EXPECT_EQ(g_seen, 2);
    signal(SIGUSR1, SIG_DFL);  // as gmsh's set-up may put in its own
    s.install();
    EXPECT_EQ(handler_of(SIGUSR1), &count);
  }
  EXPECT_EQ(handler_of(SIGUSR1), &other);
  EXPECT_EQ(handler_of(SIGUSR2), SIG_DFL);
  signal(SIGUSR1, SIG_DFL);
}

TEST(ScopedSignals, AnIgnoredSignalStaysIgnored) {
  signal(SIGHUP, SIG_IGN);
  g_seen = 0;
  {
    dspdem::ScopedSignals s({SIGHUP, SIGUSR1}, count);
    EXPECT_EQ(handler_of(SIGHUP), SIG_IGN);
    raise(SIGHUP);  // would end the test program if it were not ignored
    raise(SIGUSR1);
    EXPECT_EQ(g_seen, 1);
    s.install();
    EXPECT_EQ(handler_of(SIGHUP), SIG_IGN);
    s.restore();  // early: a signal from here on goes to the caller's action
    EXPECT_EQ(handler_of(SIGUSR1), SIG_DFL);
  }
  EXPECT_EQ(handler_of(SIGHUP), SIG_IGN);
  signal(SIGHUP, SIG_DFL);
}
