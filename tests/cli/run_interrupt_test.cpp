// Ctrl-C and SIGTERM during `myoshell run --video`: the run stops at the next step, kills and
// reaps ffmpeg, leaves no temporary file and exits 130 / 143 saying what it kept.
#include <gtest/gtest.h>
#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <thread>

#include "myoshell/render/video.h"
#include "support/cli_runner.h"
#include "support/scratch_folder.h"

namespace myo {
namespace {

namespace fs = std::filesystem;

using RunInterrupt = test::ScratchFolderTest;

// Every process whose command line mentions `text` (an ffmpeg left behind would).
int processesMentioning(const std::string& text) {
  int n = 0;
  for (const auto& e : fs::directory_iterator("/proc")) {
    const std::string pid = e.path().filename().string();
    if (pid.find_first_not_of("0123456789") != std::string::npos) continue;
    std::ifstream in(e.path() / "cmdline", std::ios::binary);
    std::string cmd((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (cmd.find(text) != std::string::npos) ++n;
  }
  return n;
}

void interruptTest(const fs::path& dir, const std::string& scenePath, int sig, int expectedExit) {
  const fs::path out = dir / ("out_" + std::to_string(sig));
  const fs::path errPath = dir / ("err_" + std::to_string(sig));
  const std::string cache = (dir / "cache").string();
  const pid_t pid = ::fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    const int fd = ::open(errPath.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    ::dup2(fd, 2);
    ::dup2(fd, 1);
    ::execl(test::cliPath().c_str(), "myoshell", "run", scenePath.c_str(), "--out", out.c_str(), "--video", "--size",
            "64", "--cache", cache.c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  const fs::path first = out / "obj" / "long_0003.obj";
  const auto start = std::chrono::steady_clock::now();
  while (!fs::exists(first) && std::chrono::steady_clock::now() - start < std::chrono::seconds(300))
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  ASSERT_TRUE(fs::exists(first)) << "no frame appeared";
  ::kill(pid, sig);
  int status = 0;
  ASSERT_EQ(::waitpid(pid, &status, 0), pid);
  std::ifstream errIn(errPath);
  const std::string err((std::istreambuf_iterator<char>(errIn)), std::istreambuf_iterator<char>());
  ASSERT_TRUE(WIFEXITED(status)) << err;
  EXPECT_EQ(WEXITSTATUS(status), expectedExit) << err;
  EXPECT_NE(err.find(sig == SIGINT ? "interrupted (SIGINT)" : "interrupted (SIGTERM)"), std::string::npos) << err;
  EXPECT_NE(err.find("kept"), std::string::npos) << err;
  for (const auto& e : fs::recursive_directory_iterator(out))
    EXPECT_EQ(e.path().filename().string().find(".tmp"), std::string::npos) << e.path();
  EXPECT_FALSE(fs::exists(out / "long.mp4"));
  EXPECT_FALSE(fs::exists(out / "stats.json"));
  EXPECT_EQ(processesMentioning(out.string()), 0);  // ffmpeg was killed and reaped
  EXPECT_TRUE(fs::exists(out / ".myoshell-manifest.json"));  // the next run can clean up what was kept
}

TEST_F(RunInterrupt, SigintAndSigtermStopAtTheNextStepAndLeaveNoTemporaryFiles) {
  if (!ffmpegAvailable()) GTEST_SKIP() << "no ffmpeg";
  const std::string path = scene("long.json", "long", 60.0);  // 1201 frames: far longer than the test waits
  interruptTest(dir_, path, SIGINT, 130);
  interruptTest(dir_, path, SIGTERM, 143);
}

}  // namespace
}  // namespace myo
