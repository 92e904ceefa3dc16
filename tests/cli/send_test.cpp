// `myoshell send` (docs/live.md): a recorded take replayed as packets to a live source listening on
// loopback (an ephemeral port), in lockstep, arrives value for value; OpenFace is refused.
#include <gtest/gtest.h>

#include <thread>

#include "myoshell/fit/arkit_names.h"
#include "myoshell/io/live_source.h"
#include "myoshell/io/performance_file.h"
#include "support/cli_runner.h"

namespace myo {
namespace {

const std::string kPerformances = std::string(MYO_SOURCE_DIR) + "/tests/anim/performances/";

TEST(SendCli, LockstepTakeArrivesValueForValue) {
  for (const std::string file : {"livelink_take.csv", "mediapipe_take.jsonl"}) {
    for (const std::string to : {"livelink", "vmc"}) {
      LiveSourceOptions options{liveProtocolFromString(to), "127.0.0.1", 0};
      options.acknowledge = true;
      LiveSource source(options);
      const Performance p = readPerformanceFile(kPerformances + file);
      std::vector<LiveSample> received;
      std::thread consumer([&] {
        while (received.size() < p.times.size() && source.waitForFrame(10.0)) received.push_back(*source.takeNewest());
      });
      const test::CliResult r = test::runCli("send '" + kPerformances + file + "' --to " + to + " 127.0.0.1:" +
                                             std::to_string(source.port()) + " --lockstep --json");
      consumer.join();
      ASSERT_EQ(r.exitCode, 0) << r.merged;
      EXPECT_NE(r.out.find("\"packets\": " + std::to_string(p.times.size())), std::string::npos) << r.out;
      ASSERT_EQ(received.size(), p.times.size()) << file << " " << to;
      const auto& names = arkitNames();
      for (const PerformanceChannel& c : p.channels) {
        const size_t k = static_cast<size_t>(std::find(names.begin(), names.end(), c.name) - names.begin());
        for (size_t i = 0; i < p.times.size(); ++i)
          EXPECT_EQ(received[i].frame.weights[k], static_cast<float>(c.values[i])) << file << " " << c.name << " " << i;
      }
      EXPECT_EQ(source.counters().superseded, 0);
    }
  }
}

TEST(SendCli, OpenFaceActionUnitsAreRefusedWithTheReason) {
  const std::string openface = std::string(MYO_SHARED_DIR) + "/data/openface/facsvatar_demo.csv";
  if (!std::filesystem::exists(openface)) GTEST_SKIP() << "no OpenFace take at " << openface;
  const test::CliResult refused = test::runCli("send '" + openface + "' --to livelink 127.0.0.1:9");
  EXPECT_EQ(refused.exitCode, 2) << refused.merged;
  EXPECT_NE(refused.err.find("OpenFace action units cannot be sent: VMC and Live Link Face carry ARKit blendshape "
                             "weights, not FACS action units"),
            std::string::npos)
      << refused.err;
}

TEST(SendCli, BadDestinationsAreInputErrors) {
  const std::string take = "'" + kPerformances + "livelink_take.csv'";
  const test::CliResult port = test::runCli("send " + take + " --to vmc 127.0.0.1:70000");
  EXPECT_EQ(port.exitCode, 2);
  EXPECT_NE(port.err.find("'127.0.0.1:70000': expected HOST:PORT with a port in 1–65535"), std::string::npos) << port.err;
  const test::CliResult protocol = test::runCli("send " + take + " --to osc");
  EXPECT_EQ(protocol.exitCode, 2);
  EXPECT_NE(protocol.err.find("unknown live input 'osc' (use vmc or livelink)"), std::string::npos) << protocol.err;
}

}  // namespace
}  // namespace myo
