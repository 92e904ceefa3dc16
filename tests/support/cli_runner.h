// Running the `myoshell` CLI from tests: exit code and everything it printed.
#pragma once

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <string>

#include "support/test_data.h"

namespace myo::test {

struct CliResult {
  int exitCode = -1;
  std::string out;  // stdout, and stderr unless the caller redirected it
};

// Runs `myoshell ARGS` through the shell (ARGS is shell syntax: quote paths with spaces) with stderr
// merged into stdout unless mergeStderr is false.
inline CliResult runCli(const std::string& args, bool mergeStderr = true) {
  CliResult r;
  const std::string cmd = "'" + cliPath() + "' " + args + (mergeStderr ? " 2>&1" : "");
  FILE* pipe = ::popen(cmd.c_str(), "r");
  if (!pipe) return r;
  std::array<char, 4096> buf;
  size_t n;
  while ((n = std::fread(buf.data(), 1, buf.size(), pipe)) > 0) r.out.append(buf.data(), n);
  const int status = ::pclose(pipe);
  r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

}  // namespace myo::test
