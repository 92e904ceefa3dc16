// `myoshell live` with `myoshell send` on loopback (docs/live.md): a take sent in lockstep is
// received and recorded value for value, and its replay (drive --interpolation step, run replay.json)
// makes live's frames; a loss of 10 % is bounded; a port in use is exit 2; Ctrl-C keeps the take.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <numeric>
#include <random>
#include <nlohmann/json.hpp>
#include <thread>

#include "myoshell/core/errors.h"
#include "myoshell/fit/arkit_names.h"
#include "myoshell/io/animation_export.h"
#include "myoshell/io/live_source.h"
#include "myoshell/io/live_take.h"
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

// The largest distance between two animations' vertices over all frames, cm.
double largestDistance(const PointCache& a, const PointCache& b) {
  EXPECT_EQ(a.samples.size(), b.samples.size());
  double largest = 0.0;
  for (size_t f = 0; f < std::min(a.samples.size(), b.samples.size()); ++f)
    largest = std::max(largest, (a.samples[f] - b.samples[f]).rowwise().norm().maxCoeff());
  return largest;
}

TEST_F(LiveCli, LockstepTakeIsRecordedValueForValueAndItsReplayPlaysTheSameFrames) {
  // Live Link (it carries the eyes too); VMC's lockstep values: SendCli and LiveSource tests.
  const int port = freePort(LiveProtocol::LiveLink);
  const std::filesystem::path out = dir_ / "live";
  test::CliResult live;
  std::thread receiver([&] {
    live = test::runCli("live --input livelink --port " + std::to_string(port) +
                        " --duration 1 --fps 30 --timeout 2 --format pc2 --lockstep --json --out '" + out.string() + "'");
  });
  const test::CliResult sent =
      test::runCli("send '" + kTake + "' --to livelink 127.0.0.1:" + std::to_string(port) + " --lockstep");
  receiver.join();
  ASSERT_EQ(sent.exitCode, 0) << sent.merged;
  ASSERT_EQ(live.exitCode, 0) << live.merged;
  const nlohmann::json j = nlohmann::json::parse(live.out);
  EXPECT_EQ(j["input"], "livelink");
  EXPECT_EQ(j["port"], port);
  EXPECT_GE(j["packets"].get<int>(), 3);
  EXPECT_EQ(j["malformed"], 0);
  EXPECT_EQ(j["dropped"], 0);
  EXPECT_EQ(j["frames"], 31);  // 1 s at 30 fps
  EXPECT_EQ(j["recorded_frames"], 31);  // what frames 1…30 played, and the closing row at 1 s
  EXPECT_EQ(j["latency_ms"]["samples"], 3);
  EXPECT_GE(j["latency_ms"]["p99"].get<double>(), j["latency_ms"]["median"].get<double>());
  EXPECT_EQ(j["replay"], (out / "replay.json").string());

  // The recording: neutral until the first frame came, then the values sent (float32 on the wire)
  // one frame each, then the last held (the timeout, 2 s, is longer than the take).
  const Performance sentTake = readPerformanceFile(kTake);
  const Performance recorded = readPerformanceFile((out / "live.csv").string(), {PerformanceInput::LiveLink, {}, -1, 0.7, 30.0});
  ASSERT_EQ(recorded.times.size(), 31u);
  EXPECT_NEAR(recorded.times.back() - recorded.times.front(), 1.0, 1e-6);
  const PerformanceChannel* jaw = recorded.find("jawOpen");
  ASSERT_NE(jaw, nullptr);
  size_t first = 0;
  while (first < 28 && jaw->values[first] == 0.0) ++first;
  ASSERT_LT(first, 28u) << "no frame sent was played";
  for (const PerformanceChannel& c : sentTake.channels) {
    const PerformanceChannel* r = recorded.find(c.name);
    ASSERT_NE(r, nullptr) << c.name;
    for (size_t i = 0; i < first; ++i) EXPECT_EQ(r->values[i], 0.0) << c.name;
    for (size_t i = 0; i < 3; ++i) EXPECT_EQ(static_cast<float>(r->values[first + i]), static_cast<float>(c.values[i])) << c.name;
    for (size_t i = first + 3; i < 31; ++i) EXPECT_EQ(r->values[i], r->values[first + 2]) << c.name;
  }
  ASSERT_EQ(recorded.headPose.size(), 31u);
  EXPECT_NEAR((recorded.headPose[first + 1] - sentTake.headPose[1]).norm(), 0.0, 1e-4);
  EXPECT_FALSE(recorded.gaze.empty());

  // Replayed, each frame held until the next as live played it, the face makes live's frames:
  // by drive with the same settings and by run of the replay scene live wrote.
  const PointCache played = readPc2(out / "live.pc2");
  ASSERT_EQ(played.samples.size(), 31u);
  const std::string replay = "'" + (out / "live.csv").string() + "' --input-fps 30 --response follow --format pc2";
  const test::CliResult step = test::runCli("drive " + replay + " --interpolation step --out '" + (dir_ / "step").string() + "'");
  ASSERT_EQ(step.exitCode, 0) << step.merged;
  const double byDrive = largestDistance(played, readPc2(dir_ / "step" / "live.pc2"));
  RecordProperty("drive_step_cm", std::to_string(byDrive));
  EXPECT_LE(byDrive, 1e-6);
  const test::CliResult run = test::runCli("run '" + (out / "replay.json").string() + "' --format pc2 --out '" + (dir_ / "run").string() + "'");
  ASSERT_EQ(run.exitCode, 0) << run.merged;
  const double byRun = largestDistance(played, readPc2(dir_ / "run" / "live_replay.pc2"));
  RecordProperty("run_replay_cm", std::to_string(byRun));
  EXPECT_LE(byRun, 1e-6);
  // Linear between the frames is another animation: the comparison can tell.
  const test::CliResult linear = test::runCli("drive " + replay + " --out '" + (dir_ / "linear").string() + "'");
  ASSERT_EQ(linear.exitCode, 0) << linear.merged;
  const double byLinear = largestDistance(played, readPc2(dir_ / "linear" / "live.pc2"));
  RecordProperty("drive_linear_cm", std::to_string(byLinear));
  EXPECT_GT(byLinear, 1e-4);
}

