// Fuzzes the attachment-override reader (scene key skin.attachment) at a few vertex counts. Overrides
// that read name each vertex once, in range, with a finite k_att > 0; written back as one entry per
// vertex they read the same again.
#include <climits>
#include <cmath>
#include <set>
#include <sstream>

#include "fuzz_common.h"
#include "myoshell/core/errors.h"
#include "myoshell/muscles/attachment_overrides.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text = myo::fuzz::text(data, size);
  for (const int count : {0, 3, 468, INT_MAX}) {
    std::vector<myo::AttachmentOverride> overrides;
    try {
      overrides = myo::parseAttachmentOverrides(text, count, "fuzz_attachment.json");
    } catch (const myo::InputError&) {
      continue;
    }
    std::set<int> seen;
    std::ostringstream again;
    again.precision(17);
    again << "{\"overrides\": [";
    for (size_t i = 0; i < overrides.size(); ++i) {
      const myo::AttachmentOverride& o = overrides[i];
      FUZZ_EXPECT(o.vertex >= 0 && o.vertex < count, "vertex in range");
      FUZZ_EXPECT(seen.insert(o.vertex).second, "each vertex once");
      FUZZ_EXPECT(std::isfinite(o.stiffness) && o.stiffness > 0, "k_att finite and > 0");
      again << (i ? ", " : "") << "{\"vertices\": [" << o.vertex << "], \"k_att\": " << o.stiffness << "}";
    }
    again << "]}";
    const std::vector<myo::AttachmentOverride> back = myo::parseAttachmentOverrides(again.str(), count, "again.json");
    FUZZ_EXPECT(back.size() == overrides.size(), "round trip: size");
    for (size_t i = 0; i < back.size(); ++i)
      FUZZ_EXPECT(back[i].vertex == overrides[i].vertex && back[i].stiffness == overrides[i].stiffness,
                  "round trip: entries");
  }
  return 0;
}
