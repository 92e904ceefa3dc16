// Retargeting maps (fit/retarget_map.h): a map reads back to itself, ICT spellings become ARKit's,
// a corrective's total is its base's plus its difference, the unreachable list is the shipped one,
// and every fault of a map file is refused with file:line:col and the fault.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "myoshell/core/errors.h"
#include "myoshell/fit/arkit_names.h"
#include "myoshell/fit/retarget_map.h"

namespace myo {
namespace {

const std::string kHead = R"({"format": "myoshell-retarget-map", "version": 1, )";

RetargetMap sampleMap() {
  RetargetMap map;
  map.rig = "ict_arkit_rig.glb";
  map.head = "ict";
  map.note = "made by hand";
  RetargetShape jaw{"jawOpen", true, "", "", {{"depressor_labii_inferioris_left", 0.5}}, {}, RetargetFitFigures{0.5, 0.25, 3.0, 9.5}};
  RetargetShape close{"mouthClose", true, "", "jawOpen", {{"depressor_labii_inferioris_left", -0.25}, {"zygomaticus_major_left", 0.125}}, {}, std::nullopt};
  RetargetShape smile{"mouthSmileLeft", true, "", "", {{"zygomaticus_major_left", 0.1 + 0.2}}, {}, RetargetFitFigures{0.8125, 0.75, 1.5, 4.0}};
  RetargetShape look{"eyeLookInLeft", false, "eye rotation", "", {}, {}, std::nullopt};
  map.shapes = {look, jaw, close, smile};
  return map;
}

TEST(RetargetMap, ReadsBackToItselfWithEveryNumberExact) {
  const RetargetMap map = sampleMap();
  const std::string text = serialiseRetargetMap(map);
  const RetargetMap back = parseRetargetMap(text, "map.json");
  EXPECT_EQ(serialiseRetargetMap(back), text);
  ASSERT_EQ(back.shapes.size(), 4u);
  EXPECT_EQ(back.rig, "ict_arkit_rig.glb");
  EXPECT_EQ(back.shapes[3].activations[0].second, 0.1 + 0.2);  // 17 digits: bit for bit
  EXPECT_FALSE(back.shapes[0].reachable);
  EXPECT_EQ(back.shapes[0].reason, "eye rotation");
  ASSERT_TRUE(back.shapes[1].fit.has_value());
  EXPECT_EQ(back.shapes[1].fit->maxMm, 9.5);
  EXPECT_EQ(back.muscleNames(), (std::vector<std::string>{"depressor_labii_inferioris_left", "zygomaticus_major_left"}));
}

TEST(RetargetMap, IctSpellingsBecomeArkitNamesAndCorrectivesAddTheirBase) {
  const RetargetMap map = parseRetargetMap(
      kHead + R"("shapes": [{"name": "jawOpen", "activations": {"a": 0.5, "b": 0.25}},
                             {"name": "mouthSmile_L", "activations": {"a": 1}},
                             {"name": "mouthClose", "corrective_of": "jawOpen", "activations": {"a": -0.5, "c": 0.75}}]})",
      "map.json");
  EXPECT_EQ(map.shapes[1].name, "mouthSmileLeft");
  EXPECT_EQ(map.find("mouthSmile_L"), &map.shapes[1]);
  EXPECT_EQ(map.find("mouthSmileLeft"), &map.shapes[1]);
  EXPECT_EQ(map.find("mouthFrownLeft"), nullptr);
  EXPECT_EQ(map.find("no such name"), nullptr);
  EXPECT_EQ(map.totalActivations(map.shapes[2]), (NamedValues{{"a", 0.0}, {"c", 0.75}, {"b", 0.25}}));
  EXPECT_EQ(map.totalActivations(map.shapes[1]), (NamedValues{{"a", 1.0}}));
}

TEST(RetargetMap, TheOnlyUnreachableShapeIsTheTongue) {
  std::vector<std::string> names;
  for (const auto& [name, reason] : unreachableArkitShapes()) {
    names.push_back(name);
    EXPECT_FALSE(reason.empty()) << name;
  }
  // The eyes' turns (their lids follow the gaze: docs/eyelids.md) and cheekPuff (air in the mouth)
  // are derived, not unreachable.
  EXPECT_EQ(names, (std::vector<std::string>{"tongueOut"}));
  EXPECT_TRUE(unreachableReason("tongueOut").has_value());
  EXPECT_EQ(unreachableReason("cheekPuff_L"), unreachableReason("cheekPuff"));  // ICT's half names the whole
  EXPECT_FALSE(unreachableReason("mouthSmile_L").has_value());
  EXPECT_FALSE(unreachableReason("jawOpen").has_value());  // the jaw is fitted: nothing else is excluded
}

