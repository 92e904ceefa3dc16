// `myoshell live` with `myoshell send` on loopback (docs/live.md): a take sent in lockstep is
// received and recorded value for value, the recording reads as a Live Link take `drive` plays, and
// a port in use is exit 2.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <fstream>
#include <nlohmann/json.hpp>
#include <thread>

#include "myoshell/core/errors.h"
#include "myoshell/io/live_source.h"
#include "myoshell/io/performance_file.h"
#include "support/cli_runner.h"
#include "support/scratch_folder.h"

namespace myo {
namespace {

const std::string kTake = std::string(MYO_SOURCE_DIR) + "/tests/anim/performances/livelink_take.csv";

// A port free a moment ago (the kernel's ephemeral choice), for a child process to listen on.
int freePort(LiveProtocol protocol) {
  LiveSource probe({protocol, "127.0.0.1", 0});
  return probe.port();
}

class LiveCli : public test::ScratchFolderTest {};

TEST_F(LiveCli, LockstepTakeIsRecordedValueForValueAndDriveReplaysIt) {
  // Live Link only (it carries the eyes too); VMC's lockstep values: SendCli and LiveSource tests.
  for (const std::string input : {"livelink"}) {
    const int port = freePort(liveProtocolFromString(input));
    const std::string out = (dir_ / input).string();
    test::CliResult live;
    std::thread receiver([&] {
      live = test::runCli("live --input " + input + " --port " + std::to_string(port) +
                          " --duration 0.2 --fps 30 --format pc2 --lockstep --json --out '" + out + "'");
    });
    const test::CliResult sent =
        test::runCli("send '" + kTake + "' --to " + input + " 127.0.0.1:" + std::to_string(port) + " --lockstep");
    receiver.join();
    ASSERT_EQ(sent.exitCode, 0) << sent.merged;
    ASSERT_EQ(live.exitCode, 0) << live.merged;
    const nlohmann::json j = nlohmann::json::parse(live.out);
    EXPECT_EQ(j["input"], input);
    EXPECT_EQ(j["port"], port);
    EXPECT_GE(j["packets"].get<int>(), 3);
    EXPECT_EQ(j["malformed"], 0);
    EXPECT_EQ(j["dropped"], 0);
    EXPECT_EQ(j["frames"], 7);  // 0.2 s at 30 fps
    EXPECT_EQ(j["recorded_frames"], 3);
    EXPECT_EQ(j["latency_ms"]["samples"], 3);
    EXPECT_GE(j["latency_ms"]["p99"].get<double>(), j["latency_ms"]["median"].get<double>());
    EXPECT_TRUE(std::filesystem::exists(out + "/live.pc2"));

    // The recording: the values sent (float32 on the wire), in a file the Live Link reader takes.
    const Performance sentTake = readPerformanceFile(kTake);
    const Performance recorded = readPerformanceFile(out + "/live.csv", {PerformanceInput::LiveLink, {}, -1, 0.7, 60.0});
    ASSERT_EQ(recorded.times.size(), 3u);
    for (const PerformanceChannel& c : sentTake.channels) {
      const PerformanceChannel* r = recorded.find(c.name);
      ASSERT_NE(r, nullptr) << c.name;
      for (size_t i = 0; i < 3; ++i) EXPECT_EQ(static_cast<float>(r->values[i]), static_cast<float>(c.values[i])) << c.name;
    }
    ASSERT_EQ(recorded.headPose.size(), 3u);
    EXPECT_NEAR((recorded.headPose[1] - sentTake.headPose[1]).norm(), 0.0, 1e-4);
    EXPECT_EQ(recorded.gaze.empty(), input == "vmc");  // VMC carries no eye angles

    const test::CliResult drive = test::runCli("drive '" + out + "/live.csv' --input-fps 60 --format pc2 --out '" +
                                               (dir_ / (input + "_drive")).string() + "'");
    EXPECT_EQ(drive.exitCode, 0) << drive.merged;
  }
}

TEST_F(LiveCli, PortInUseIsExit2) {
  LiveSource holder({LiveProtocol::Vmc, "127.0.0.1", 0});
  const test::CliResult r = test::runCli("live --input vmc --port " + std::to_string(holder.port()) +
                                         " --duration 0.1 --out '" + (dir_ / "out").string() + "'");
  EXPECT_EQ(r.exitCode, 2) << r.merged;
  EXPECT_NE(r.err.find("port " + std::to_string(holder.port()) +
                       " on 127.0.0.1 is in use (another receiver is listening; choose another port)"),
            std::string::npos)
      << r.err;
}

// Ctrl-C keeps what was recorded: the frames received so far stay in live.csv, and live exits 130.
TEST_F(LiveCli, CtrlCKeepsTheRecording) {
  const int port = freePort(LiveProtocol::LiveLink);
  const std::filesystem::path out = dir_ / "out", err = dir_ / "err";
  const pid_t pid = ::fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    const int fd = ::open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    ::dup2(fd, 2);
    ::dup2(fd, 1);
    const std::string portText = std::to_string(port);
    ::execl(test::cliPath().c_str(), "myoshell", "live", "--input", "livelink", "--port", portText.c_str(),
            "--duration", "60", "--format", "obj", "--lockstep", "--out", out.c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  // Lockstep: when send returns, live has taken (and recorded) all three frames.
  const test::CliResult sent =
      test::runCli("send '" + kTake + "' --to livelink 127.0.0.1:" + std::to_string(port) + " --lockstep");
  EXPECT_EQ(sent.exitCode, 0) << sent.merged;
  ::kill(pid, SIGINT);
  int status = 0;
  ASSERT_EQ(::waitpid(pid, &status, 0), pid);
  std::ifstream errIn(err);
  const std::string printed((std::istreambuf_iterator<char>(errIn)), std::istreambuf_iterator<char>());
  ASSERT_TRUE(WIFEXITED(status)) << printed;
  EXPECT_EQ(WEXITSTATUS(status), 130) << printed;
  EXPECT_NE(printed.find("interrupted (SIGINT)"), std::string::npos) << printed;
  const Performance kept = readPerformanceFile((out / "live.csv").string(), {PerformanceInput::LiveLink, {}, -1, 0.7, 60.0});
  EXPECT_EQ(kept.times.size(), 3u);
}

}  // namespace
}  // namespace myo
