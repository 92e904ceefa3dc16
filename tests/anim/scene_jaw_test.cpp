// timeline.jaw (docs/scene_format.md, docs/jaw.md): parsed, round-tripped, refused under the thesis
// model, and applied by ScenePlayer every step (the played positions are the jawed rest + the turned
// residual of head/jaw.h).
#include <gtest/gtest.h>

#include "myoshell/anatomy/anatomical_face.h"
#include "myoshell/anim/scene_parser.h"
#include "myoshell/anim/scene_player.h"
#include "myoshell/core/errors.h"
#include "myoshell/io/scene_face.h"
#include "support/basis_cache.h"

namespace myo {
namespace {

const char* kJawScene = R"({"name": "jaw", "duration": 0.1, "fps": 30, "numerics": {"skin_modes": 8},
  "muscles": {"use": ["zygomaticus_major_left"]},
  "timeline": {"activations": {"zygomaticus_major_left": [{"t": 0, "value": 1}]},
               "jaw": {"open": [{"t": 0, "value": 0}, {"t": 0.1, "value": 20}],
                       "forward": [{"t": 0, "value": 0.3}],
                       "lateral": [{"t": 0, "value": -0.2}]}}})";

TEST(SceneJaw, ParsesAndRoundTrips) {
  const SceneDesc a = parseScene(kJawScene, "jaw.json");
  ASSERT_TRUE(a.hasJaw());
  EXPECT_DOUBLE_EQ(a.jawOpen.at(0.05), 10.0);
  EXPECT_DOUBLE_EQ(a.jawForward.at(0.05), 0.3);
  EXPECT_DOUBLE_EQ(a.jawLateral.at(0.05), -0.2);
  const SceneDesc b = parseScene(sceneToJson(a), "jaw.json");
  EXPECT_EQ(sceneToJson(b), sceneToJson(a));
  EXPECT_DOUBLE_EQ(b.jawOpen.at(0.1), 20.0);
  EXPECT_FALSE(parseScene("{}", "empty.json").hasJaw());
}

TEST(SceneJaw, TheThesisModelRefusesTheJaw) {
  try {
    (void)parseScene(R"({"model": "thesis", "timeline": {"jaw": {"open": [{"t": 0, "value": 5}]}}})", "t.json");
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("key 'timeline.jaw': only \"model\": \"anatomical\" uses it"), std::string::npos)
        << e.what();
  }
}

TEST(SceneJaw, ThePlayerAppliesTheJawEveryStep) {
  const SceneDesc scene = parseScene(kJawScene, "jaw.json");
  const auto face = buildSceneFace(scene, test::sharedBasisCache());
  ScenePlayer player(scene, face);
  player.playTo(0.1);
  const FrameSnapshot& s = player.snapshot(false);
  const auto* anatomical = dynamic_cast<const AnatomicalFace*>(face.get());
  ASSERT_NE(anatomical, nullptr);
  ASSERT_NE(anatomical->jawRig(), nullptr);
  const JawPose jaw = player.simulator().jaw();
  EXPECT_DOUBLE_EQ(jaw.forwardCm, 0.3);
  EXPECT_DOUBLE_EQ(jaw.lateralCm, -0.2);
  EXPECT_GT(jaw.openDeg, 19.0);  // the last applied step's time, just before 0.1 s
  // The jawed rest + the turned residual, then the built-in head's lids (open eyes; none of the
  // scene's muscles drives them, so only the eyeballs' contact can act): AnatomicalFace::placeSkin.
  MatX3 jawed, expected;
  jawedPositions(*anatomical->jawRig(), jaw, face->head().mesh.V, s.displacement, jawed);
  VecX activations(face->muscleCount());
  for (int m = 0; m < face->muscleCount(); ++m) activations(m) = player.simulator().activation(m);
  anatomical->placeSkin(s.displacement, jaw, activations, expected);
  EXPECT_TRUE(s.positions == expected);
  EXPECT_LT((s.positions - jawed).cwiseAbs().maxCoeff(), 0.01);  // the contact moves the skin by < 0.1 mm
  EXPECT_GT((s.positions - face->head().mesh.V).rowwise().norm().maxCoeff(), 2.0);  // the chin moved
}

}  // namespace
}  // namespace myo
