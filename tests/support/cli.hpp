// Running the dspdem executable from tests: exit code and combined output.
#pragma once
#include <sys/wait.h>

#include <cstdio>
#include <string>

namespace dspdem::testsupport {

struct CliResult {
  int code;
  std::string out;
};

/// Runs `cmd` through the shell with stderr folded into stdout.
inline CliResult shell(const std::string& cmd) {
  std::string out;
  FILE* p = popen((cmd + " 2>&1").c_str(), "r");
  char buf[4096];
  while (std::size_t n = fread(buf, 1, sizeof buf, p)) out.append(buf, n);
  const int st = pclose(p);
  return {WIFEXITED(st) ? WEXITSTATUS(st) : -1, out};
}

}  // namespace dspdem::testsupport
