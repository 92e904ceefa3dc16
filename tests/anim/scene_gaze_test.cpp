// timeline.gaze (docs/scene_format.md, docs/eyelids.md): parsed, round-tripped, refused under the
// thesis model and out of the eye's range, and applied by ScenePlayer every step: the played frame is
// the face's placement at that gaze (SkinPlacement::place, the rigs' path); a zero gaze track plays
// bit for bit as none.
#include <gtest/gtest.h>

#include <cmath>

#include "myoshell/anatomy/anatomical_face.h"
#include "myoshell/anim/scene_parser.h"
#include "myoshell/anim/scene_player.h"
#include "myoshell/core/errors.h"
#include "myoshell/fit/arkit_rig.h"
#include "myoshell/io/scene_face.h"
#include "support/basis_cache.h"

namespace myo {
namespace {

const char* kGazeScene = R"({"name": "gaze", "duration": 0.1, "fps": 30, "numerics": {"skin_modes": 8},
  "muscles": {"use": ["zygomaticus_major_left"]},
  "timeline": {"activations": {"zygomaticus_major_left": [{"t": 0, "value": 0.5}]},
               "gaze": {"left_pitch": [{"t": 0, "value": 0}, {"t": 0.05, "value": 20}],
                        "right_yaw": [{"t": 0, "value": -10}]}}})";

TEST(SceneGaze, ParsesAndRoundTrips) {
  const SceneDesc a = parseScene(kGazeScene, "gaze.json");
  ASSERT_TRUE(a.hasGaze());
  EXPECT_DOUBLE_EQ(a.gazeAt(0.025).pitchDeg[1], 10.0);
  EXPECT_DOUBLE_EQ(a.gazeAt(0.09).pitchDeg[1], 20.0);
  EXPECT_DOUBLE_EQ(a.gazeAt(0.09).yawDeg[0], -10.0);
  EXPECT_DOUBLE_EQ(a.gazeAt(0.09).pitchDeg[0], 0.0);
  const SceneDesc b = parseScene(sceneToJson(a), "gaze.json");
  EXPECT_EQ(sceneToJson(b), sceneToJson(a));
  EXPECT_FALSE(parseScene("{}", "empty.json").hasGaze());
}

TEST(SceneGaze, ErrorsNameTheKey) {
  auto errorOfScene = [](const std::string& text) -> std::string {
    try {
      (void)parseScene(text, "g.json");
    } catch (const InputError& e) {
      return e.what();
    }
    return "(no error)";
  };
  EXPECT_NE(errorOfScene(R"({"model": "thesis", "timeline": {"gaze": {"left_pitch": [{"t": 0, "value": 5}]}}})")
                .find("key 'timeline.gaze': only \"model\": \"anatomical\" uses it"),
            std::string::npos);
  EXPECT_NE(errorOfScene(R"({"timeline": {"gaze": {"left_pitch": [{"t": 0, "value": 50}]}}})")
                .find("must lie in [-45, 45] degrees (the eye's range, docs/eyelids.md) (got 50)"),
            std::string::npos);
  EXPECT_NE(errorOfScene(R"({"timeline": {"gaze": {"left_roll": [{"t": 0, "value": 5}]}}})").find("left_roll"),
            std::string::npos);
}

TEST(SceneGaze, TheThesisModelHasNoEyesToTurn) {
  const SceneDesc scene = parseScene(R"({"model": "thesis", "muscles": {"use": ["zygomaticus_major_left"]},
    "numerics": {"skin_modes": 4}, "duration": 0.05})", "t.json");
  const auto face = buildSceneFace(scene, test::sharedBasisCache());
  auto sim = makeStepper(face);
  sim->setGaze(EyeGaze{});  // zero: nothing to turn, no error
  EyeGaze g;
  g.pitchDeg[1] = 5.0;
  try {
    sim->setGaze(g);
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(),
                 "the eyes' turn (timeline.gaze) needs \"model\": \"anatomical\"; the thesis model has no eyes to turn");
  }
}

