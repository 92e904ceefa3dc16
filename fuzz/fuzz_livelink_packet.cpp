// Fuzzes the Live Link Face packet decoder (io/live_packets.h): any bytes give a frame or a
// malformed packet with a reason, never an exception. A frame has 52 weights in [0, 1], a finite
// head pose and gaze; encoding it again and decoding gives the same weights to float precision.
#include <cmath>

#include "fuzz_common.h"
#include "myoshell/io/live_packets.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const myo::DecodedPacket p = myo::decodeLiveLinkPacket(data, size);
  if (p.status != myo::PacketStatus::Frame) {
    FUZZ_EXPECT(p.status == myo::PacketStatus::Malformed && !p.reason.empty(), "a dropped packet says why");
    return 0;
  }
  for (const double w : p.frame.weights) FUZZ_EXPECT(w >= 0 && w <= 1, "weights in [0, 1]");
  FUZZ_EXPECT(p.frame.headPose && p.frame.headPose->allFinite(), "a finite head pose");
  FUZZ_EXPECT(p.frame.gaze, "a gaze");
  for (size_t e = 0; e < 2; ++e)
    FUZZ_EXPECT(std::isfinite(p.frame.gaze->pitchDeg[e]) && std::isfinite(p.frame.gaze->yawDeg[e]), "finite gaze");
  const auto again = myo::encodeLiveLinkPacket(p.frame, {*p.senderFrame, 0.0f, 60, 1});
  const myo::DecodedPacket q = myo::decodeLiveLinkPacket(again.data(), again.size());
  FUZZ_EXPECT(q.status == myo::PacketStatus::Frame, "a re-encoded frame decodes");
  for (int k = 0; k < myo::kArkitWeightCount; ++k)
    FUZZ_EXPECT(std::fabs(q.frame.weights[k] - p.frame.weights[k]) <= 1e-6, "re-encoded weights equal");
  return 0;
}
