// Marker targets for `myoshell fit` (fit/marker_target.h): units converted to cm, and every fault
// named with the file, line, column and key.
#include <gtest/gtest.h>

#include "myoshell/core/errors.h"
#include "myoshell/fit/marker_target.h"

namespace myo {
namespace {

std::string markerErrorOf(const std::string& text, int vertexCount = 68) {
  try {
    parseMarkerTarget(text, vertexCount, "m.json");
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(MarkerTarget, PositionsAreConvertedToCentimetresInTheFilesOrder) {
  const MarkerTarget mm = parseMarkerTarget(
      R"({"units": "mm", "note": "two", "markers": [{"vertex": 7, "position": [10, -20, 5]}, {"vertex": 2, "position": [0, 1, 2], "note": "tip"}]})",
      68);
  EXPECT_EQ(mm.unit, LengthUnit::mm);
  ASSERT_EQ(mm.vertices, (std::vector<int>{7, 2}));
  EXPECT_EQ(mm.positions.row(0), Vec3(1.0, -2.0, 0.5).transpose());
  EXPECT_EQ(mm.positions.row(1), Vec3(0.0, 0.1, 0.2).transpose());
  const MarkerTarget m = parseMarkerTarget("units: m\nmarkers:\n  - {vertex: 0, position: [0.01, 0.02, -0.5]}\n", 68);
  EXPECT_EQ(m.positions.row(0), Vec3(1.0, 2.0, -50.0).transpose());
  const MarkerTarget cm = parseMarkerTarget(R"({"units": "cm", "markers": [{"vertex": 67, "position": [1.25, 2, 3]}]})", 68);
  EXPECT_EQ(cm.positions.row(0), Vec3(1.25, 2.0, 3.0).transpose());
}

TEST(MarkerTarget, ErrorsNameTheFileLineColumnAndFault) {
  EXPECT_EQ(markerErrorOf(R"({"markers": [{"vertex": 1, "position": [0, 0, 0]}]})"),
            "m.json:1:1: key 'units': missing required key");
  EXPECT_EQ(markerErrorOf(R"({"units": "inch", "markers": [{"vertex": 1, "position": [0, 0, 0]}]})"),
            "m.json:1:11: key 'units': unknown length unit 'inch' (use cm, mm or m)");
  EXPECT_EQ(markerErrorOf(R"({"units": "cm", "markers": []})"), "m.json:1:28: key 'markers': must hold at least one marker");
  EXPECT_EQ(markerErrorOf("{\"units\": \"cm\", \"markers\": [\n  {\"vertex\": 68, \"position\": [0, 0, 0]}]}"),
            "m.json:2:14: key 'markers[0].vertex': vertex 68 is outside [0, 68) of the head");
  EXPECT_EQ(markerErrorOf(R"({"units": "cm", "markers": [{"vertex": 3, "position": [0, 0, 0]}, {"vertex": 3, "position": [1, 1, 1]}]})"),
            "m.json:1:78: key 'markers[1].vertex': vertex 3 is already placed by markers[0]");
  EXPECT_EQ(markerErrorOf(R"({"units": "cm", "markers": [{"vertex": 1.5, "position": [0, 0, 0]}]})"),
            "m.json:1:40: key 'markers[0].vertex': must be an integer ≥ 0 (got 1.5)");
  EXPECT_EQ(markerErrorOf(R"({"units": "cm", "markers": [{"vertex": 1, "position": [0, 0]}]})"),
            "m.json:1:55: key 'markers[0].position': must be three numbers [x, y, z]");
  EXPECT_EQ(markerErrorOf(R"({"units": "cm", "markers": [{"vertex": 1, "position": [0, ".5", 0]}]})"),
            "m.json:1:59: key 'markers[0].position[1]': must be a number");
  EXPECT_EQ(markerErrorOf(R"({"units": "m", "markers": [{"vertex": 1, "position": [0, 1e307, 0]}]})"),
            "m.json:1:58: key 'markers[0].position[1]': is too large (1e307)");
  EXPECT_EQ(markerErrorOf(R"({"units": "cm", "markers": [{"vertex": 1, "position": [0, 0, 0], "weight": 2}]})"),
            "m.json:1:66: key 'markers[0].weight': unknown key");
  EXPECT_EQ(markerErrorOf(R"({"units": "cm", "markers": {"vertex": 1}})"), "m.json:1:28: key 'markers': must be a list of {vertex, position}");
}

}  // namespace
}  // namespace myo
