#pragma once
// Runs a shell command (a test's view of a program as a user runs it) and returns its standard output and
// exit code. Callers add the redirections they need (e.g. "2>&1", "2>FILE", "</dev/null").
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <string>

namespace reamsim::test {

struct CommandOutput {
  int exitCode = -1;  // -1: could not start, or ended by a signal
  std::string out;
};

inline CommandOutput runCommand(const std::string& shellCommand) {
  CommandOutput r;
  FILE* pipe = popen(shellCommand.c_str(), "r");
  if (!pipe) return r;
  std::array<char, 4096> buf{};
  while (std::size_t n = fread(buf.data(), 1, buf.size(), pipe)) r.out.append(buf.data(), n);
  const int status = pclose(pipe);
  r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

}  // namespace reamsim::test
