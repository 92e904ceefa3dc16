// The live packet decoders (io/live_packets.h): a Live Link Face packet assembled byte by byte from
// the layout, OSC built by liblo itself, and every kind of malformed packet dropped with its reason.
#include "myoshell/io/live_packets.h"

#include <gtest/gtest.h>
#include <lo/lo.h>

#include <cmath>
#include <cstring>
#include <limits>

#include "myoshell/fit/arkit_names.h"

namespace myo {
namespace {

int arkitIndex(const std::string& name) {
  const auto& names = arkitNames();
  return static_cast<int>(std::find(names.begin(), names.end(), name) - names.begin());
}

void pushU32(std::vector<std::uint8_t>& b, std::uint32_t v) {
  b.push_back(static_cast<std::uint8_t>(v >> 24));
  b.push_back(static_cast<std::uint8_t>(v >> 16));
  b.push_back(static_cast<std::uint8_t>(v >> 8));
  b.push_back(static_cast<std::uint8_t>(v));
}
void pushF32(std::vector<std::uint8_t>& b, float f) {
  std::uint32_t v;
  std::memcpy(&v, &f, 4);
  pushU32(b, v);
}

// The layout, written out here without the encoder: value i of the 61 is i / 100 for the
// 52 weights; the rotations are given.
std::vector<std::uint8_t> handMadeLiveLinkPacket(const std::string& subject, int count = 61) {
  std::vector<std::uint8_t> b;
  b.push_back(6);
  const std::string device = "4B1D-iPhone";
  pushU32(b, static_cast<std::uint32_t>(device.size()));
  b.insert(b.end(), device.begin(), device.end());
  pushU32(b, static_cast<std::uint32_t>(subject.size()));
  b.insert(b.end(), subject.begin(), subject.end());
  pushU32(b, 1234);   // frame
  pushF32(b, 0.25f);  // sub-frame
  pushU32(b, 60);     // rate 60/1
  pushU32(b, 1);
  b.push_back(static_cast<std::uint8_t>(count));
  for (int i = 0; i < 52; ++i) pushF32(b, static_cast<float>(i) / 100.0f);
  const float rotations[9] = {0.1f, -0.05f, 0.02f, 0.03f, 0.04f, 0.0f, -0.03f, 0.06f, 0.0f};
  for (const float r : rotations) pushF32(b, r);
  return b;
}

TEST(LiveLinkPacket, AssembledByteByByteDecodesInLiveLinksOrder) {
  for (const std::string subject : {"", "iPhone", "A rather longer subject name, 41 bytes."}) {
    const std::vector<std::uint8_t> bytes = handMadeLiveLinkPacket(subject);
    const DecodedPacket p = decodeLiveLinkPacket(bytes.data(), bytes.size());
    ASSERT_EQ(p.status, PacketStatus::Frame) << p.reason;
    EXPECT_EQ(*p.senderFrame, 1234);
    const auto& w = p.frame.weights;
    EXPECT_FLOAT_EQ(w[arkitIndex("eyeBlinkLeft")], 0.00f);
    EXPECT_FLOAT_EQ(w[arkitIndex("jawRight")], 0.15f);  // Live Link: JawRight (15) before JawLeft (16)
    EXPECT_FLOAT_EQ(w[arkitIndex("jawLeft")], 0.16f);
    EXPECT_FLOAT_EQ(w[arkitIndex("mouthRight")], 0.21f);
    EXPECT_FLOAT_EQ(w[arkitIndex("mouthLeft")], 0.22f);
    EXPECT_FLOAT_EQ(w[arkitIndex("tongueOut")], 0.51f);
    // [pitch, yaw, roll] = 180·[HeadPitch, HeadYaw, HeadRoll] (the CSV reader's reading).
    ASSERT_TRUE(p.frame.headPose);
    EXPECT_NEAR(p.frame.headPose->x(), 180 * -0.05, 1e-4);
    EXPECT_NEAR(p.frame.headPose->y(), 180 * 0.1, 1e-4);
    EXPECT_NEAR(p.frame.headPose->z(), 180 * 0.02, 1e-4);
    ASSERT_TRUE(p.frame.gaze);
    EXPECT_NEAR(p.frame.gaze->yawDeg[1], 180 * 0.03, 1e-4);     // the left eye (1): LeftEyeYaw
    EXPECT_NEAR(p.frame.gaze->pitchDeg[1], -180 * 0.04, 1e-4);  // pitch + up = −180·LeftEyePitch
    EXPECT_NEAR(p.frame.gaze->yawDeg[0], 180 * -0.03, 1e-4);
    EXPECT_NEAR(p.frame.gaze->pitchDeg[0], -180 * 0.06, 1e-4);
  }
}

TEST(LiveLinkPacket, EncoderRoundTripsToFloatPrecision) {
  LiveFrame f;
  for (int k = 0; k < kArkitWeightCount; ++k) f.weights[k] = std::fmod(0.37 * k, 1.0);
  f.headPose = Vec3(10, -20, 5);
  EyeGaze g;
  g.pitchDeg = {3, 4};
  g.yawDeg = {-5, 6};
  f.gaze = g;
  const auto bytes = encodeLiveLinkPacket(f, {77, 0.0f, 60, 1}, "dev", "me");
  const DecodedPacket p = decodeLiveLinkPacket(bytes.data(), bytes.size());
  ASSERT_EQ(p.status, PacketStatus::Frame) << p.reason;
  EXPECT_EQ(*p.senderFrame, 77);
  for (int k = 0; k < kArkitWeightCount; ++k) EXPECT_EQ(p.frame.weights[k], static_cast<float>(f.weights[k])) << k;
  EXPECT_NEAR((*p.frame.headPose - *f.headPose).norm(), 0.0, 1e-4);
  EXPECT_NEAR(p.frame.gaze->pitchDeg[0], 3, 1e-4);
  EXPECT_NEAR(p.frame.gaze->yawDeg[1], 6, 1e-4);
}

TEST(LiveLinkPacket, MalformedPacketsAreDroppedWithTheirReason) {
  const std::vector<std::uint8_t> good = handMadeLiveLinkPacket("iPhone");
  // Every truncation is malformed (and none reads past the end: ASan/the fuzzer check that).
  for (size_t n = 0; n < good.size(); ++n)
    EXPECT_EQ(decodeLiveLinkPacket(good.data(), n).status, PacketStatus::Malformed) << n << " bytes";
  auto reason = [](std::vector<std::uint8_t> b) {
    const DecodedPacket p = decodeLiveLinkPacket(b.data(), b.size());
    EXPECT_EQ(p.status, PacketStatus::Malformed);
    return p.reason;
  };
  EXPECT_EQ(reason({}), "empty packet");
  auto v5 = good;
  v5[0] = 5;
  EXPECT_EQ(reason(v5), "version 5 (this reader knows version 6)");
  auto longName = good;
  longName[1 + 4 + 11 + 1] = 1;  // the subject's length: 65536 + 6, more than is left
  EXPECT_EQ(reason(longName), "truncated subject name (length 65542, 267 bytes left)");
  EXPECT_EQ(reason(handMadeLiveLinkPacket("iPhone", 60)), "60 values (a Live Link Face packet has 61)");
  auto trailing = good;
  trailing.push_back(0);
  EXPECT_EQ(reason(trailing), "245 bytes for 61 float32 values (expected 244)");
  auto nan = good;
  const float quietNan = std::numeric_limits<float>::quiet_NaN();
  std::uint32_t bits;
  std::memcpy(&bits, &quietNan, 4);
  const size_t jawOpenAt = good.size() - 4 * 61 + 4 * 17;
  for (int k = 0; k < 4; ++k) nan[jawOpenAt + k] = static_cast<std::uint8_t>(bits >> (24 - 8 * k));
  EXPECT_EQ(reason(nan), "JawOpen is not a finite number");
  auto big = good;
  const float two = 2.0f;
  std::memcpy(&bits, &two, 4);
  for (int k = 0; k < 4; ++k) big[jawOpenAt + k] = static_cast<std::uint8_t>(bits >> (24 - 8 * k));
  EXPECT_EQ(reason(big), "JawOpen is 2, outside [0, 1]");
}

// ---- VMC ----

std::vector<std::uint8_t> oscMessage(const char* path, lo_message m) {
  size_t size = 0;
  void* data = lo_message_serialise(m, path, nullptr, &size);
  std::vector<std::uint8_t> out(static_cast<std::uint8_t*>(data), static_cast<std::uint8_t*>(data) + size);
  std::free(data);
  lo_message_free(m);
  return out;
}

std::vector<std::uint8_t> blendVal(const char* name, float value) {
  lo_message m = lo_message_new();
  lo_message_add_string(m, name);
  lo_message_add_float(m, value);
  return oscMessage("/VMC/Ext/Blend/Val", m);
}

std::vector<std::uint8_t> apply() { return oscMessage("/VMC/Ext/Blend/Apply", lo_message_new()); }

DecodedPacket feed(VmcDecoder& d, const std::vector<std::uint8_t>& b) { return d.decode(b.data(), b.size()); }

TEST(VmcPacket, ValuesThenApplyMakeAFrameWithNamesInAnyCase) {
  VmcDecoder d;
  EXPECT_EQ(feed(d, blendVal("MouthSmileLeft", 0.75f)).status, PacketStatus::Incomplete);
  EXPECT_EQ(feed(d, blendVal("jawopen", 0.5f)).status, PacketStatus::Incomplete);
  const DecodedPacket p = feed(d, apply());
  ASSERT_EQ(p.status, PacketStatus::Frame);
  EXPECT_EQ(p.frame.weights[arkitIndex("mouthSmileLeft")], 0.75);
  EXPECT_EQ(p.frame.weights[arkitIndex("jawOpen")], 0.5);
  EXPECT_FALSE(p.frame.headPose);
  // Values not sent again hold: a sender may send only what changed.
  feed(d, blendVal("JAWOPEN", 0.25f));
  const DecodedPacket q = feed(d, apply());
  EXPECT_EQ(q.frame.weights[arkitIndex("mouthSmileLeft")], 0.75);
  EXPECT_EQ(q.frame.weights[arkitIndex("jawOpen")], 0.25);
}

TEST(VmcPacket, VrmPresetsMapWhereTheyMeanSomethingElseCountedAndWarnedOnce) {
  VmcDecoder d;
  feed(d, blendVal("Blink", 0.5f));
  feed(d, blendVal("A", 0.4f));
  feed(d, blendVal("LookUp", 1.0f));
  feed(d, blendVal("LookUp", 0.5f));
  feed(d, blendVal("Neutral", 1.0f));
  const DecodedPacket p = feed(d, apply());
  ASSERT_EQ(p.status, PacketStatus::Frame);
  EXPECT_EQ(p.frame.weights[arkitIndex("eyeBlinkLeft")], 0.5);
  EXPECT_EQ(p.frame.weights[arkitIndex("eyeBlinkRight")], 0.5);
  EXPECT_FLOAT_EQ(p.frame.weights[arkitIndex("jawOpen")], 0.4f);
  EXPECT_EQ(d.unknownNames(), (std::vector<std::string>{"LookUp", "Neutral"}));
  EXPECT_EQ(d.unknownValues(), 3);
}

TEST(VmcPacket, EncodedBundleRoundTripsWithTheHead) {
  LiveFrame f;
  for (int k = 0; k < kArkitWeightCount; ++k) f.weights[k] = std::fmod(0.61 * k, 1.0);
  f.headPose = Vec3(10, -20, 5);
  const auto bytes = encodeVmcPacket(f);
  VmcDecoder d;
  const DecodedPacket p = d.decode(bytes.data(), bytes.size());
  ASSERT_EQ(p.status, PacketStatus::Frame) << p.reason;
  for (int k = 0; k < kArkitWeightCount; ++k) EXPECT_EQ(p.frame.weights[k], static_cast<float>(f.weights[k])) << k;
  ASSERT_TRUE(p.frame.headPose);
  EXPECT_NEAR((*p.frame.headPose - *f.headPose).norm(), 0.0, 1e-4);
  EXPECT_TRUE(d.unknownNames().empty());
}

TEST(VmcPacket, UnityHeadQuaternionTurnsAsTheFaceFrameSays) {
  // Unity (left-handed, y up, the avatar facing +z): +30° about y turns the avatar to its right,
  // the face frame's −yaw (its yaw + is towards its own left); +20° about x looks down, as +pitch.
  const double h = 15.0 * M_PI / 180.0;
  const Vec3 turned = headPoseFromUnityQuaternion(0, std::sin(h), 0, std::cos(h));
  EXPECT_NEAR(turned.y(), -30.0, 1e-9);
  EXPECT_NEAR(turned.x(), 0.0, 1e-9);
  const double p = 10.0 * M_PI / 180.0;
  const Vec3 nod = headPoseFromUnityQuaternion(std::sin(p), 0, 0, std::cos(p));
  EXPECT_NEAR(nod.x(), 20.0, 1e-9);
  EXPECT_NEAR(nod.y(), 0.0, 1e-9);
}

TEST(VmcPacket, MalformedPacketsAreDroppedAndChangeNothing) {
  VmcDecoder d;
  feed(d, blendVal("JawOpen", 0.5f));
  auto reason = [&](const std::vector<std::uint8_t>& b) {
    const DecodedPacket p = feed(d, b);
    EXPECT_EQ(p.status, PacketStatus::Malformed);
    return p.reason;
  };
  EXPECT_EQ(reason({}), "empty packet");
  EXPECT_EQ(reason({'/', 'a', 0}), "3 bytes, not a multiple of 4 (OSC)");
  lo_message wrongTypes = lo_message_new();
  lo_message_add_string(wrongTypes, "JawOpen");
  lo_message_add_int32(wrongTypes, 1);
  EXPECT_EQ(reason(oscMessage("/VMC/Ext/Blend/Val", wrongTypes)), "/VMC/Ext/Blend/Val with arguments 'si' (expected 'sf')");
  EXPECT_EQ(reason(blendVal("JawOpen", std::numeric_limits<float>::quiet_NaN())),
            "blend value of JawOpen is not a finite number");
  EXPECT_EQ(reason(blendVal("JawOpen", 3.0f)), "blend value of JawOpen is 3, outside [0, 1]");
  // A bundle whose second element claims more bytes than there are: the first (a value) is undone.
  std::vector<std::uint8_t> bundle = {'#', 'b', 'u', 'n', 'd', 'l', 'e', 0, 0, 0, 0, 0, 0, 0, 0, 1};
  const auto val = blendVal("JawOpen", 0.9f);
  pushU32(bundle, static_cast<std::uint32_t>(val.size()));
  bundle.insert(bundle.end(), val.begin(), val.end());
  pushU32(bundle, 64);
  EXPECT_EQ(reason(bundle), "bundle element of 64 bytes, 0 left");
  // Garbage: no OSC address.
  EXPECT_EQ(reason({0xff, 0xfe, 0x00, 0x01}), "not an OSC message (no address)");
  // Unknown addresses are ignored, not malformed.
  lo_message root = lo_message_new();
  lo_message_add_string(root, "root");
  EXPECT_EQ(feed(d, oscMessage("/VMC/Ext/Root/Pos", root)).status, PacketStatus::Ignored);
  const DecodedPacket p = feed(d, apply());
  EXPECT_EQ(p.frame.weights[arkitIndex("jawOpen")], 0.5);  // as set before the bad packets
}

}  // namespace
}  // namespace myo
