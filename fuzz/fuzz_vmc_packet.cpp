// Fuzzes the VMC (OSC) packet decoder (io/live_packets.h), fed the input twice so the values kept
// between packets are exercised: any bytes give a frame, nothing yet, an ignored packet or a
// malformed one with a reason, never an exception. A frame has 52 weights in [0, 1] and a finite
// head pose when it has one; a malformed packet changes nothing the next Apply shows.
#include <cmath>

#include "fuzz_common.h"
#include "myoshell/io/live_packets.h"

namespace {

const std::uint8_t kApply[] = {'/', 'V', 'M', 'C', '/', 'E', 'x', 't', '/', 'B', 'l', 'e', 'n', 'd',
                               '/', 'A', 'p', 'p', 'l', 'y', 0, 0, 0, 0, ',', 0, 0, 0};

void check(const myo::DecodedPacket& p) {
  if (p.status == myo::PacketStatus::Malformed) FUZZ_EXPECT(!p.reason.empty(), "a dropped packet says why");
  if (p.status != myo::PacketStatus::Frame) return;
  for (const double w : p.frame.weights) FUZZ_EXPECT(w >= 0 && w <= 1, "weights in [0, 1]");
  FUZZ_EXPECT(!p.frame.headPose || p.frame.headPose->allFinite(), "a finite head pose");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  myo::VmcDecoder decoder;
  const myo::DecodedPacket before = decoder.decode(kApply, sizeof kApply);
  const myo::DecodedPacket first = decoder.decode(data, size);
  check(first);
  check(decoder.decode(data, size));
  if (first.status == myo::PacketStatus::Malformed) {
    myo::VmcDecoder fresh;
    fresh.decode(data, size);
    const myo::DecodedPacket after = fresh.decode(kApply, sizeof kApply);
    FUZZ_EXPECT(after.frame.weights == before.frame.weights && !after.frame.headPose, "a malformed packet changes nothing");
  }
  return 0;
}