// A lost packet holds the last frame until the next arrives (LiveSource keeps the newest; the face
// plays it each step). Live plays what its recording replays (above), so a loss is measured by
// replaying a take with 10 % of its frames lost, held, against the lossless take: the largest
// deviation is bounded by how far the skin moves over the longest run of held frames.
TEST_F(LiveCli, TenPercentLossDeviatesByAtMostTheSkinsMotionOverTheLongestGap) {
  const double fps = 30.0;
  const int frames = 61;  // 2 s
  const auto& names = arkitNames();
  auto index = [&](const std::string& n) { return std::find(names.begin(), names.end(), n) - names.begin(); };
  std::vector<LiveFrame> take(frames);
  for (int f = 0; f < frames; ++f) {
    const double t = f / fps;
    LiveFrame& k = take[static_cast<size_t>(f)];
    k.weights[index("jawOpen")] = 0.3 * (1.0 - std::cos(2.0 * M_PI * 0.7 * t));
    k.weights[index("mouthSmileLeft")] = k.weights[index("mouthSmileRight")] = 0.5 * (1.0 - std::cos(2.0 * M_PI * 1.1 * t));
    k.weights[index("browInnerUp")] = 0.4 * (1.0 + std::sin(2.0 * M_PI * 0.9 * t));
    k.headPose = Vec3(6.0 * std::sin(2.0 * M_PI * 0.5 * t), 10.0 * std::sin(2.0 * M_PI * 0.3 * t), 0.0);
  }
  // 10 % of the frames after the first lost at random (a fixed seed), each replaced by the last one held.
  std::mt19937 random(43);
  std::vector<bool> lost(frames, false);
  std::vector<int> order(frames - 1);
  std::iota(order.begin(), order.end(), 1);
  std::shuffle(order.begin(), order.end(), random);
  for (int k = 0; k < frames / 10; ++k) lost[static_cast<size_t>(order[static_cast<size_t>(k)])] = true;
  int longestGap = 0, gap = 0;
  {
    LiveTakeRecorder lossless((dir_ / "lossless.csv").string(), true, fps), lossy((dir_ / "lossy.csv").string(), true, fps);
    LiveFrame held;
    for (int f = 0; f < frames; ++f) {
      lossless.write(f / fps, take[static_cast<size_t>(f)]);
      if (!lost[static_cast<size_t>(f)]) held = take[static_cast<size_t>(f)];
      lossy.write(f / fps, held);
      gap = lost[static_cast<size_t>(f)] ? gap + 1 : 0;
      longestGap = std::max(longestGap, gap);
    }
  }
  ASSERT_GE(longestGap, 1);
  for (const std::string name : {"lossless", "lossy"}) {
    const test::CliResult r = test::runCli("drive '" + (dir_ / (name + ".csv")).string() +
                                           "' --input-fps 30 --interpolation step --format pc2 --out '" + (dir_ / name).string() + "'");
    ASSERT_EQ(r.exitCode, 0) << r.merged;
  }
  const PointCache clean = readPc2(dir_ / "lossless" / "lossless.pc2"), lossy = readPc2(dir_ / "lossy" / "lossy.pc2");
  const double deviation = largestDistance(clean, lossy);
  // The skin's largest motion over the longest gap (plus the frame the next value takes to act).
  double motion = 0.0;
  for (size_t f = static_cast<size_t>(longestGap) + 1; f < clean.samples.size(); ++f)
    motion = std::max(motion, (clean.samples[f] - clean.samples[f - static_cast<size_t>(longestGap) - 1]).rowwise().norm().maxCoeff());
  RecordProperty("held_frames", frames / 10);
  RecordProperty("longest_gap", longestGap);
  RecordProperty("deviation_cm", std::to_string(deviation));
  RecordProperty("motion_over_gap_cm", std::to_string(motion));
  EXPECT_GT(deviation, 1e-4);  // the loss shows
  EXPECT_LE(deviation, motion) << "held " << frames / 10 << " frames, longest gap " << longestGap;
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
            "--duration", "60", "--format", "glb", "--lockstep", "--out", out.c_str(), static_cast<char*>(nullptr));
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
  // Every frame played is kept (the three sent among them), the animation of the frames made, and
  // the scene that replays them.
  const Performance kept = readPerformanceFile((out / "live.csv").string(), {PerformanceInput::LiveLink, {}, -1, 0.7, 60.0});
  EXPECT_GE(kept.times.size(), 3u);
  EXPECT_TRUE(std::filesystem::exists(out / "live.glb")) << printed;
  EXPECT_TRUE(std::filesystem::exists(out / "replay.json")) << printed;
}

}  // namespace
}  // namespace myo
