// scripts/setup's two package sets (docs/install.md): `scripts/setup --list` prints what building and
// running need (make demo), `scripts/setup --test --list` that and what the tests, fuzzers and
// benchmarks need. Listing runs no apt, needs no root and no network: the script runs here with an
// empty environment and a PATH holding only stand-ins for apt-get, dpkg-query, sudo, npm and the
// like, each of which records its call and fails. The Makefile's `demo` and `test` paths are read
// with `make -n`, which runs none of their commands.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "support/test_data.h"

namespace myo {
namespace {

namespace fs = std::filesystem;
using ::testing::Contains;
using ::testing::HasSubstr;
using ::testing::IsEmpty;
using ::testing::Not;

struct ScriptRun {
  int exitCode = -1;
  std::string out;
  std::string err;
};

std::string readScriptFile(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::vector<std::string> linesOf(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

// Packages only the tests, fuzzers, benchmark programs and figure scripts use: none may be in the
// run-time set. slurmctld, slurmd (pulled in by slurm-wlm) and blender are named too, so that
// nobody adds them to what `make demo` installs.
const char* const kTestOnly[] = {
    "slurm-wlm",          "slurmctld",     "slurmd",       "munge",        "clang-14",         "libclang-rt-14-dev",
    "libsuitesparse-dev", "blender",       "libgtest-dev", "libgmock-dev", "libbenchmark-dev", "python3-pytest",
    "parallel",           "libassimp-dev", "xvfb",         "xauth"};

// Of those, what `scripts/setup --test` installs (tests/CMakeLists.txt, bench/, fuzz/, tests/viewer,
// tests/cli/batch_recipes_test.cpp, tests/python).
const char* const kTestInstalls[] = {
    "libgtest-dev",  "libgmock-dev", "libbenchmark-dev", "libassimp-dev", "libsuitesparse-dev", "xvfb",
    "xauth",         "parallel",     "slurm-wlm",        "munge",         "clang-14",           "libclang-rt-14-dev",
    "python3-pytest"};

// What the run-time build finds at configure time (CMakeLists.txt, src/io, src/render, src/gl,
// apps/viewer, python/) and what `myoshell demo` and scripts/fetch_default_head run.
const char* const kRunTimeNeeds[] = {
    "build-essential",    "cmake",        "pkg-config",    "libeigen3-dev",   "libspectra-dev", "libtinyobjloader-dev",
    "nlohmann-json3-dev", "libcli11-dev", "libfmt-dev",    "libyaml-cpp-dev", "libstb-dev",     "libtinygltf-dev",
    "libepoxy-dev",       "libegl-dev",   "libegl-mesa0",  "libgl1-mesa-dri", "libglfw3-dev",   "libimgui-dev",
    "python3-dev",        "pybind11-dev", "python3-numpy", "ffmpeg",          "nodejs",         "npm"};

class SetupScript : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = fs::temp_directory_path() / ("myo_SetupScript_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_ / "bin");
    for (const char* tool : {"apt-get", "apt", "apt-cache", "dpkg", "dpkg-query", "sudo", "su", "id", "npm", "node",
                             "npx", "curl", "wget"}) {
      const fs::path p = dir_ / "bin" / tool;
      std::ofstream(p) << "#!/bin/sh\necho \"" << tool << " $*\" >> '" << (dir_ / "calls.txt").string()
                       << "'\nexit 1\n";
      fs::permissions(p, fs::perms::owner_all, fs::perm_options::add);
    }
  }
  static void TearDownTestSuite() {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  void SetUp() override { fs::remove(dir_ / "calls.txt"); }

  // `bash scripts/setup ARGS` with an empty environment and only the stand-ins on PATH.
  static ScriptRun setup(const std::string& args) {
    const fs::path out = dir_ / "out.txt", err = dir_ / "err.txt";
    const std::string cmd = "env -i PATH='" + (dir_ / "bin").string() + "' /bin/bash '" +
                            (test::sourceDir() / "scripts" / "setup").string() + "' " + args + " > '" + out.string() +
                            "' 2> '" + err.string() + "'";
    const int status = std::system(cmd.c_str());
    ScriptRun r;
    r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    r.out = readScriptFile(out);
    r.err = readScriptFile(err);
    return r;
  }
  // What the stand-ins were asked to do since the test began ("" when nothing called them).
  static std::string calls() { return fs::exists(dir_ / "calls.txt") ? readScriptFile(dir_ / "calls.txt") : ""; }

  // A --list run's packages, checked: exit 0, nothing on stderr, no stand-in called, one Debian
  // package name a line (Debian Policy 5.6.1: lower-case letters, digits, + - and ., at least two
  // characters, starting with a letter or digit), no duplicates.
  static std::vector<std::string> listed(const std::string& args) {
    const ScriptRun r = setup(args);
    EXPECT_EQ(r.exitCode, 0) << "scripts/setup " << args << "\n" << r.out << r.err;
    EXPECT_EQ(r.err, "") << "scripts/setup " << args;
    EXPECT_EQ(calls(), "") << "scripts/setup " << args << " ran these (it must not run apt, sudo or npm)";
    EXPECT_TRUE(r.out.empty() || r.out.back() == '\n') << "the last line is not ended";
    const std::regex name("[a-z0-9][a-z0-9+.-]+");
    const std::vector<std::string> lines = linesOf(r.out);
    std::set<std::string> seen;
    for (const std::string& line : lines) {
      EXPECT_TRUE(std::regex_match(line, name))
          << "not a Debian package name: '" << line << "' (scripts/setup " << args << ")";
      EXPECT_TRUE(seen.insert(line).second) << line << " is listed twice (scripts/setup " << args << ")";
    }
    return lines;
  }

  static inline fs::path dir_;
};

TEST_F(SetupScript, ListPrintsTheRunTimeSetWithoutAptRootOrNetwork) {
  const std::vector<std::string> runTime = listed("--list");
  EXPECT_GE(runTime.size(), 10u);
  for (const char* p : kRunTimeNeeds) EXPECT_THAT(runTime, Contains(p)) << "make demo's build or run needs " << p;
}

TEST_F(SetupScript, RunTimeSetHoldsNoTestOnlyPackage) {
  const std::vector<std::string> runTime = listed("--list");
  for (const char* p : kTestOnly)
    EXPECT_THAT(runTime, Not(Contains(p))) << p << " is only for the tests; `make demo` must not install it";
}

TEST_F(SetupScript, TestListHoldsTheRunTimeSetAndWhatTheTestsNeed) {
  const std::vector<std::string> runTime = listed("--list");
  const std::vector<std::string> full = listed("--test --list");
  for (const std::string& p : runTime) EXPECT_THAT(full, Contains(p)) << "make test builds what make demo builds";
  for (const char* p : kTestInstalls) EXPECT_THAT(full, Contains(p)) << "the tests need " << p;
  EXPECT_GT(full.size(), runTime.size());
  // The flags in either order.
  EXPECT_EQ(listed("--list --test"), full);
}

TEST_F(SetupScript, AnUnknownOptionFailsWithTheUsageAndInstallsNothing) {
  const ScriptRun r = setup("--tests");
  EXPECT_EQ(r.exitCode, 2) << r.out << r.err;
  EXPECT_THAT(r.err, HasSubstr("unknown option '--tests'"));
  EXPECT_THAT(r.err, HasSubstr("usage: scripts/setup [--test] [--web] [--list]"));
  EXPECT_EQ(r.out, "");
  EXPECT_EQ(calls(), "");
  const ScriptRun help = setup("--help");
  EXPECT_EQ(help.exitCode, 0) << help.out << help.err;
  EXPECT_THAT(help.out, HasSubstr("--list"));
  EXPECT_EQ(calls(), "");
}

// `make -n TARGET` in the source folder: the commands make would run, none of them run.
ScriptRun makeDryRun(const std::string& target) {
  const fs::path out = fs::temp_directory_path() / ("myo_SetupScript_make_" + std::to_string(::getpid()) + ".txt");
  const std::string cmd = "make -n -C '" + test::sourceDir().string() + "' BUILD_DIR=/nonexistent/build " + target +
                          " > '" + out.string() + "' 2>&1";
  const int status = std::system(cmd.c_str());
  ScriptRun r;
  r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = readScriptFile(out);
  fs::remove(out);
  return r;
}

TEST(SetupMakefile, DemoSetsUpTheRunTimeSetAndBuildsWithoutTests) {
  if (std::system("command -v make > /dev/null 2>&1") != 0) GTEST_SKIP() << "make is not installed";
  const ScriptRun demo = makeDryRun("demo");
  ASSERT_EQ(demo.exitCode, 0) << demo.out;
  EXPECT_THAT(demo.out, HasSubstr("bash scripts/setup\n"));
  EXPECT_THAT(demo.out, Not(HasSubstr("--test"))) << demo.out;
  EXPECT_THAT(demo.out, HasSubstr("-DMYO_BUILD_TESTS=OFF"));
  EXPECT_THAT(demo.out, HasSubstr("-DMYO_BUILD_BENCH=OFF"));
}

TEST(SetupMakefile, TestPathsSetUpWithTest) {
  if (std::system("command -v make > /dev/null 2>&1") != 0) GTEST_SKIP() << "make is not installed";
  const ScriptRun testRun = makeDryRun("test");
  ASSERT_EQ(testRun.exitCode, 0) << testRun.out;
  EXPECT_THAT(testRun.out, HasSubstr("bash scripts/setup --test\n"));
  EXPECT_THAT(testRun.out, HasSubstr("-DMYO_BUILD_TESTS=ON"));
  for (const char* target : {"test-asan", "test-asan-ci", "fuzz-replay", "fuzz", "bench"}) {
    const ScriptRun r = makeDryRun(target);
    ASSERT_EQ(r.exitCode, 0) << target << "\n" << r.out;
    EXPECT_THAT(r.out, HasSubstr("bash scripts/setup --test\n")) << "make " << target;
  }
}

}  // namespace
}  // namespace myo