// The player turns the eyes every step, and the frame is the face's placement at that gaze
// (SkinPlacement::place, the rigs' path): the left upper lid rises with the left eye, as the rig's
// eyeLookUpLeft lifts it; out of range is an InputError; a zero gaze track leaves the frame bit for bit.
TEST(SceneGaze, ThePlayerTurnsTheEyesEveryStep) {
  const SceneDesc scene = parseScene(kGazeScene, "gaze.json");
  const auto face = buildSceneFace(scene, test::sharedBasisCache());
  const auto* anatomical = dynamic_cast<const AnatomicalFace*>(face.get());
  ASSERT_NE(anatomical, nullptr);
  ASSERT_NE(anatomical->lidRig(), nullptr);  // the built-in head has open eyes
  ScenePlayer player(scene, face);
  player.playTo(0.1);
  const FrameSnapshot& s = player.snapshot(false);
  const EyeGaze gaze = player.simulator().gaze();
  EXPECT_DOUBLE_EQ(gaze.pitchDeg[1], 20.0);
  EXPECT_DOUBLE_EQ(gaze.yawDeg[0], -10.0);
  VecX activations(face->muscleCount());
  for (int m = 0; m < face->muscleCount(); ++m) activations(m) = player.simulator().activation(m);
  MatX3 expected;
  anatomical->placement().place(s.displacement, JawPose{}, activations, expected, anatomical->placement().contact(), gaze);
  EXPECT_TRUE(s.positions == expected);

  // The left upper lid's middle margin vertex rises (face frame y), in the direction the rig's
  // eyeLookUpLeft (the shipped map's gaze, placed on the rest) moves it.
  const EyeLids& left = anatomical->lidRig()->eyes[1];
  const int mid = left.upperMargin[left.upperMargin.size() / 2];
  const Vec3 up = face->head().frame().axes.col(1);
  MatX3 without;
  anatomical->placement().place(s.displacement, JawPose{}, activations, without, anatomical->placement().contact());
  const Vec3 lift = (s.positions.row(mid) - without.row(mid)).transpose();
  EXPECT_GT(lift.dot(up), 0.1);  // cm: 20° lifts the upper margin by ~2–3 mm
  const RetargetShape* look = builtinRetargetMap().find("eyeLookUpLeft");
  ASSERT_NE(look, nullptr);
  MatX3 rig;
  const MatX3 still = MatX3::Zero(face->head().mesh.vertexCount(), 3);
  anatomical->placement().place(still, JawPose{}, VecX::Zero(face->muscleCount()), rig, anatomical->placement().contact(),
                                gazeOf(*look));
  const Vec3 rigLift = (rig.row(mid) - face->head().mesh.V.row(mid)).transpose();
  EXPECT_GT(lift.normalized().dot(rigLift.normalized()), 0.9);
  // The right eye turned only sideways: its upper margin barely rises.
  const EyeLids& right = anatomical->lidRig()->eyes[0];
  const int rmid = right.upperMargin[right.upperMargin.size() / 2];
  EXPECT_LT(std::abs((s.positions.row(rmid) - without.row(rmid)).dot(up.transpose())), 0.05);

  // Out of the eye's range: an InputError naming the eye.
  EyeGaze far;
  far.yawDeg[0] = 50.0;
  try {
    player.simulator().setGaze(far);
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "gaze: right eye yaw 50 degrees is outside [-45, 45] degrees");
  }

  // A zero gaze track plays exactly as no track.
  SceneDesc zero = parseScene(kGazeScene, "gaze.json");
  zero.gazePitch[1] = ScalarTrack({{0.0, 0.0, Interpolation::Linear}});
  zero.gazeYaw[0] = ScalarTrack({{0.0, 0.0, Interpolation::Linear}});
  SceneDesc none = zero;
  none.gazePitch = {};
  none.gazeYaw = {};
  ASSERT_TRUE(zero.hasGaze());
  ASSERT_FALSE(none.hasGaze());
  ScenePlayer a(zero, face), b(none, face);
  a.playTo(0.1);
  b.playTo(0.1);
  EXPECT_TRUE(a.snapshot(false).positions == b.snapshot(false).positions);
}

}  // namespace
}  // namespace myo
