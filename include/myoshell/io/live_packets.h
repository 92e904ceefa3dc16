// What face trackers stream over UDP, decoded into one frame of ARKit weights (docs/live.md):
//   - Live Link Face (Epic's iPhone app, default port 11111): one packet per frame, big-endian: a
//     version byte (6), the device id and the subject name each as a uint32 length and its bytes,
//     the frame time (int32 frame, float32 sub-frame, int32 rate numerator, int32 denominator), a
//     count byte (61) and 61 float32: ARKit's 52 weights in Live Link's own order (the order of a
//     Live Link CSV's columns: JawRight before JawLeft, MouthRight before MouthLeft), then HeadYaw,
//     HeadPitch, HeadRoll and each eye's yaw, pitch, roll, as degrees / 180 (anim/performance.h).
//   - VMC protocol (OSC over UDP, default port 39539; VSeeFace, iFacialMocap, Warudo):
//     `/VMC/Ext/Blend/Val (s name)(f value)` repeated, then `/VMC/Ext/Blend/Apply`, in bundles or
//     not; `/VMC/Ext/Bone/Pos (s "Head")(f px py pz)(f qx qy qz qw)`, Unity's left-handed axes.
//     OSC messages are read and written by liblo; only the bundle envelope (which liblo decodes
//     only inside a socket-owning lo_server) is split here.
// Decoding is a pure function of the bytes (plus, for VMC, the values set since the last Apply):
// a packet gives a frame, nothing yet, or is dropped with the reason. Nothing here throws on bad
// bytes, so both decoders are fuzzed (fuzz/fuzz_live_packets.cpp).
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "myoshell/core/types.h"
#include "myoshell/head/eye_gaze.h"

namespace myo {

constexpr int kArkitWeightCount = 52;

// One tracked frame: ARKit's 52 weights in arkitNames()' order (fit/arkit_names.h), each in [0, 1],
// the head's rotation and the eyes' turn when the packet carries them.
struct LiveFrame {
  std::array<double, kArkitWeightCount> weights{};
  // [pitch, yaw, roll] degrees about the face frame's x, y, z (anim/head_pose_track.h).
  std::optional<Vec3> headPose;
  std::optional<EyeGaze> gaze;  // head/eye_gaze.h's angles (not yet clamped)
};

enum class PacketStatus {
  Frame,       // a complete frame
  Incomplete,  // VMC: values set, no Apply yet
  Ignored,     // well-formed, but nothing a face uses (an unknown OSC address, another bone)
  Malformed,   // dropped: `reason` says why
};

struct DecodedPacket {
  PacketStatus status = PacketStatus::Malformed;
  LiveFrame frame;     // when status == Frame
  std::string reason;  // when Malformed: "truncated subject name (length 40, 12 bytes left)"
  // Live Link: the sender's frame number (its frame time's frame), to count frames lost on the way.
  std::optional<std::int32_t> senderFrame;
};

// ---- Live Link Face ----
constexpr std::uint8_t kLiveLinkVersion = 6;
constexpr int kLiveLinkValueCount = 61;

// The 61 value names of a Live Link packet (and CSV columns after BlendShapeCount), in order.
const std::array<std::string, kLiveLinkValueCount>& liveLinkValueNames();

DecodedPacket decodeLiveLinkPacket(const std::uint8_t* data, std::size_t size);

struct LiveLinkFrameTime {
  std::int32_t frame = 0;
  float subFrame = 0.0f;
  std::int32_t rateNumerator = 60;
  std::int32_t rateDenominator = 1;
};
// The packet for `frame` (weights as float32; the head and eyes as degrees / 180, 0 when absent).
std::vector<std::uint8_t> encodeLiveLinkPacket(const LiveFrame& frame, const LiveLinkFrameTime& time,
                                               const std::string& deviceId = "myoshell",
                                               const std::string& subject = "myoshell");

// ---- VMC ----
// Keeps the blend values set since the start (VMC senders may send only what changed) and turns
// each Apply into a frame. Names: ARKit's 52 (perfect sync, matched case-insensitively) and VRM's
// presets with an ARKit meaning (vrmPresetMeaning); any other name is counted and warned about once.
class VmcDecoder {
 public:
  DecodedPacket decode(const std::uint8_t* data, std::size_t size);

  // Blend names that mean nothing here (VRM's LookUp, Neutral, a model's own), each once, in order.
  const std::vector<std::string>& unknownNames() const { return unknownNames_; }
  long unknownValues() const { return unknownValues_; }  // how many values had such a name

 private:
  enum class Outcome { None, Apply, Ignored };
  std::string message(const std::uint8_t* data, std::size_t size, int depth, Outcome& outcome, bool& head);
  std::array<double, kArkitWeightCount> arkit_{};     // as set by ARKit names
  std::map<std::string, double> presets_;             // as set by VRM preset names (lowercase)
  std::optional<Vec3> headPose_;
  std::vector<std::string> unknownNames_;
  std::set<std::string> unknownSeen_;
  long unknownValues_ = 0;
};

// A VRM blend-shape preset's ARKit meaning: the ARKit names (arkitNames() indices) it moves and by
// how much; empty for a preset without one (LookUp, Neutral). Case-insensitive; VRM 0 (A, Joy) and
// VRM 1 (aa, happy) spellings.
std::vector<std::pair<int, double>> vrmPresetMeaning(std::string_view name);

// A bundle with the head (when the frame has it) as /VMC/Ext/Bone/Pos "Head", every weight as
// /VMC/Ext/Blend/Val with ARKit's PascalCase name, then /VMC/Ext/Blend/Apply.
std::vector<std::uint8_t> encodeVmcPacket(const LiveFrame& frame);

// The head's [pitch, yaw, roll] degrees (face frame) from a Unity quaternion (x, y, z, w) of a
// head facing +z, and back. Unity's x is the avatar's right, the face frame's x its left: the
// mirror S = diag(−1, 1, 1) takes one to the other, R_face = S R_unity S, i.e. (x, −y, −z, w).
Vec3 headPoseFromUnityQuaternion(double x, double y, double z, double w);
std::array<double, 4> unityQuaternionFromHeadPose(const Vec3& pitchYawRollDeg);

}  // namespace myo
