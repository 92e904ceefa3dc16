// Fuzzes the vertex-set (pin) reader at a few vertex counts. A set that reads is sorted, unique
// and in range; reading it again from its own JSON list gives the same set.
#include <climits>

#include "fuzz_common.h"
#include "myoshell/core/errors.h"
#include "myoshell/mesh/vertex_set.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text = myo::fuzz::text(data, size);
  for (const int count : {0, 3, 7152, INT_MAX}) {
    std::vector<int> set;
    try {
      set = myo::parseVertexSet(text, count, "fuzz_pins.json");
    } catch (const myo::InputError&) {
      continue;
    }
    for (size_t i = 0; i < set.size(); ++i) {
      FUZZ_EXPECT(set[i] >= 0 && set[i] < count, "index in range");
      FUZZ_EXPECT(i == 0 || set[i - 1] < set[i], "sorted and unique");
    }
    std::string again = "[";
    for (size_t i = 0; i < set.size(); ++i) again += (i ? "," : "") + std::to_string(set[i]);
    again += "]";
    FUZZ_EXPECT(myo::parseVertexSet(again, count, "again.json") == set, "round trip");
  }
  return 0;
}
