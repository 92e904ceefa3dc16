// The live source (io/live_source.h) over loopback on ephemeral ports (parallel runs never share
// one), and the face input's hold, ease and calibration on an injected clock (no test sleeps).
#include "myoshell/io/live_source.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <random>
#include <thread>

#include "myoshell/core/errors.h"
#include "myoshell/fit/arkit_names.h"
#include "myoshell/io/performance_file.h"

namespace myo {
namespace {

const std::string kTake = std::string(MYO_SOURCE_DIR) + "/tests/anim/performances/livelink_take.csv";

// A 5 s take at 60 fps: every weight and the head on its own slow sine (a tracker's smooth curves).
std::vector<LiveFrame> syntheticTake() {
  std::vector<LiveFrame> frames(300);
  for (size_t i = 0; i < frames.size(); ++i) {
    const double t = i / 60.0;
    for (int k = 0; k < kArkitWeightCount; ++k) frames[i].weights[k] = 0.5 + 0.5 * std::sin(2.0 * t + 0.3 * k);
    frames[i].headPose = Vec3(10 * std::sin(t), 20 * std::sin(0.7 * t), -5 * std::cos(1.3 * t));
  }
  return frames;
}

// The take's frames as the sender sends them (weights in ARKit order, head pose, gaze).
std::vector<LiveFrame> takeFrames() {
  const Performance p = readPerformanceFile(kTake);
  std::vector<LiveFrame> frames(p.times.size());
  const auto& names = arkitNames();
  for (const PerformanceChannel& c : p.channels) {
    const int k = static_cast<int>(std::find(names.begin(), names.end(), c.name) - names.begin());
    for (size_t i = 0; i < frames.size(); ++i) frames[i].weights[k] = c.values[i];
  }
  for (size_t i = 0; i < frames.size(); ++i) {
    if (!p.headPose.empty()) frames[i].headPose = p.headPose[i];
    if (!p.gaze.empty()) frames[i].gaze = p.gaze[i];
  }
  return frames;
}

std::vector<std::uint8_t> packetOf(LiveProtocol protocol, const LiveFrame& f, int i) {
  return protocol == LiveProtocol::Vmc ? encodeVmcPacket(f) : encodeLiveLinkPacket(f, {i, 0.0f, 60, 1});
}

TEST(LiveSource, PortInUseIsAClearInputError) {
  LiveSource first({LiveProtocol::Vmc, "127.0.0.1", 0});
  const int port = first.port();
  ASSERT_GT(port, 0);
  try {
    LiveSource second({LiveProtocol::Vmc, "127.0.0.1", port});
    FAIL() << "the second bind succeeded";
  } catch (const InputError& e) {
    EXPECT_EQ(e.message(), "port " + std::to_string(port) +
                               " on 127.0.0.1 is in use (another receiver is listening; choose another port)");
  }
  EXPECT_THROW(LiveSource({LiveProtocol::Vmc, "not-an-address", 0}), InputError);
}

TEST(LiveSource, LockstepLoopbackReceivesExactlyTheValuesSent) {
  std::vector<LiveFrame> frames = takeFrames();  // the recorded take (3 frames), then a longer one
  for (const LiveFrame& f : syntheticTake()) frames.push_back(f);
  for (const LiveProtocol protocol : {LiveProtocol::LiveLink, LiveProtocol::Vmc}) {
    LiveSourceOptions options{protocol, "127.0.0.1", 0};
    options.acknowledge = true;
    LiveSource source(options);
    bool acknowledged = true;
    std::thread sender([&] {
      LiveSender to("127.0.0.1", source.port());
      for (size_t i = 0; i < frames.size() && acknowledged; ++i) {
        to.send(packetOf(protocol, frames[i], static_cast<int>(i)));
        acknowledged = to.waitForAcknowledgement(5.0);
      }
    });
    std::vector<LiveSample> received;
    while (received.size() < frames.size() && source.waitForFrame(5.0)) received.push_back(*source.takeNewest());
    sender.join();
    ASSERT_TRUE(acknowledged);
    ASSERT_EQ(received.size(), frames.size());
    for (size_t i = 0; i < frames.size(); ++i) {
      EXPECT_EQ(received[i].sequence, static_cast<long>(i + 1));
      for (int k = 0; k < kArkitWeightCount; ++k)
        ASSERT_EQ(received[i].frame.weights[k], static_cast<float>(frames[i].weights[k])) << i << " " << k;
      ASSERT_TRUE(received[i].frame.headPose);
      EXPECT_NEAR((*received[i].frame.headPose - *frames[i].headPose).norm(), 0.0, 1e-4);
    }
    const LiveCounters c = source.counters();
    EXPECT_EQ(c.superseded, 0);
    EXPECT_EQ(c.malformed, 0);
    EXPECT_EQ(c.dropped, 0);
    EXPECT_EQ(c.taken, static_cast<long>(frames.size()));
  }
}

TEST(LiveSource, FloodIsSupersededAndEachStepTakesOneFrame) {
  LiveSource source({LiveProtocol::LiveLink, "127.0.0.1", 0});
  LiveSender to("127.0.0.1", source.port());
  LiveFrame f;
  long steps = 0, taken = 0, lastSequence = 0;
  for (int i = 0; i < 10000; ++i) {
    f.weights[0] = (i % 100) / 100.0;
    to.send(encodeLiveLinkPacket(f, {i, 0.0f, 60, 1}));
    if (i % 100 == 99) {  // a step of the frame loop: the newest frame, once
      ++steps;
      if (const auto s = source.takeNewest()) {
        ++taken;
        EXPECT_GT(s->sequence, lastSequence);  // never an older frame
        lastSequence = s->sequence;
      }
    }
  }
  source.waitForPackets(10000, 2.0);  // the kernel may drop some under a flood; not waiting forever
  const LiveCounters c = source.counters();
  EXPECT_EQ(c.taken, taken);  // one frame per step that found one, never more
  EXPECT_LE(taken, steps);
  EXPECT_GT(taken, 0);
  EXPECT_EQ(c.frames, c.packets);
  EXPECT_EQ(c.malformed, 0);
  // Every complete frame was either taken, replaced by a newer one, or is the one still waiting.
  const long waiting = source.takeNewest() ? 1 : 0;
  EXPECT_EQ(c.frames, c.taken + c.superseded + waiting);
  EXPECT_GE(c.superseded, c.packets - steps - 1);  // all but one per step was superseded
  // Packets the kernel dropped show as gaps in the sender's frame numbers (the ends excepted).
  EXPECT_LE(c.dropped, 10000 - c.packets);
}

TEST(LiveSource, MalformedPacketsAreCountedAndTheStreamGoesOn) {
  LiveSource source({LiveProtocol::LiveLink, "127.0.0.1", 0});
  LiveSender to("127.0.0.1", source.port());
  LiveFrame f;
  f.weights[3] = 0.5;
  auto good = encodeLiveLinkPacket(f, {1, 0.0f, 60, 1});
  to.send({6, 0, 0});
  to.send(std::vector<std::uint8_t>(good.begin(), good.end() - 4));
  to.send(encodeLiveLinkPacket(f, {4, 0.0f, 60, 1}));  // frames 2 and 3 never sent: lost on the way
  to.send(encodeLiveLinkPacket(f, {1, 0.0f, 60, 1}));  // an older frame number: not a gap
  ASSERT_TRUE(source.waitForPackets(4, 5.0));
  const LiveCounters c = source.counters();
  EXPECT_EQ(c.packets, 4);
  EXPECT_EQ(c.malformed, 2);
  EXPECT_EQ(c.frames, 2);
  EXPECT_EQ(c.superseded, 1);
  EXPECT_EQ(source.lastMalformed(), "240 bytes for 61 float32 values (expected 244)");
  EXPECT_EQ(source.takeNewest()->frame.weights[3], 0.5);
}

// liblo's own command-line sender (Debian's liblo-tools), not ours.
TEST(LiveSource, ReadsWhatOscsendSends) {
  if (std::system("command -v oscsend > /dev/null 2>&1") != 0)
    GTEST_SKIP() << "oscsend not found: install liblo-tools (scripts/setup's TEST_PACKAGES)";
  LiveSource source({LiveProtocol::Vmc, "127.0.0.1", 0});
  const std::string to = "oscsend 127.0.0.1 " + std::to_string(source.port()) + " ";
  ASSERT_EQ(std::system((to + "/VMC/Ext/Blend/Val sf MouthSmileLeft 0.75").c_str()), 0);
  ASSERT_EQ(std::system((to + "/VMC/Ext/Blend/Val sf blink_l 0.5").c_str()), 0);
  ASSERT_EQ(std::system((to + "/VMC/Ext/Bone/Pos sfffffff Head 0 0 0 0 0.258819 0 0.965926").c_str()), 0);
  ASSERT_EQ(std::system((to + "/VMC/Ext/Blend/Apply").c_str()), 0);
  ASSERT_TRUE(source.waitForFrame(5.0));
  const LiveSample s = *source.takeNewest();
  const auto& names = arkitNames();
  auto weight = [&](const char* n) { return s.frame.weights[std::find(names.begin(), names.end(), n) - names.begin()]; };
  EXPECT_EQ(weight("mouthSmileLeft"), 0.75);
  EXPECT_EQ(weight("eyeBlinkLeft"), 0.5);
  EXPECT_EQ(weight("eyeBlinkRight"), 0.0);
  ASSERT_TRUE(s.frame.headPose);
  EXPECT_NEAR(s.frame.headPose->y(), -30.0, 1e-4);  // Unity's +30° about y: the face frame's −30° yaw
  EXPECT_EQ(source.counters().packets, 4);
}

// ---- the face input, on an injected clock ----

LiveSample sampleAt(double t, double weight, long sequence) {
  LiveSample s;
  s.arrival = t;
  s.sequence = sequence;
  s.frame.weights.fill(weight);
  s.frame.headPose = Vec3(10, 20, -5);
  return s;
}

TEST(LiveFaceInput, SilenceHoldsThenEasesToNeutral) {
  LiveFaceInput input;  // timeout 0.5 s, ease 0.5 s
  EXPECT_EQ(input.at(0.0).weights[0], 0.0);  // neutral before the first frame
  input.receive(sampleAt(1.0, 0.6, 1));
  EXPECT_EQ(input.at(1.0).weights[7], 0.6);
  EXPECT_EQ(input.at(1.5).weights[7], 0.6);  // held through the timeout
  const LiveFrame halfway = input.at(1.75);  // half the ease: smoothstep gives 1/2
  EXPECT_NEAR(halfway.weights[7], 0.3, 1e-12);
  EXPECT_NEAR(halfway.headPose->y(), 10.0, 1e-12);
  const LiveFrame silent = input.at(3.0);  // 2 s of silence
  for (const double w : silent.weights) EXPECT_EQ(w, 0.0);
  EXPECT_EQ(silent.headPose->norm(), 0.0);
  input.receive(sampleAt(3.0, 0.2, 2));  // the stream is back: at once
  EXPECT_EQ(input.at(3.0).weights[0], 0.2);
}

TEST(LiveFaceInput, CalibrationSubtractsTheRestingWeights) {
  LiveFaceSettings settings;
  settings.calibrateSeconds = 1.0;
  LiveFaceInput input(settings);
  long n = 0;
  for (int i = 0; i <= 10; ++i) input.receive(sampleAt(0.1 * i, i % 2 ? 0.15 : 0.05, ++n));
  EXPECT_EQ(input.at(1.0).weights[0], 0.0);  // neutral while calibrating
  EXPECT_TRUE(input.calibrating(1.0));
  input.receive(sampleAt(1.1, 0.7, ++n));
  EXPECT_FALSE(input.calibrating(1.1));
  const double rest = (6 * 0.05 + 5 * 0.15) / 11;
  EXPECT_NEAR(input.rest()[4], rest, 1e-12);
  EXPECT_NEAR(input.at(1.1).weights[4], 0.7 - rest, 1e-12);
  input.receive(sampleAt(1.2, 0.01, ++n));
  EXPECT_EQ(input.at(1.2).weights[4], 0.0);  // below the rest: clamped, never negative
}

// "Calibrate neutral" at run time: the frames of the next seconds become the rest, the face is
// neutral while they arrive, and what comes after is measured from the new rest.
TEST(LiveFaceInput, CalibratingAgainTakesTheNewRestingWeights) {
  LiveFaceInput input;  // no calibration at the start: the rest is zero
  long n = 0;
  input.receive(sampleAt(0.0, 0.3, ++n));
  EXPECT_EQ(input.at(0.0).weights[2], 0.3);
  input.startCalibration(5.0, 0.5);
  EXPECT_TRUE(input.calibrating(5.0));
  EXPECT_EQ(input.at(5.0).weights[2], 0.0);  // neutral while calibrating
  input.receive(sampleAt(5.1, 0.2, ++n));
  input.receive(sampleAt(5.4, 0.4, ++n));
  EXPECT_EQ(input.at(5.4).weights[2], 0.0);
  EXPECT_EQ(input.rest()[2], 0.0);  // not known before the window closes
  input.receive(sampleAt(5.6, 0.5, ++n));  // after the window: the rest is the mean of 0.2 and 0.4
  EXPECT_FALSE(input.calibrating(5.6));
  EXPECT_NEAR(input.rest()[2], 0.3, 1e-12);
  EXPECT_NEAR(input.at(5.6).weights[2], 0.2, 1e-12);
  EXPECT_THROW(input.startCalibration(6.0, 0.0), InputError);
  EXPECT_THROW(input.startCalibration(6.0, std::nan("")), InputError);
}

// 10 % of a take's packets lost at random: each lost frame is held, so the face input deviates
// from the lossless take by at most what a weight moves over the longest run of lost frames.
TEST(LiveFaceInput, RandomLossDeviatesByAtMostTheHeldChange) {
  const std::vector<LiveFrame> frames = syntheticTake();
  std::mt19937 random(43);
  std::bernoulli_distribution lost(0.1);
  LiveFaceInput lossless, lossy;
  double largest = 0.0, bound = 0.0;
  size_t lastKept = 0;
  int lostCount = 0;
  for (size_t i = 0; i < frames.size(); ++i) {
    const double t = i / 60.0;
    LiveSample s;
    s.frame = frames[i];
    s.arrival = t;
    s.sequence = static_cast<long>(i + 1);
    lossless.receive(s);
    if (i == 0 || !lost(random)) {
      lossy.receive(s);
      lastKept = i;
    } else {
      ++lostCount;
    }
    const LiveFrame a = lossless.at(t), b = lossy.at(t);
    for (int k = 0; k < kArkitWeightCount; ++k) {
      largest = std::max(largest, std::fabs(a.weights[k] - b.weights[k]));
      bound = std::max(bound, std::fabs(frames[i].weights[k] - frames[lastKept].weights[k]));
    }
  }
  RecordProperty("lost_frames", lostCount);
  RecordProperty("largest_weight_deviation", std::to_string(largest));
  std::printf("%d of %zu frames lost: largest weight deviation %.4f (bound %.4f)\n", lostCount, frames.size(), largest,
              bound);
  EXPECT_GT(lostCount, 0);
  EXPECT_GT(largest, 0.0);
  EXPECT_LE(largest, bound + 1e-12);
}

}  // namespace
}  // namespace myo
