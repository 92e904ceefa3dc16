// The eyes' turn in a performance (docs/performance_input.md, docs/eyelids.md): read from OpenFace's
// gaze_angle_x/y and Live Link's eye angles with their documented signs, turned into the head by the
// head's pose, bridged over dropped frames, filtered, clamped, the angles winning over the eyeLook*
// curves, and the tracks a scene gets (timeline.gaze: scene_gaze_test.cpp).
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "myoshell/anatomy/anatomical_face.h"  // headPoseRotation
#include "myoshell/anim/performance.h"
#include "myoshell/anim/performance_map.h"
#include "myoshell/core/errors.h"
#include "myoshell/io/performance_file.h"
#include "myoshell/muscles/muscle_def.h"
#include "support/test_data.h"

namespace myo {
namespace {

constexpr double kDeg = 180.0 / M_PI;

std::string gazeErrorOf(const std::string& text, const std::string& name = "p.csv") {
  try {
    parsePerformance(text, name);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

OneEuroSettings gazeFilterOff() {
  OneEuroSettings s;
  s.enabled = false;
  return s;
}

std::vector<std::string> gazeMuscleNames() {
  std::vector<std::string> names;
  for (const MuscleDef& d : faceMuscleDefs()) names.push_back(d.name);
  return names;
}

// ---- OpenFace ---------------------------------------------------------------------------------

// OpenFace's angles are atan2(g_x, −g_z) and atan2(g_y, −g_z) of the camera's gaze vector (y down):
// gaze_angle_y < 0 looks up, gaze_angle_x > 0 towards the image's right, the subject's left. Without
// a head pose the eyes' pitch is −gaze_angle_y and their yaw gaze_angle_x, both eyes alike.
TEST(PerformanceGaze, OpenFaceGazeAnglesTurnBothEyesWithTheirSigns) {
  const Performance p = parsePerformance(
      "timestamp,gaze_angle_x,gaze_angle_y,AU12_r\n0,0,0,0\n0.04,0.2,-0.3,0\n0.08,-0.1,0.25,0\n", "g.csv");
  ASSERT_EQ(p.gaze.size(), 3u);
  EXPECT_TRUE(p.gaze[0].isZero());
  for (size_t e = 0; e < 2; ++e) {
    EXPECT_NEAR(p.gaze[1].pitchDeg[e], 0.3 * kDeg, 1e-9);  // looking up
    EXPECT_NEAR(p.gaze[1].yawDeg[e], 0.2 * kDeg, 1e-9);    // towards the subject's left
    EXPECT_NEAR(p.gaze[2].pitchDeg[e], -0.25 * kDeg, 1e-9);
    EXPECT_NEAR(p.gaze[2].yawDeg[e], -0.1 * kDeg, 1e-9);
  }
  EXPECT_TRUE(p.warnings.empty()) << p.warnings.front();
  // A file without the columns has no gaze.
  EXPECT_TRUE(parsePerformance("timestamp,AU12_r\n0,0\n0.1,0\n").gaze.empty());
}

// The angles are the camera's: a face pitched down by 10° (pose_Rx > 0) that looks into the camera
// (gaze 0) has its eyes turned up by 10° in the head; a face turned to the subject's right by 0.2 rad
// (pose_Ry > 0) looking into the camera has them turned towards its left. In general the eyes'
// direction in the head, turned by the head, is the camera's gaze direction.
TEST(PerformanceGaze, OpenFaceGazeIsTurnedIntoTheHeadByItsPose) {
  std::ostringstream down;
  down.precision(17);
  down << 10.0 / kDeg;
  const Performance p = parsePerformance(
      "timestamp,gaze_angle_x,gaze_angle_y,pose_Rx,pose_Ry,pose_Rz,AU12_r\n"
      "0,0,0," + down.str() + ",0,0,0\n"
      "0.04,0,0,0,0.2,0,0\n"
      "0.08,0.15,0.1,0.1,-0.2,0.3,0\n",
      "g.csv");
  ASSERT_EQ(p.gaze.size(), 3u);
  EXPECT_NEAR(p.gaze[0].pitchDeg[0], 10.0, 1e-9);
  EXPECT_NEAR(p.gaze[0].yawDeg[0], 0.0, 1e-9);
  EXPECT_NEAR(p.gaze[1].yawDeg[1], 0.2 * kDeg, 1e-6);
  EXPECT_NEAR(p.gaze[1].pitchDeg[1], 0.0, 1e-9);
  // Frame 2: the eye's direction (tan yaw, tan pitch, 1) turned by the head (face frame) is the
  // camera's (tan x, −tan y, 1), OpenFace's camera y pointing down.
  const Mat3 H = headPoseRotation(p.headPose[2]).toRotationMatrix();
  const Vec3 inHead(std::tan(p.gaze[2].yawDeg[0] / kDeg), std::tan(p.gaze[2].pitchDeg[0] / kDeg), 1.0);
  const Vec3 camera(std::tan(0.15), -std::tan(0.1), 1.0);
  EXPECT_TRUE((H * inHead).normalized().isApprox(camera.normalized(), 1e-9)) << (H * inHead).normalized().transpose();
}

// Low-confidence frames are bridged as every channel is: the gaze too, linearly in time.
TEST(PerformanceGaze, DroppedFramesBridgeTheGaze) {
  const Performance p = parsePerformance(
      "timestamp,confidence,success,gaze_angle_x,gaze_angle_y,AU12_r\n"
      "0,0.98,1,0,0.2,0\n0.04,0.3,1,0.9,-0.9,0\n0.08,0.98,1,0,-0.2,0\n0.12,0.98,1,,0.1,0\n",
      "g.csv");
  ASSERT_EQ(p.gaze.size(), 3u);  // the last, with an empty gaze cell, is trimmed
  EXPECT_EQ(p.droppedFrames, 2);
  EXPECT_NEAR(p.gaze[1].pitchDeg[0], 0.0, 1e-12);  // between −0.2·deg and 0.2·deg, not the 0.9 written
  EXPECT_NEAR(p.gaze[1].yawDeg[1], 0.0, 1e-12);
}

TEST(PerformanceGaze, OpenFaceGazeErrorsNameTheFileLineAndColumn) {
  EXPECT_EQ(gazeErrorOf("timestamp,gaze_angle_x,AU12_r\n0,0,0\n"),
            "p.csv:1: missing required column 'gaze_angle_y' (the gaze needs gaze_angle_x and gaze_angle_y)");
  EXPECT_EQ(gazeErrorOf("timestamp,gaze_angle_y,AU12_r\n0,0,0\n"),
            "p.csv:1: missing required column 'gaze_angle_x' (the gaze needs gaze_angle_x and gaze_angle_y)");
  EXPECT_EQ(gazeErrorOf("timestamp,gaze_angle_x,gaze_angle_y,AU12_r\n0,0,0,0\n0.04,0,nan,0\n"),
            "p.csv:3: non-finite number 'nan' in column 'gaze_angle_y'");
  EXPECT_EQ(gazeErrorOf("timestamp,gaze_angle_x,gaze_angle_y,AU12_r\n0,inf,0,0\n"),
            "p.csv:2: non-finite number 'inf' in column 'gaze_angle_x'");
  EXPECT_EQ(gazeErrorOf("timestamp,gaze_angle_x,gaze_angle_y,AU12_r\n0,0,0,0\n0.04,1.6,0,0\n"),
            "p.csv:3: gaze_angle_x is 1.6 radians, outside (-π/2, π/2)");
  EXPECT_EQ(gazeErrorOf("timestamp,gaze_angle_x,gaze_angle_y,AU12_r\n0,0,abc,0\n"),
            "p.csv:2: unreadable number 'abc' in column 'gaze_angle_y'");
}

// ---- Live Link --------------------------------------------------------------------------------

// The plugin writes each eye's angles as the head's (degrees / 180, right-handed about the face
// frame's x and y): LeftEyePitch < 0 turns the left eye up, LeftEyeYaw > 0 towards the subject's left.
TEST(PerformanceGaze, LiveLinkEyeAnglesTurnEachEyeWithTheDocumentedSign) {
  const Performance p = parsePerformance(
      "Timecode,BlendShapeCount,JawOpen,LeftEyeYaw,LeftEyePitch,LeftEyeRoll,RightEyeYaw,RightEyePitch,RightEyeRoll\n"
      "00:00:00:00,7,0,0.05,-0.1,0.3,-0.03,0.02,0.3\n"
      "00:00:00:01,7,0,0,0,0,0,0,0\n",
      "l.csv", {.inputFps = 60.0});
  ASSERT_EQ(p.gaze.size(), 2u);
  EXPECT_DOUBLE_EQ(p.gaze[0].pitchDeg[1], 18.0);   // the left eye up
  EXPECT_DOUBLE_EQ(p.gaze[0].yawDeg[1], 9.0);      // towards the subject's left
  EXPECT_DOUBLE_EQ(p.gaze[0].pitchDeg[0], -3.6);   // the right eye down
  EXPECT_DOUBLE_EQ(p.gaze[0].yawDeg[0], -5.4);     // towards the subject's right
  EXPECT_TRUE(p.gaze[1].isZero());
  EXPECT_EQ(p.channels.size(), 1u);  // the eyes' angles are no channels; the rolls are not read
  // The sample take: LeftEyePitch −0.0412, LeftEyeYaw 0.0631.
  const Performance take =
      readPerformanceFile((test::sourceDir() / "tests" / "anim" / "performances" / "livelink_take.csv").string());
  ASSERT_EQ(take.gaze.size(), 3u);
  EXPECT_NEAR(take.gaze[0].pitchDeg[1], 0.0412 * 180, 1e-9);
  EXPECT_NEAR(take.gaze[0].yawDeg[1], 0.0631 * 180, 1e-9);
  EXPECT_NEAR(take.gaze[0].pitchDeg[0], 0.0408 * 180, 1e-9);
}

TEST(PerformanceGaze, LiveLinkEyeErrorsNameTheFileLineAndColumn) {
  EXPECT_EQ(gazeErrorOf("Timecode,BlendShapeCount,JawOpen,LeftEyeYaw,LeftEyePitch,RightEyeYaw\n"),
            "p.csv:1: missing required column 'RightEyePitch' (the eyes' turn needs LeftEyePitch, LeftEyeYaw, "
            "RightEyePitch and RightEyeYaw)");
  EXPECT_EQ(gazeErrorOf("Timecode,BlendShapeCount,JawOpen,LeftEyeYaw,LeftEyeYaw\n"),
            "p.csv:1: column 'LeftEyeYaw' appears twice (columns 4 and 5)");
  const std::string header = "Timecode,BlendShapeCount,JawOpen,LeftEyeYaw,LeftEyePitch,RightEyeYaw,RightEyePitch\n";
  EXPECT_EQ(gazeErrorOf(header + "00:00:00:00,5,0,0,1.5,0,0\n"),
            "p.csv:2: LeftEyePitch is 1.5, outside [-1, 1] (degrees / 180)");
  EXPECT_EQ(gazeErrorOf(header + "00:00:00:00,5,0,0,0,nan,0\n"),
            "p.csv:2: non-finite number 'nan' in column 'RightEyeYaw'");
  // The rolls alone are no gaze: read past, as before.
  EXPECT_TRUE(parsePerformance("Timecode,BlendShapeCount,JawOpen,LeftEyeRoll\n00:00:00:00,2,0,0.5\n00:00:00:01,2,0,0.5\n",
                               "p.csv", {.inputFps = 60.0})
                  .gaze.empty());
}

// ---- mapping ----------------------------------------------------------------------------------

Performance arkitTake(PerformanceInput input, std::vector<PerformanceChannel> channels, int frames = 5) {
  Performance p;
  p.input = input;
  p.fps = 25.0;
  for (int f = 0; f < frames; ++f) p.times.push_back(f / 25.0);
  for (auto& c : channels) c.values.resize(frames, c.values.empty() ? 0.0 : c.values.back());
  p.channels = std::move(channels);
  return p;
}

// Without eye angles the eyeLook* curves turn the eyes through the map's gaze (25° at 1), each its
// own eye; AU61–64 through the FACS map's.
TEST(PerformanceGaze, WithoutAnglesTheEyeLookCurvesTurnTheEyes) {
  const Performance p = arkitTake(PerformanceInput::MediaPipe,
                                  {{"eyeLookUpLeft", {0.6}}, {"eyeLookInRight", {0.4}}, {"mouthSmileLeft", {0.5}}});
  const MappedPerformance m = mapPerformance(p, gazeMuscleNames(), builtinFacsMap(), builtinRetargetMap(), gazeFilterOff());
  ASSERT_EQ(m.gaze.size(), 5u);
  EXPECT_DOUBLE_EQ(m.gaze[2].pitchDeg[1], 0.6 * 25.0);  // the left eye up
  EXPECT_DOUBLE_EQ(m.gaze[2].pitchDeg[0], 0.0);
  EXPECT_DOUBLE_EQ(m.gaze[2].yawDeg[0], 0.4 * 25.0);    // the right eye in: towards the subject's left
  EXPECT_DOUBLE_EQ(m.gaze[2].yawDeg[1], 0.0);
  EXPECT_TRUE(m.unmapped.empty()) << m.unmapped.front();
  const Performance au = arkitTake(PerformanceInput::OpenFace, {{"AU64", {0.5}}, {"AU61", {0.2}}});
  const MappedPerformance a = mapPerformance(au, gazeMuscleNames(), builtinFacsMap(), RetargetMap{}, gazeFilterOff());
  ASSERT_EQ(a.gaze.size(), 5u);
  for (size_t e = 0; e < 2; ++e) {
    EXPECT_DOUBLE_EQ(a.gaze[0].pitchDeg[e], -12.5);  // AU64: eyes down
    EXPECT_DOUBLE_EQ(a.gaze[0].yawDeg[e], 5.0);      // AU61: eyes to the subject's left
  }
  EXPECT_TRUE(a.unmapped.empty());
  EXPECT_TRUE(a.warnings.empty()) << a.warnings.front();
  // Nothing that turns the eyes: no gaze at all.
  EXPECT_TRUE(mapPerformance(arkitTake(PerformanceInput::OpenFace, {{"AU12", {0.5}}}), gazeMuscleNames(),
                             builtinFacsMap(), RetargetMap{}, gazeFilterOff())
                  .gaze.empty());
}

// With eye angles the eyes follow them alone: Live Link writes both its angles and its eyeLook*
// curves, and one turn is not added twice. The eyeLook* curves then drive nothing and are no
// unmapped curves (the eyes do turn).
TEST(PerformanceGaze, TheFileAnglesWinOverTheEyeLookCurves) {
  Performance p = arkitTake(PerformanceInput::LiveLink, {{"eyeLookUpLeft", {1.0}}, {"eyeLookDownRight", {1.0}}});
  EyeGaze g;
  g.pitchDeg = {-4.0, 7.0};
  g.yawDeg = {2.0, 3.0};
  p.gaze.assign(5, g);
  const MappedPerformance m = mapPerformance(p, gazeMuscleNames(), builtinFacsMap(), builtinRetargetMap(), gazeFilterOff());
  ASSERT_EQ(m.gaze.size(), 5u);
  EXPECT_EQ(m.gaze[3].pitchDeg, g.pitchDeg);
  EXPECT_EQ(m.gaze[3].yawDeg, g.yawDeg);
  EXPECT_TRUE(m.unmapped.empty());
  EXPECT_TRUE(m.warnings.empty()) << m.warnings.front();
}

// The eye stops at its range, and the angles go through the One-Euro filter as the curves do.
TEST(PerformanceGaze, AnglesAreFilteredAndClampedToTheEyesRange) {
  Performance p = arkitTake(PerformanceInput::LiveLink, {{"jawOpen", {0.0}}}, 20);
  p.gaze.resize(20);
  for (int f = 0; f < 20; ++f) {
    p.gaze[static_cast<size_t>(f)].pitchDeg = {f < 10 ? 0.0 : 30.0, 80.0};
    p.gaze[static_cast<size_t>(f)].yawDeg = {0.0, -60.0};
  }
  const MappedPerformance raw = mapPerformance(p, gazeMuscleNames(), builtinFacsMap(), RetargetMap{}, gazeFilterOff());
  EXPECT_DOUBLE_EQ(raw.gaze[5].pitchDeg[1], kGazeMaxDeg);
  EXPECT_DOUBLE_EQ(raw.gaze[5].yawDeg[1], -kGazeMaxDeg);
  EXPECT_DOUBLE_EQ(raw.gaze[10].pitchDeg[0], 30.0);
  const OneEuroSettings filter;
  const MappedPerformance smooth = mapPerformance(p, gazeMuscleNames(), builtinFacsMap(), RetargetMap{}, filter);
  std::vector<double> pitch(20);
  for (int f = 0; f < 20; ++f) pitch[static_cast<size_t>(f)] = p.gaze[static_cast<size_t>(f)].pitchDeg[0];
  const std::vector<double> expected = oneEuroFilter(p.times, pitch, filter);
  for (size_t f = 0; f < 20; ++f) EXPECT_DOUBLE_EQ(smooth.gaze[f].pitchDeg[0], expected[f]);
  EXPECT_GT(smooth.gaze[10].pitchDeg[0], 0.0);
  EXPECT_LT(smooth.gaze[10].pitchDeg[0], 30.0);  // the step is smoothed
}

// The scene gets a track per angle that moves, the scene's own keys add, the sum held within ±45°;
// a gaze that is 0 throughout gives no track at all.
TEST(PerformanceGaze, TheSceneGetsGazeTracks) {
  Performance p = arkitTake(PerformanceInput::LiveLink, {{"jawOpen", {0.0}}}, 26);
  EyeGaze g;
  g.pitchDeg = {0.0, 20.0};
  p.gaze.assign(26, g);
  const MappedPerformance m = mapPerformance(p, gazeMuscleNames(), builtinFacsMap(), RetargetMap{}, gazeFilterOff());
  SceneDesc scene;
  scene.gazePitch[1] = ScalarTrack({{0.0, 30.0, Interpolation::Linear}});
  addPerformanceToScene(scene, m);
  ASSERT_TRUE(scene.hasGaze());
  EXPECT_DOUBLE_EQ(scene.gazePitch[1].at(0.5), kGazeMaxDeg);  // 20 + 30, held at 45
  EXPECT_TRUE(scene.gazePitch[0].empty());
  EXPECT_TRUE(scene.gazeYaw[0].empty() && scene.gazeYaw[1].empty());
  p.gaze.assign(26, EyeGaze{});
  SceneDesc still;
  addPerformanceToScene(still, mapPerformance(p, gazeMuscleNames(), builtinFacsMap(), RetargetMap{}, gazeFilterOff()));
  EXPECT_FALSE(still.hasGaze());
}

}  // namespace
}  // namespace myo
