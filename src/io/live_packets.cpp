#include "myoshell/io/live_packets.h"

#include <fmt/core.h>
#include <lo/lo.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <Eigen/Geometry>

#include "myoshell/fit/arkit_names.h"

namespace myo {

namespace {

// A weight may overshoot [0, 1] by float round-off; anything further is not what ARKit writes.
constexpr double kWeightSlack = 1e-5;

std::string lowercase(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

// arkitNames() index of a name in any case, or -1.
int arkitIndexAnyCase(std::string_view name) {
  static const std::map<std::string, int> byLowercase = [] {
    std::map<std::string, int> m;
    const auto& names = arkitNames();
    for (size_t i = 0; i < names.size(); ++i) m[lowercase(names[i])] = static_cast<int>(i);
    return m;
  }();
  const auto it = byLowercase.find(lowercase(name));
  return it == byLowercase.end() ? -1 : it->second;
}

DecodedPacket malformed(std::string reason) {
  DecodedPacket p;
  p.status = PacketStatus::Malformed;
  p.reason = std::move(reason);
  return p;
}

// Big-endian reads that never run past the end.
struct ByteReader {
  const std::uint8_t* data;
  std::size_t size;
  std::size_t at = 0;
  std::size_t left() const { return size - at; }
  std::uint32_t u32() {
    const std::uint32_t v = (std::uint32_t{data[at]} << 24) | (std::uint32_t{data[at + 1]} << 16) |
                            (std::uint32_t{data[at + 2]} << 8) | std::uint32_t{data[at + 3]};
    at += 4;
    return v;
  }
  float f32() {
    const std::uint32_t bits = u32();
    float v;
    std::memcpy(&v, &bits, 4);
    return v;
  }
};

void putU32(std::vector<std::uint8_t>& out, std::uint32_t v) {
  for (int shift = 24; shift >= 0; shift -= 8) out.push_back(static_cast<std::uint8_t>(v >> shift));
}
void putF32(std::vector<std::uint8_t>& out, float v) {
  std::uint32_t bits;
  std::memcpy(&bits, &v, 4);
  putU32(out, bits);
}

// The 61 values' roles: an ARKit index, or one of the rotations.
enum Rotation { kHeadYaw = -1, kHeadPitch = -2, kHeadRoll = -3, kLeftEyeYaw = -4, kLeftEyePitch = -5,
                kLeftEyeRoll = -6, kRightEyeYaw = -7, kRightEyePitch = -8, kRightEyeRoll = -9 };

const std::array<int, kLiveLinkValueCount>& liveLinkRoles() {
  static const std::array<int, kLiveLinkValueCount> roles = [] {
    std::array<int, kLiveLinkValueCount> r{};
    const auto& names = liveLinkValueNames();
    for (int i = 0; i < kArkitWeightCount; ++i) r[i] = arkitIndexAnyCase(names[i]);
    for (int i = kArkitWeightCount; i < kLiveLinkValueCount; ++i) r[i] = -(i - kArkitWeightCount + 1);
    return r;
  }();
  return roles;
}

std::string pascalCase(const std::string& camel) {
  std::string s = camel;
  if (!s.empty()) s[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(s[0])));
  return s;
}

}  // namespace

const std::array<std::string, kLiveLinkValueCount>& liveLinkValueNames() {
  static const std::array<std::string, kLiveLinkValueCount> names = {
      "EyeBlinkLeft", "EyeLookDownLeft", "EyeLookInLeft", "EyeLookOutLeft", "EyeLookUpLeft", "EyeSquintLeft",
      "EyeWideLeft", "EyeBlinkRight", "EyeLookDownRight", "EyeLookInRight", "EyeLookOutRight", "EyeLookUpRight",
      "EyeSquintRight", "EyeWideRight", "JawForward", "JawRight", "JawLeft", "JawOpen", "MouthClose",
      "MouthFunnel", "MouthPucker", "MouthRight", "MouthLeft", "MouthSmileLeft", "MouthSmileRight",
      "MouthFrownLeft", "MouthFrownRight", "MouthDimpleLeft", "MouthDimpleRight", "MouthStretchLeft",
      "MouthStretchRight", "MouthRollLower", "MouthRollUpper", "MouthShrugLower", "MouthShrugUpper",
      "MouthPressLeft", "MouthPressRight", "MouthLowerDownLeft", "MouthLowerDownRight", "MouthUpperUpLeft",
      "MouthUpperUpRight", "BrowDownLeft", "BrowDownRight", "BrowInnerUp", "BrowOuterUpLeft", "BrowOuterUpRight",
      "CheekPuff", "CheekSquintLeft", "CheekSquintRight", "NoseSneerLeft", "NoseSneerRight", "TongueOut",
      "HeadYaw", "HeadPitch", "HeadRoll", "LeftEyeYaw", "LeftEyePitch", "LeftEyeRoll", "RightEyeYaw",
      "RightEyePitch", "RightEyeRoll"};
  return names;
}

DecodedPacket decodeLiveLinkPacket(const std::uint8_t* data, std::size_t size) {
  ByteReader in{data, size};
  if (in.left() < 1) return malformed("empty packet");
  const std::uint8_t version = data[in.at++];
  if (version != kLiveLinkVersion)
    return malformed(fmt::format("version {} (this reader knows version {})", version, kLiveLinkVersion));
  for (const char* what : {"device id", "subject name"}) {
    if (in.left() < 4) return malformed(fmt::format("truncated before the {}'s length", what));
    const std::uint32_t length = in.u32();
    if (length > in.left())
      return malformed(fmt::format("truncated {} (length {}, {} bytes left)", what, length, in.left()));
    in.at += length;
  }
  if (in.left() < 17) return malformed(fmt::format("truncated frame time ({} bytes left, 16 + a count needed)", in.left()));
  DecodedPacket out;
  out.senderFrame = static_cast<std::int32_t>(in.u32());
  const float subFrame = in.f32();
  const std::int32_t rateNumerator = static_cast<std::int32_t>(in.u32());
  const std::int32_t rateDenominator = static_cast<std::int32_t>(in.u32());
  if (!std::isfinite(subFrame)) return malformed("non-finite sub-frame");
  if (rateNumerator <= 0 || rateDenominator <= 0)
    return malformed(fmt::format("frame rate {}/{} is not positive", rateNumerator, rateDenominator));
  const int count = data[in.at++];
  if (count != kLiveLinkValueCount)
    return malformed(fmt::format("{} values (a Live Link Face packet has {})", count, kLiveLinkValueCount));
  if (in.left() != 4u * kLiveLinkValueCount)
    return malformed(fmt::format("{} bytes for {} float32 values (expected {})", in.left(), count,
                                 4 * kLiveLinkValueCount));
  const auto& names = liveLinkValueNames();
  const auto& roles = liveLinkRoles();
  double rotation[9];
  for (int i = 0; i < kLiveLinkValueCount; ++i) {
    const double v = in.f32();
    if (!std::isfinite(v)) return malformed(fmt::format("{} is not a finite number", names[i]));
    if (roles[i] >= 0) {
      if (v < -kWeightSlack || v > 1 + kWeightSlack)
        return malformed(fmt::format("{} is {}, outside [0, 1]", names[i], v));
      out.frame.weights[roles[i]] = std::clamp(v, 0.0, 1.0);
    } else {
      // The app maps −180…180° onto −1…1 (anim/performance.h): anything further is not an angle.
      if (std::fabs(v) > 1 + kWeightSlack)
        return malformed(fmt::format("{} is {}, outside [-1, 1] (degrees / 180)", names[i], v));
      rotation[-roles[i] - 1] = v;
    }
  }
  // As the Live Link CSV reader (performance_livelink.cpp): [pitch, yaw, roll] = 180·[HeadPitch,
  // HeadYaw, HeadRoll]; an eye's pitch (+ up) = −180·EyePitch, yaw = 180·EyeYaw; eye 0 the right.
  out.frame.headPose = Vec3(180.0 * rotation[-kHeadPitch - 1], 180.0 * rotation[-kHeadYaw - 1],
                            180.0 * rotation[-kHeadRoll - 1]);
  EyeGaze gaze;
  gaze.pitchDeg = {-180.0 * rotation[-kRightEyePitch - 1], -180.0 * rotation[-kLeftEyePitch - 1]};
  gaze.yawDeg = {180.0 * rotation[-kRightEyeYaw - 1], 180.0 * rotation[-kLeftEyeYaw - 1]};
  out.frame.gaze = gaze;
  out.status = PacketStatus::Frame;
  return out;
}

std::vector<std::uint8_t> encodeLiveLinkPacket(const LiveFrame& frame, const LiveLinkFrameTime& time,
                                               const std::string& deviceId, const std::string& subject) {
  std::vector<std::uint8_t> out;
  out.push_back(kLiveLinkVersion);
  for (const std::string* s : {&deviceId, &subject}) {
    putU32(out, static_cast<std::uint32_t>(s->size()));
    out.insert(out.end(), s->begin(), s->end());
  }
  putU32(out, static_cast<std::uint32_t>(time.frame));
  putF32(out, time.subFrame);
  putU32(out, static_cast<std::uint32_t>(time.rateNumerator));
  putU32(out, static_cast<std::uint32_t>(time.rateDenominator));
  out.push_back(static_cast<std::uint8_t>(kLiveLinkValueCount));
  const Vec3 head = frame.headPose.value_or(Vec3::Zero());
  const EyeGaze gaze = frame.gaze.value_or(EyeGaze{});
  double rotation[9] = {0};
  rotation[-kHeadYaw - 1] = head.y() / 180.0;
  rotation[-kHeadPitch - 1] = head.x() / 180.0;
  rotation[-kHeadRoll - 1] = head.z() / 180.0;
  rotation[-kLeftEyeYaw - 1] = gaze.yawDeg[1] / 180.0;
  rotation[-kLeftEyePitch - 1] = -gaze.pitchDeg[1] / 180.0;
  rotation[-kRightEyeYaw - 1] = gaze.yawDeg[0] / 180.0;
  rotation[-kRightEyePitch - 1] = -gaze.pitchDeg[0] / 180.0;
  const auto& roles = liveLinkRoles();
  for (int i = 0; i < kLiveLinkValueCount; ++i)
    putF32(out, static_cast<float>(roles[i] >= 0 ? frame.weights[roles[i]] : rotation[-roles[i] - 1]));
  return out;
}

// ---- VMC ----

std::vector<std::pair<int, double>> vrmPresetMeaning(std::string_view name) {
  // The readings of VRM's expressions as ARKit shapes: the vowels by their mouth shapes, the
  // emotions by their most telling FACS motion. A choice, not a standard (docs/live.md).
  static const std::map<std::string, std::vector<std::pair<std::string, double>>> table = {
      {"a", {{"jawOpen", 1.0}}},
      {"aa", {{"jawOpen", 1.0}}},
      {"i", {{"mouthStretchLeft", 1.0}, {"mouthStretchRight", 1.0}}},
      {"ih", {{"mouthStretchLeft", 1.0}, {"mouthStretchRight", 1.0}}},
      {"u", {{"mouthPucker", 1.0}}},
      {"ou", {{"mouthPucker", 1.0}}},
      {"e", {{"jawOpen", 0.5}, {"mouthStretchLeft", 0.5}, {"mouthStretchRight", 0.5}}},
      {"ee", {{"jawOpen", 0.5}, {"mouthStretchLeft", 0.5}, {"mouthStretchRight", 0.5}}},
      {"o", {{"mouthFunnel", 1.0}, {"jawOpen", 0.5}}},
      {"oh", {{"mouthFunnel", 1.0}, {"jawOpen", 0.5}}},
      {"blink", {{"eyeBlinkLeft", 1.0}, {"eyeBlinkRight", 1.0}}},
      {"blink_l", {{"eyeBlinkLeft", 1.0}}},
      {"blinkleft", {{"eyeBlinkLeft", 1.0}}},
      {"blink_r", {{"eyeBlinkRight", 1.0}}},
      {"blinkright", {{"eyeBlinkRight", 1.0}}},
      {"joy", {{"mouthSmileLeft", 1.0}, {"mouthSmileRight", 1.0}, {"cheekSquintLeft", 0.5}, {"cheekSquintRight", 0.5}}},
      {"happy", {{"mouthSmileLeft", 1.0}, {"mouthSmileRight", 1.0}, {"cheekSquintLeft", 0.5}, {"cheekSquintRight", 0.5}}},
      {"fun", {{"mouthSmileLeft", 0.7}, {"mouthSmileRight", 0.7}}},
      {"relaxed", {{"mouthSmileLeft", 0.7}, {"mouthSmileRight", 0.7}}},
      {"angry", {{"browDownLeft", 1.0}, {"browDownRight", 1.0}, {"noseSneerLeft", 0.3}, {"noseSneerRight", 0.3}}},
      {"sorrow", {{"browInnerUp", 1.0}, {"mouthFrownLeft", 1.0}, {"mouthFrownRight", 1.0}}},
      {"sad", {{"browInnerUp", 1.0}, {"mouthFrownLeft", 1.0}, {"mouthFrownRight", 1.0}}},
      {"surprised", {{"browInnerUp", 1.0}, {"browOuterUpLeft", 1.0}, {"browOuterUpRight", 1.0}, {"eyeWideLeft", 1.0},
                     {"eyeWideRight", 1.0}, {"jawOpen", 0.5}}},
  };
  const auto it = table.find(lowercase(name));
  std::vector<std::pair<int, double>> out;
  if (it == table.end()) return out;
  for (const auto& [arkit, weight] : it->second) out.emplace_back(arkitIndexAnyCase(arkit), weight);
  return out;
}

namespace {

// RAII for liblo's C objects.
struct LoMessage {
  lo_message m;
  ~LoMessage() {
    if (m) lo_message_free(m);
  }
};

std::uint32_t readBigEndian32(const std::uint8_t* p) {
  return (std::uint32_t{p[0]} << 24) | (std::uint32_t{p[1]} << 16) | (std::uint32_t{p[2]} << 8) | std::uint32_t{p[3]};
}

constexpr int kMaxBundleDepth = 8;  // a deeper nesting is no tracker's; it only costs stack

}  // namespace

// One OSC packet (a message or a bundle): "" when read, else the reason it is malformed. Apply and
// a head pose are reported through `outcome` and `head`.
std::string VmcDecoder::message(const std::uint8_t* data, std::size_t size, int depth, Outcome& outcome, bool& head) {
  if (size >= 8 && std::memcmp(data, "#bundle", 8) == 0) {
    // "#bundle\0", a 64-bit time tag, then elements: an int32 size and that many bytes each.
    if (depth >= kMaxBundleDepth) return "bundles nested too deep";
    if (size < 16) return "truncated bundle header";
    std::size_t at = 16;
    while (at < size) {
      if (size - at < 4) return "truncated bundle element size";
      const std::uint32_t length = readBigEndian32(data + at);
      at += 4;
      if (length > size - at) return fmt::format("bundle element of {} bytes, {} left", length, size - at);
      if (length % 4 != 0) return fmt::format("bundle element of {} bytes, not a multiple of 4", length);
      if (std::string why = message(data + at, length, depth + 1, outcome, head); !why.empty()) return why;
      at += length;
    }
    return "";
  }
  // liblo reads the address and the arguments (it validates the padding and the type tags).
  std::vector<std::uint8_t> copy(data, data + size);  // liblo takes non-const pointers
  const char* path = lo_get_path(copy.data(), static_cast<ssize_t>(copy.size()));
  if (!path) return "not an OSC message (no address)";
  const std::string address(path);
  int result = 0;
  LoMessage msg{lo_message_deserialise(copy.data(), copy.size(), &result)};
  if (!msg.m) return fmt::format("unreadable OSC message at {} (liblo error {})", address, result);
  const std::string types = lo_message_get_types(msg.m) ? lo_message_get_types(msg.m) : "";
  lo_arg** argv = lo_message_get_argv(msg.m);
  // liblo packs arguments at 4-byte offsets, not lo_arg's 8-byte alignment: read them by copy.
  auto text = [&](int i) { return std::string(reinterpret_cast<const char*>(argv[i])); };
  auto number = [&](int i) {
    float f;
    std::memcpy(&f, argv[i], sizeof f);
    return static_cast<double>(f);
  };
  if (address == "/VMC/Ext/Blend/Val") {
    if (types != "sf") return fmt::format("/VMC/Ext/Blend/Val with arguments '{}' (expected 'sf')", types);
    const std::string name = text(0);
    const double value = number(1);
    if (!std::isfinite(value)) return fmt::format("blend value of {} is not a finite number", name);
    if (value < -kWeightSlack || value > 1 + kWeightSlack)
      return fmt::format("blend value of {} is {}, outside [0, 1]", name, value);
    const double clamped = std::clamp(value, 0.0, 1.0);
    if (const int k = arkitIndexAnyCase(name); k >= 0) {
      arkit_[k] = clamped;
    } else if (!vrmPresetMeaning(name).empty()) {
      presets_[lowercase(name)] = clamped;
    } else {
      ++unknownValues_;
      if (unknownSeen_.insert(name).second) unknownNames_.push_back(name);
    }
    if (outcome == Outcome::Ignored) outcome = Outcome::None;
  } else if (address == "/VMC/Ext/Blend/Apply") {
    outcome = Outcome::Apply;
  } else if (address == "/VMC/Ext/Bone/Pos") {
    if (types.size() < 8 || types.compare(0, 8, "sfffffff") != 0)
      return fmt::format("/VMC/Ext/Bone/Pos with arguments '{}' (expected 'sfffffff')", types);
    if (text(0) != "Head") return "";  // another bone: not the face's
    const double q[4] = {number(4), number(5), number(6), number(7)};
    const double norm = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    if (!std::isfinite(norm) || norm < 1e-6) return "the head's quaternion is not a finite, non-zero quaternion";
    headPose_ = headPoseFromUnityQuaternion(q[0], q[1], q[2], q[3]);
    head = true;
    if (outcome == Outcome::Ignored) outcome = Outcome::None;
  }
  return "";  // unknown addresses (VMC's root, other extensions) are ignored
}

DecodedPacket VmcDecoder::decode(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return malformed("empty packet");
  if (size % 4 != 0) return malformed(fmt::format("{} bytes, not a multiple of 4 (OSC)", size));
  // Work on copies so a packet dropped half-way changes nothing.
  const auto arkit = arkit_;
  const auto presets = presets_;
  const auto pose = headPose_;
  Outcome outcome = Outcome::Ignored;
  bool head = false;
  if (std::string why = message(data, size, 0, outcome, head); !why.empty()) {
    arkit_ = arkit;
    presets_ = presets;
    headPose_ = pose;
    return malformed(why);
  }
  DecodedPacket out;
  if (outcome == Outcome::Ignored) {
    out.status = PacketStatus::Ignored;
    return out;
  }
  if (outcome == Outcome::None) {
    out.status = PacketStatus::Incomplete;
    return out;
  }
  out.status = PacketStatus::Frame;
  out.frame.weights = arkit_;
  for (const auto& [name, value] : presets_)
    for (const auto& [k, weight] : vrmPresetMeaning(name)) out.frame.weights[k] += value * weight;
  for (double& w : out.frame.weights) w = std::clamp(w, 0.0, 1.0);
  out.frame.headPose = headPose_;
  return out;
}

std::vector<std::uint8_t> encodeVmcPacket(const LiveFrame& frame) {
  lo_bundle bundle = lo_bundle_new(LO_TT_IMMEDIATE);
  if (frame.headPose) {
    const std::array<double, 4> q = unityQuaternionFromHeadPose(*frame.headPose);
    lo_message m = lo_message_new();
    lo_message_add_string(m, "Head");
    for (int k = 0; k < 3; ++k) lo_message_add_float(m, 0.0f);  // the position: not the face's concern
    for (const double c : q) lo_message_add_float(m, static_cast<float>(c));
    lo_bundle_add_message(bundle, "/VMC/Ext/Bone/Pos", m);
  }
  const auto& names = arkitNames();
  for (int k = 0; k < kArkitWeightCount; ++k) {
    lo_message m = lo_message_new();
    lo_message_add_string(m, pascalCase(names[k]).c_str());
    lo_message_add_float(m, static_cast<float>(frame.weights[k]));
    lo_bundle_add_message(bundle, "/VMC/Ext/Blend/Val", m);
  }
  lo_bundle_add_message(bundle, "/VMC/Ext/Blend/Apply", lo_message_new());
  std::size_t size = 0;
  void* bytes = lo_bundle_serialise(bundle, nullptr, &size);
  std::vector<std::uint8_t> out(static_cast<std::uint8_t*>(bytes), static_cast<std::uint8_t*>(bytes) + size);
  std::free(bytes);
  lo_bundle_free_recursive(bundle);
  return out;
}

Vec3 headPoseFromUnityQuaternion(double x, double y, double z, double w) {
  const Mat3 R = Eigen::Quaterniond(w, x, -y, -z).normalized().toRotationMatrix();
  // R = R_z(roll) R_y(yaw) R_x(pitch) (anatomy/anatomical_face.h's headPoseRotation), inverted.
  const double d = 180.0 / M_PI;
  return Vec3(std::atan2(R(2, 1), R(2, 2)) * d, std::asin(std::clamp(-R(2, 0), -1.0, 1.0)) * d,
              std::atan2(R(1, 0), R(0, 0)) * d);
}

std::array<double, 4> unityQuaternionFromHeadPose(const Vec3& pyr) {
  const double d = M_PI / 180.0;
  const Eigen::Quaterniond q = Eigen::AngleAxisd(pyr.z() * d, Vec3::UnitZ()) *
                               Eigen::AngleAxisd(pyr.y() * d, Vec3::UnitY()) *
                               Eigen::AngleAxisd(pyr.x() * d, Vec3::UnitX());
  return {q.x(), -q.y(), -q.z(), q.w()};
}

}  // namespace myo
