// The one path from ARKit names and action units to muscles (fit/facs_route.h), derived map entries,
// and what a map records (source, library: fit/retarget_map.h).
#include "myoshell/fit/facs_route.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <map>

#include "myoshell/anim/performance_map.h"
#include "myoshell/core/errors.h"
#include "myoshell/fit/arkit_names.h"
#include "myoshell/muscles/muscle_def.h"

namespace myo {
namespace {

std::vector<std::string> faceNames() {
  std::vector<std::string> names;
  for (const MuscleDef& d : faceMuscleDefs()) names.push_back(d.name);
  return names;
}

std::map<std::string, double> asMap(const NamedValues& v) { return {v.begin(), v.end()}; }

TEST(FacsRoute, ASidedShapeDrivesItsSideFullyAndTheMidlineAtHalfWeight) {
  EXPECT_EQ(facsSideShare("corrugator_supercilii_left", "left"), 1.0);
  EXPECT_EQ(facsSideShare("corrugator_supercilii_right", "left"), 0.0);
  EXPECT_EQ(facsSideShare("procerus", "left"), 0.5);
  EXPECT_EQ(facsSideShare("corrugator_supercilii_right", ""), 1.0);
  // browDownLeft shows AU4 (brow lowerer) on the subject's left: the FACS map's AU4 muscles there.
  const std::optional<RetargetShape> s = derivedRetargetShape(builtinFacsMap(), "browDown_L", faceNames());
  ASSERT_TRUE(s.has_value());
  EXPECT_EQ(s->name, "browDownLeft");
  EXPECT_EQ(s->source, RetargetSource::Derived);
  const FacsEntry* au4 = builtinFacsMap().find(4);
  ASSERT_NE(au4, nullptr);
  std::map<std::string, double> expected;
  for (const auto& [muscle, w] : au4->muscles)
    if (facsSideShare(muscle, "left") > 0) expected[muscle] = w * facsSideShare(muscle, "left");
  EXPECT_EQ(asMap(s->activations), expected);
  for (const auto& [muscle, w] : s->activations) EXPECT_THAT(muscle, ::testing::Not(::testing::EndsWith("_right")));
  EXPECT_TRUE(s->jaw.empty());
}

TEST(FacsRoute, OnlyTheGivenMusclesAreKeptAndANameWithNothingToDriveGivesNoEntry) {
  // The built-in library has the corrugator but no depressor supercilii or procerus.
  const std::optional<RetargetShape> s =
      derivedRetargetShape(builtinFacsMap(), "browDownLeft", {"corrugator_supercilii_left", "corrugator_supercilii_right"});
  ASSERT_TRUE(s.has_value());
  EXPECT_EQ(asMap(s->activations), (std::map<std::string, double>{{"corrugator_supercilii_left", 1.0}}));
  EXPECT_FALSE(derivedRetargetShape(builtinFacsMap(), "browDownLeft", {"zygomaticus_major_left"}).has_value());
  // mouthLeft has no FACS unit; tongueOut's (AU19) is not in the map: nothing to derive.
  EXPECT_FALSE(derivedRetargetShape(builtinFacsMap(), "mouthLeft", faceNames()).has_value());
  EXPECT_FALSE(derivedRetargetShape(builtinFacsMap(), "tongueOut", faceNames()).has_value());
  std::vector<int> idle;
  EXPECT_TRUE(facsDriveOfArkitName(builtinFacsMap(), "tongueOut", &idle).empty());
  EXPECT_EQ(idle, std::vector<int>{19});
}

TEST(FacsRoute, ADerivedEntryDrivesAPerformanceExactlyAsTheFacsRouteDoes) {
  // A Live Link take of every ARKit name the FACS map can make, ramping: mapped once through a map
  // without those names (drive's FACS route) and once through a map of their derived entries.
  Performance p;
  p.input = PerformanceInput::LiveLink;
  p.times = {0.0, 1.0 / 60, 2.0 / 60, 3.0 / 60};
  p.fps = 60;
  RetargetMap derived;
  RetargetMap empty;
  empty.shapes.push_back({"tongueOut", false, "no tongue", "", {}, {}, std::nullopt});
  int k = 0;
  for (const std::string& name : arkitNames()) {
    std::optional<RetargetShape> s = derivedRetargetShape(builtinFacsMap(), name, faceNames());
    if (!s) continue;
    derived.shapes.push_back(*s);
    const double peak = 0.3 + 0.01 * (k++ % 7);
    p.channels.push_back({name, {0.0, peak / 3, 2 * peak / 3, peak}});
  }
  // All but tongueOut (AU19), which the FACS map has nothing for, and mouthClose, mouthLeft,
  // mouthRight, which have no FACS unit. The eyes' turns (AU61–64) are entries with a gaze and no
  // muscle, cheekPuff (AU34) air and no muscle: a performance plays neither gaze nor air yet,
  // so both ways give the same muscles.
  ASSERT_EQ(derived.shapes.size(), 52u - 4u);
  OneEuroSettings filter;
  filter.enabled = false;
  const MappedPerformance viaFacs = mapPerformance(p, faceNames(), builtinFacsMap(), empty, filter);
  const MappedPerformance viaMap = mapPerformance(p, faceNames(), builtinFacsMap(), derived, filter);
  ASSERT_EQ(viaFacs.activations.size(), viaMap.activations.size());
  double largest = 0.0;
  for (size_t m = 0; m < viaMap.activations.size(); ++m)
    for (size_t f = 0; f < p.times.size(); ++f) {
      EXPECT_NEAR(viaFacs.activations[m][f], viaMap.activations[m][f], 1e-12) << viaMap.muscles[m] << " frame " << f;
      largest = std::max(largest, viaMap.activations[m][f]);
    }
  EXPECT_GT(largest, 0.25);  // the take moves the face
  ASSERT_EQ(viaFacs.jaw.size(), viaMap.jaw.size());
  for (size_t f = 0; f < viaMap.jaw.size(); ++f) EXPECT_LT((viaFacs.jaw[f] - viaMap.jaw[f]).norm(), 1e-12);
}

TEST(RetargetMapSource, SourceAndLibraryRoundTripAndBadValuesAreNamed) {
  const std::string text = R"({"format": "myoshell-retarget-map", "version": 1, "library": "face",
  "shapes": [
    {"name": "mouthSmileLeft", "source": "fitted", "activations": {"zygomaticus_major_left": 0.9}},
    {"name": "browDownLeft", "source": "derived", "activations": {"corrugator_supercilii_left": 1}},
    {"name": "tongueOut", "reachable": false, "reason": "no tongue"}]})";
  const RetargetMap map = parseRetargetMap(text, "m.json");
  EXPECT_EQ(map.library, "face");
  EXPECT_EQ(map.shapes[0].source, RetargetSource::Fitted);
  EXPECT_EQ(map.shapes[1].source, RetargetSource::Derived);
  const RetargetMap again = parseRetargetMap(serialiseRetargetMap(map), "again.json");
  EXPECT_EQ(again.library, "face");
  EXPECT_EQ(again.shapes[1].source, RetargetSource::Derived);
  EXPECT_EQ(serialiseRetargetMap(again), serialiseRetargetMap(map));

  auto errorOf = [](const std::string& t) {
    try {
      parseRetargetMap(t, "bad.json");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const std::string head = R"({"format": "myoshell-retarget-map", "version": 1, "shapes": [)";
  EXPECT_THAT(errorOf(head + R"({"name": "mouthSmileLeft", "source": "guessed", "activations": {}}]})"),
              ::testing::HasSubstr("must be \"fitted\" or \"derived\" (got \"guessed\")"));
  EXPECT_THAT(errorOf(head + R"({"name": "tongueOut", "reachable": false, "reason": "r", "source": "derived"}]})"),
              ::testing::HasSubstr("an unreachable shape has no source"));
  EXPECT_THAT(errorOf(head + R"({"name": "jawOpen", "activations": {}},
      {"name": "mouthClose", "corrective_of": "jawOpen", "source": "derived", "activations": {}}]})"),
              ::testing::HasSubstr("a corrective is fitted on its base's shape, not derived"));
  EXPECT_THAT(errorOf(R"({"format": "myoshell-retarget-map", "version": 1, "library": "",
      "shapes": [{"name": "jawOpen", "activations": {}}]})"),
              ::testing::HasSubstr("must name the muscle library"));
}

}  // namespace
}  // namespace myo