std::string mapError(const std::string& text, const std::vector<std::string>& muscles = {}) {
  try {
    parseRetargetMap(text, "map.json", muscles);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

TEST(RetargetMap, AGazeReadsBackAndABadOneIsNamed) {
  const std::string text = kHead + R"("shapes": [{"name": "eyeLookUpLeft", "source": "derived", "activations": {}, )"
                                   R"("gaze": {"left_pitch": 25, "left_yaw": -1.5}}]})";
  const RetargetMap map = parseRetargetMap(text, "map.json");
  ASSERT_EQ(map.shapes.size(), 1u);
  EXPECT_EQ(map.shapes[0].gaze, (NamedValues{{"left_pitch", 25.0}, {"left_yaw", -1.5}}));
  EXPECT_EQ(parseRetargetMap(serialiseRetargetMap(map), "back.json").shapes[0].gaze, map.shapes[0].gaze);
  // The air in the mouth reads back too, and more than 10 kPa is refused.
  const RetargetMap puff = parseRetargetMap(kHead + R"("shapes": [{"name": "cheekPuff", "source": "derived", )"
                                                    R"("activations": {}, "mouth_pressure_kpa": 2.5}]})", "map.json");
  EXPECT_EQ(puff.shapes[0].mouthPressureKpa, 2.5);
  EXPECT_EQ(parseRetargetMap(serialiseRetargetMap(puff), "back.json").shapes[0].mouthPressureKpa, 2.5);
  EXPECT_THAT(mapError(kHead + R"("shapes": [{"name": "cheekPuff", "mouth_pressure_kpa": 12}]})"),
              ::testing::HasSubstr("key 'shapes[0].mouth_pressure_kpa': must lie in [0, 10] (got 12)"));
  EXPECT_EQ(mapError(kHead + R"("shapes": [{"name": "eyeLookUpLeft", "gaze": {"left_roll": 5}}]})"),
            "map.json:1:97: key 'shapes[0].gaze.left_roll': 'left_roll' is not left_pitch, left_yaw, right_pitch or right_yaw");
  EXPECT_EQ(mapError(kHead + R"("shapes": [{"name": "eyeLookUpLeft", "gaze": {"left_pitch": 60}}]})"),
            "map.json:1:111: key 'shapes[0].gaze.left_pitch': turn 60 degrees is outside [-45, 45]");
  EXPECT_EQ(mapError(kHead + R"("shapes": [{"name": "eyeLookUpLeft", "reachable": false, "reason": "r", "gaze": {"left_pitch": 5}}]})"),
            "map.json:1:131: key 'shapes[0].gaze': an unreachable shape has no activations, jaw, gaze, air or base");
}

TEST(RetargetMap, EveryFaultIsRefusedWithItsPlaceAndWhatIsWrong) {
  EXPECT_EQ(mapError(R"({"format": "x", "version": 1, "shapes": []})"),
            "map.json:1:12: key 'format': must be \"myoshell-retarget-map\" (got \"x\")");
  EXPECT_EQ(mapError(R"({"format": "myoshell-retarget-map", "version": 2, "shapes": []})"),
            "map.json:1:48: key 'version': this Myoshell reads version 1");
  EXPECT_EQ(mapError(kHead + R"("shapes": []})"), "map.json:1:61: key 'shapes': must hold at least one shape");
  EXPECT_EQ(mapError(kHead + R"("shapes": [{"name": "mouthSmil_L", "activations": {}}]})"),
            "map.json:1:71: key 'shapes[0].name': unknown blendshape name 'mouthSmil_L' (did you mean mouthSmile_L, "
            "mouthSmile_R?)");
  EXPECT_EQ(mapError(kHead + R"("shapes": [{"name": "mouthSmile_L"}, {"name": "mouthSmileLeft"}]})"),
            "map.json:1:97: key 'shapes[1].name': 'mouthSmileLeft' is mouthSmileLeft, already given by shapes[0]");
  EXPECT_EQ(mapError(kHead + R"("shapes": [{"name": "jawOpen", "activations": {"a": 1.5}}]})"),
            "map.json:1:103: key 'shapes[0].activations.a': activation 1.5 is outside [0, 1]");
  EXPECT_EQ(mapError(kHead + R"("shapes": [{"name": "jawOpen", "activations": {"a": 0.5}}, {"name": "mouthClose", )"
                          R"("corrective_of": "jawOpen", "activations": {"a": -0.75}}]})"),
            "map.json:1:176: key 'shapes[1].activations': with its base jawOpen, a reaches -0.250000, outside [0, 1]");
  EXPECT_EQ(mapError(kHead + R"("shapes": [{"name": "mouthClose", "corrective_of": "jawOpen", "activations": {}}]})"),
            "map.json:1:102: key 'shapes[0].corrective_of': the base jawOpen must be a reachable shape of the map that "
            "is not itself a corrective");
  EXPECT_EQ(mapError(kHead + R"("shapes": [{"name": "eyeLookIn_L", "reachable": false}]})"),
            "map.json:1:62: key 'shapes[0].reason': an unreachable shape needs a reason (why muscles cannot make it)");
  EXPECT_EQ(mapError(kHead + R"("shapes": [{"name": "eyeLookIn_L", "reachable": false, "reason": "eyes", "activations": {"a": 0.5}}]})"),
            "map.json:1:139: key 'shapes[0].activations': an unreachable shape has no activations, jaw, gaze, air or base");
  EXPECT_EQ(mapError(kHead + R"("shapes": [{"name": "jawOpen", "activations": {"frontalis": 0.5}}]})", {"a", "b"}),
            "map.json:1:98: key 'shapes[0].activations.frontalis': unknown muscle 'frontalis' (the model's muscles: a, b)");
  EXPECT_EQ(mapError(kHead + R"("shapes": [{"name": "jawOpen", "weight": 1}]})"),
            "map.json:1:82: key 'shapes[0].weight': unknown key");
  EXPECT_EQ(mapError(kHead + R"("shapes": [{"name": "jawOpen", "jaw": {"open": "wide"}}]})"),
            "map.json:1:98: key 'shapes[0].jaw.open': must be a number");
}

}  // namespace
}  // namespace myo
