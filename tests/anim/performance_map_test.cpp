// From performance curves to muscle activations: the FACS map for action units, the retargeting
// map (and, for what it lacks, the shape's FACS units on its side) for ARKit weights, clamping,
// the filter, the window, and the tracks a scene gets.
#include "myoshell/anim/performance_map.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "myoshell/core/errors.h"
#include "myoshell/fit/arkit_names.h"
#include "myoshell/muscles/muscle_def.h"

namespace myo {
namespace {

std::vector<std::string> faceMuscleNames() {
  std::vector<std::string> names;
  for (const MuscleDef& d : faceMuscleDefs()) names.push_back(d.name);
  return names;
}

Performance makePerformance(PerformanceInput input, std::vector<PerformanceChannel> channels, int frames = 5,
                            double fps = 25.0) {
  Performance p;
  p.input = input;
  p.fps = fps;
  for (int f = 0; f < frames; ++f) p.times.push_back(f / fps);
  for (auto& c : channels) c.values.resize(frames, c.values.empty() ? 0.0 : c.values.back());
  p.channels = std::move(channels);
  return p;
}

double activationOf(const MappedPerformance& m, const std::string& muscle, int frame) {
  const auto it = std::find(m.muscles.begin(), m.muscles.end(), muscle);
  EXPECT_NE(it, m.muscles.end()) << muscle;
  return m.activations[it - m.muscles.begin()][frame];
}

OneEuroSettings off() {
  OneEuroSettings s;
  s.enabled = false;
  return s;
}

TEST(PerformanceMap, ActionUnitsGoThroughTheFacsMap) {
  const Performance p = makePerformance(PerformanceInput::OpenFace, {{"AU12", {0.5}},
                                                                     {"AU14", {0.25}},
                                                                     {"AU9", {0.4}},
                                                                     {"AU26", {0.7}},
                                                                     {"AU45", {0.3}}});
  const MappedPerformance m = mapPerformance(p, faceMuscleNames(), builtinFacsMap(), RetargetMap{}, off());
  EXPECT_DOUBLE_EQ(activationOf(m, "zygomaticus_major_left", 2), 0.5);
  EXPECT_DOUBLE_EQ(activationOf(m, "zygomaticus_major_right", 2), 0.5);
  EXPECT_DOUBLE_EQ(activationOf(m, "buccinator_left", 2), 0.25);
  EXPECT_DOUBLE_EQ(activationOf(m, "procerus", 2), 0.4 * 0.5);  // AU9's weight on the procerus
  EXPECT_DOUBLE_EQ(activationOf(m, "corrugator_supercilii_left", 2), 0.0);
  // AU26 (jaw drop) opens the jaw: 12° at full intensity, the hinge opening (assets/facs/au_map.json).
  ASSERT_EQ(m.jaw.size(), 5u);
  EXPECT_DOUBLE_EQ(m.jaw[2].x(), 0.7 * 12.0);
  EXPECT_DOUBLE_EQ(m.jaw[2].y(), 0.0);
  // AU45 (blink) closes the lids through the palpebral part of orbicularis oculi.
  EXPECT_DOUBLE_EQ(activationOf(m, "orbicularis_oculi_palpebral_left", 2), 0.3);
  EXPECT_TRUE(m.unmapped.empty());
  EXPECT_TRUE(m.warnings.empty());
}

TEST(PerformanceMap, ContributionsAddAndClampToOne) {
  // AU23 and AU24 both drive the mouth ring at weight 1: 0.7 + 0.6 clamps to 1.
  const Performance p = makePerformance(PerformanceInput::OpenFace, {{"AU23", {0.7}}, {"AU24", {0.6}}});
  const MappedPerformance m = mapPerformance(p, faceMuscleNames(), builtinFacsMap(), RetargetMap{}, off());
  EXPECT_DOUBLE_EQ(activationOf(m, "orbicularis_oris_upper", 0), 1.0);
}

TEST(PerformanceMap, MusclesTheModelLacksAreWarnedAboutAndLeftOut) {
  const Performance p = makePerformance(PerformanceInput::OpenFace, {{"AU12", {0.5}}, {"AU1", {0.3}}});
  const MappedPerformance m = mapPerformance(p, {"zygomaticus_major_left", "zygomaticus_major_right"},
                                             builtinFacsMap(), RetargetMap{}, off());
  EXPECT_DOUBLE_EQ(activationOf(m, "zygomaticus_major_left", 0), 0.5);
  EXPECT_EQ(m.unmapped, std::vector<std::string>{"AU1"});
  ASSERT_EQ(m.warnings.size(), 2u);
  EXPECT_EQ(m.warnings[0], "AU1 drives nothing: AU1 drives no muscle of this model");
  EXPECT_EQ(m.warnings[1],
            "the maps name muscles this model does not have, left out: frontalis_medial_left, frontalis_medial_right");
}

TEST(PerformanceMap, ArkitWeightsGoThroughTheRetargetingMap) {
  RetargetMap map;
  RetargetShape smile;
  smile.name = "mouthSmileLeft";
  smile.activations = {{"zygomaticus_major_left", 0.8}, {"risorius_left", 0.2}};
  map.shapes.push_back(smile);
  RetargetShape look;
  look.name = "eyeLookUpLeft";
  look.reachable = false;
  look.reason = "eye rotation";
  map.shapes.push_back(look);
  const Performance p = makePerformance(PerformanceInput::LiveLink, {{"mouthSmileLeft", {0.5}},
                                                                     {"browDownLeft", {0.6}},
                                                                     {"noseSneerRight", {0.4}},
                                                                     {"eyeLookUpLeft", {0.9}},
                                                                     {"mouthClose", {0.3}}});
  const MappedPerformance m = mapPerformance(p, faceMuscleNames(), builtinFacsMap(), map, off());
  EXPECT_DOUBLE_EQ(activationOf(m, "zygomaticus_major_left", 1), 0.4);
  EXPECT_DOUBLE_EQ(activationOf(m, "risorius_left", 1), 0.1);
  EXPECT_DOUBLE_EQ(activationOf(m, "zygomaticus_major_right", 1), 0.0);
  // browDownLeft is not in the map: AU4 on the subject's left only.
  EXPECT_DOUBLE_EQ(activationOf(m, "corrugator_supercilii_left", 1), 0.6);
  EXPECT_DOUBLE_EQ(activationOf(m, "depressor_supercilii_left", 1), 0.6);
  EXPECT_DOUBLE_EQ(activationOf(m, "corrugator_supercilii_right", 1), 0.0);
  // noseSneerRight: AU9 on the right. The midline procerus gets half of each sided name's weight:
  // AU4's 1 from browDownLeft and AU9's 0.5 from noseSneerRight.
  EXPECT_DOUBLE_EQ(activationOf(m, "levator_labii_superioris_alaeque_nasi_right", 1), 0.4);
  EXPECT_DOUBLE_EQ(activationOf(m, "levator_labii_superioris_alaeque_nasi_left", 1), 0.0);
  EXPECT_NEAR(activationOf(m, "procerus", 1), 0.6 * 1.0 * 0.5 + 0.4 * 0.5 * 0.5, 1e-15);
  // eyeLookUpLeft, unreachable in this map, turns the left eye up through AU63 (25° at 1).
  ASSERT_EQ(m.gaze.size(), 5u);
  EXPECT_DOUBLE_EQ(m.gaze[1].pitchDeg[1], 0.9 * 25.0);
  EXPECT_DOUBLE_EQ(m.gaze[1].pitchDeg[0], 0.0);
  EXPECT_EQ(m.unmapped, (std::vector<std::string>{"mouthClose"}));
  ASSERT_EQ(m.warnings.size(), 1u);
  EXPECT_EQ(m.warnings[0], "mouthClose drives nothing: the retargeting map has no mouthClose, and it has no FACS unit");
}

TEST(PerformanceMap, ArkitJawShapesMoveTheJawTowardsTheirSide) {
  const Performance p = makePerformance(PerformanceInput::LiveLink,
                                        {{"jawOpen", {0.5}}, {"jawLeft", {0.4}}, {"jawRight", {0.1}}, {"jawForward", {1.0}}});
  const MappedPerformance m = mapPerformance(p, faceMuscleNames(), builtinFacsMap(), RetargetMap{}, off());
  ASSERT_EQ(m.jaw.size(), 5u);
  EXPECT_DOUBLE_EQ(m.jaw[0].x(), 0.5 * 12.0);          // AU26
  EXPECT_DOUBLE_EQ(m.jaw[0].y(), 0.8);                 // AU29
  EXPECT_NEAR(m.jaw[0].z(), (0.4 - 0.1) * 1.0, 1e-15);  // AU30 left minus right
  EXPECT_TRUE(m.unmapped.empty());
  SceneDesc scene;
  scene.jawOpen = ScalarTrack({{0.0, 35.0, Interpolation::Linear}});
  addPerformanceToScene(scene, m);
  EXPECT_DOUBLE_EQ(scene.jawOpen.at(0.1), 40.0);  // 10 + 35, held at the jaw's 40° limit
  EXPECT_DOUBLE_EQ(scene.jawForward.at(0.1), 0.8);
  EXPECT_NEAR(scene.jawLateral.at(0.1), 0.3, 1e-15);
}

TEST(PerformanceMap, EveryArkitNameMapsOrIsWarnedAbout) {
  // With the shipped map and the whole face, every one of the 52 names drives muscles or is named
  // in a warning, and what drives nothing is what the model cannot make yet (eyes, jaw, air, tongue).
  std::vector<PerformanceChannel> channels;
  for (const std::string& name : arkitNames()) channels.push_back({name, {0.5}});
  const Performance p = makePerformance(PerformanceInput::MediaPipe, channels);
  const MappedPerformance m = mapPerformance(p, faceMuscleNames(), builtinFacsMap(), builtinRetargetMap(), off());
  EXPECT_EQ(m.warnings.size(), m.unmapped.size());
  for (const std::string& name : m.unmapped) {
    const bool expected = name.rfind("eyeLook", 0) == 0 || name.rfind("jaw", 0) == 0 || name == "eyeBlinkLeft" ||
                          name == "eyeBlinkRight" || name == "eyeWideLeft" || name == "eyeWideRight" ||
                          name == "cheekPuff" || name == "tongueOut" || name == "mouthClose" || name == "mouthLeft" ||
                          name == "mouthRight";
    EXPECT_TRUE(expected) << name << " drives nothing";
  }
  EXPECT_LE(m.unmapped.size(), 24u);
}

TEST(PerformanceMap, TheFilterSmoothsTheInputCurves) {
  Performance p = makePerformance(PerformanceInput::OpenFace, {{"AU12", {0.0}}}, 10);
  for (int f = 5; f < 10; ++f) p.channels[0].values[f] = 1.0;  // a step
  const MappedPerformance raw = mapPerformance(p, faceMuscleNames(), builtinFacsMap(), RetargetMap{}, off());
  const MappedPerformance smooth = mapPerformance(p, faceMuscleNames(), builtinFacsMap(), RetargetMap{}, OneEuroSettings{});
  EXPECT_DOUBLE_EQ(activationOf(raw, "zygomaticus_major_left", 5), 1.0);
  const double a5 = activationOf(smooth, "zygomaticus_major_left", 5);
  EXPECT_GT(a5, 0.0);
  EXPECT_LT(a5, 1.0);
  EXPECT_GT(activationOf(smooth, "zygomaticus_major_left", 9), a5);
}

TEST(PerformanceMap, CropKeepsTheWindowFromZero) {
  const Performance p = makePerformance(PerformanceInput::OpenFace, {{"AU12", {0.3}}}, 50, 25.0);
  const Performance c = cropPerformance(p, 0.4, 1.0, "x.csv");
  ASSERT_EQ(c.times.size(), 16u);  // frames 10 … 25
  EXPECT_DOUBLE_EQ(c.times.front(), 0.0);
  EXPECT_NEAR(c.times.back(), 0.6, 1e-12);
  EXPECT_EQ(c.channels[0].values.size(), 16u);
  try {
    cropPerformance(p, 1.95, -1.0, "x.csv");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "x.csv: the window 1.95–end s holds 1 frame(s) of the performance (1.96 s long); it needs two");
  }
}

TEST(PerformanceMap, TheSceneGetsTracksAndItsOwnKeysAdd) {
  Performance p = makePerformance(PerformanceInput::OpenFace, {{"AU12", {0.4}}}, 26, 25.0);
  p.headPose.assign(26, Vec3(10.0, 0.0, 0.0));
  const MappedPerformance m = mapPerformance(p, faceMuscleNames(), builtinFacsMap(), RetargetMap{}, off());
  SceneDesc scene;
  scene.activations["zygomaticus_major_left"] =
      ScalarTrack({{0.0, 0.0, Interpolation::Linear}, {0.5, 0.8, Interpolation::Linear}});
  addPerformanceToScene(scene, m);
  EXPECT_DOUBLE_EQ(scene.duration, 1.0);
  EXPECT_DOUBLE_EQ(scene.fps, 25.0);
  const ScalarTrack& left = scene.activations.at("zygomaticus_major_left");
  EXPECT_NEAR(left.at(0.0), 0.4, 1e-12);
  EXPECT_NEAR(left.at(0.25), 0.8, 1e-12);  // 0.4 + 0.4
  EXPECT_NEAR(left.at(0.9), 1.0, 1e-12);   // 0.4 + 0.8 clamped
  EXPECT_NEAR(scene.activations.at("zygomaticus_major_right").at(0.9), 0.4, 1e-12);
  EXPECT_FALSE(scene.activations.count("buccinator_left"));  // driven by nothing: no track
  ASSERT_FALSE(scene.headPose.empty());
  EXPECT_NEAR(scene.headPose.at(0.5).angularDistance(Eigen::Quaterniond(Eigen::AngleAxisd(10.0 * M_PI / 180.0, Vec3::UnitX()))),
              0.0, 1e-9);
}

}  // namespace
}  // namespace myo

