// Running the `myoshell` CLI from tests: its exit code, and what it printed on stdout and stderr.
#pragma once

#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "support/test_data.h"

namespace myo::test {

struct CliResult {
  int exitCode = -1;
  std::string out;     // stdout
  std::string err;     // stderr
  std::string merged;  // stdout followed by stderr
};

// Runs `PROGRAM ARGS` through the shell (ARGS is shell syntax: quote paths with spaces), in
// `workDir` when given, after `prefix` (shell syntax too, e.g. "env -u HOME MYOSHELL_CACHE=/c").
inline CliResult runProgram(const std::string& program, const std::string& args,
                            const std::filesystem::path& workDir = {}, const std::string& prefix = {}) {
  namespace fs = std::filesystem;
  static std::atomic<int> counter{0};
  const fs::path base = fs::temp_directory_path() /
                        ("myo_cli_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
  const fs::path outFile = base.string() + ".out", errFile = base.string() + ".err";
  std::string cmd = prefix + " '" + program + "' " + args + " >'" + outFile.string() + "' 2>'" + errFile.string() + "'";
  if (!workDir.empty()) cmd = "cd '" + workDir.string() + "' && " + cmd;
  const int status = std::system(cmd.c_str());
  auto slurp = [](const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream ss;
    ss << in.rdbuf();
    return ss.str();
  };
  CliResult r;
  r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = slurp(outFile);
  r.err = slurp(errFile);
  r.merged = r.out + r.err;
  fs::remove(outFile);
  fs::remove(errFile);
  return r;
}

// Runs `myoshell ARGS` (runProgram).
inline CliResult runCli(const std::string& args, const std::filesystem::path& workDir = {},
                        const std::string& prefix = {}) {
  return runProgram(cliPath(), args, workDir, prefix);
}

}  // namespace myo::test
