// Fuzzes the landmark reader. Landmarks that read resolve without surprises (vertex() of every
// name they have, requireAll() only ever InputError), and landmarksToJson reads back to the same
// landmarks.
#include <climits>

#include "fuzz_common.h"
#include "myoshell/core/errors.h"
#include "myoshell/head/landmarks.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text = myo::fuzz::text(data, size);
  for (const int count : {0, 468, INT_MAX}) {
    myo::Landmarks lm;
    try {
      lm = myo::parseLandmarks(text, count, "fuzz_landmarks.json");
    } catch (const myo::InputError&) {
      continue;
    }
    FUZZ_EXPECT(lm.multipie68.empty() || lm.multipie68.size() == 68, "multipie68 size");
    for (int v : lm.multipie68) FUZZ_EXPECT(v >= 0 && v < count, "multipie68 id in range");
    for (const auto& [name, v] : lm.named) FUZZ_EXPECT(v >= 0 && v < count, "named id in range");
    for (const auto& [name, v] : lm.resolved()) {
      FUZZ_EXPECT(lm.has(name), "a resolved landmark is had");
      FUZZ_EXPECT(lm.vertex(name) == v, "resolved agrees with vertex()");
    }
    try {
      lm.requireAll();
    } catch (const myo::InputError&) {
    }
    const myo::Landmarks again = myo::parseLandmarks(myo::landmarksToJson(lm), count, "again.json");
    FUZZ_EXPECT(again.multipie68 == lm.multipie68 && again.named == lm.named, "round trip");
  }
  return 0;
}