namespace myo {
namespace {

// A live take's replay (performance.interpolation step): every played curve holds each frame's
// value until the next frame, where linear goes straight between them.
TEST(PerformanceMap, StepInterpolationHoldsEachFrameUntilTheNext) {
  MappedPerformance m;
  m.times = {0.0, 0.1, 0.2};
  m.fps = 10.0;
  m.muscles = {"zygomaticus_major_left"};
  m.activations = {{0.2, 0.6, 0.4}};
  m.jaw = {Vec3(2.0, 0.0, 0.0), Vec3(10.0, 0.0, 0.0), Vec3(4.0, 0.0, 0.0)};
  m.headPose = {Vec3(0.0, 0.0, 0.0), Vec3(0.0, 20.0, 0.0), Vec3(0.0, 10.0, 0.0)};
  SceneDesc step, linear;
  addPerformanceToScene(step, m, Interpolation::Step);
  addPerformanceToScene(linear, m, Interpolation::Linear);
  const ScalarTrack& a = step.activations.at("zygomaticus_major_left");
  EXPECT_DOUBLE_EQ(a.at(0.0), 0.2);
  EXPECT_DOUBLE_EQ(a.at(0.0999), 0.2);
  EXPECT_DOUBLE_EQ(a.at(0.1), 0.6);
  EXPECT_DOUBLE_EQ(a.at(0.15), 0.6);
  EXPECT_DOUBLE_EQ(a.at(0.3), 0.4);  // after the last frame, held
  EXPECT_NEAR(linear.activations.at("zygomaticus_major_left").at(0.05), 0.4, 1e-12);
  EXPECT_DOUBLE_EQ(step.jawOpen.at(0.19), 10.0);
  EXPECT_NEAR(linear.jawOpen.at(0.15), 7.0, 1e-12);
  // The head: the rotation of frame 1 held until frame 2 (20° about the face's up axis).
  EXPECT_TRUE(step.headPose.at(0.15).isApprox(step.headPose.at(0.1), 1e-12));
  EXPECT_FALSE(linear.headPose.at(0.15).isApprox(linear.headPose.at(0.1), 1e-6));
  EXPECT_EQ(step.duration, 0.2);
  EXPECT_EQ(step.fps, 10.0);
}

}  // namespace
}  // namespace myo
