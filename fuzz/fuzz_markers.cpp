// Fuzzes the marker-target reader (`myoshell fit MARKERS.json`) at a few vertex counts. Markers that
// read name each vertex once, in range, at finite positions (cm); written back in cm they read the
// same again.
#include <climits>
#include <cmath>
#include <set>
#include <sstream>

#include "fuzz_common.h"
#include "myoshell/core/errors.h"
#include "myoshell/fit/marker_target.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text = myo::fuzz::text(data, size);
  for (const int count : {0, 68, 11248, INT_MAX}) {
    myo::MarkerTarget markers;
    try {
      markers = myo::parseMarkerTarget(text, count, "fuzz_markers.json");
    } catch (const myo::InputError&) {
      continue;
    }
    FUZZ_EXPECT(!markers.vertices.empty(), "at least one marker");
    FUZZ_EXPECT(markers.positions.rows() == static_cast<Eigen::Index>(markers.vertices.size()), "one position each");
    std::set<int> seen;
    std::ostringstream again;
    again.precision(17);
    again << "{\"units\": \"cm\", \"markers\": [";
    for (size_t i = 0; i < markers.vertices.size(); ++i) {
      const int v = markers.vertices[i];
      FUZZ_EXPECT(v >= 0 && v < count, "vertex in range");
      FUZZ_EXPECT(seen.insert(v).second, "each vertex once");
      FUZZ_EXPECT(markers.positions.row(static_cast<Eigen::Index>(i)).allFinite(), "finite position");
      const auto p = markers.positions.row(static_cast<Eigen::Index>(i));
      again << (i ? ", " : "") << "{\"vertex\": " << v << ", \"position\": [" << p(0) << ", " << p(1) << ", " << p(2)
            << "]}";
    }
    again << "]}";
    const myo::MarkerTarget back = myo::parseMarkerTarget(again.str(), count, "again.json");
    FUZZ_EXPECT(back.vertices == markers.vertices, "round trip: vertices");
    FUZZ_EXPECT(back.positions == markers.positions, "round trip: positions");
  }
  return 0;
}
