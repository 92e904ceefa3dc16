// ScenePlayer: the one frame-count formula and frame times, advancing equals stepping by hand (bit
// for bit), cancellation between steps, names resolved once (unknown ones rejected with the exact
// message), and the snapshot's maxima against the channel fields.
#include <gtest/gtest.h>

#include <atomic>

#include "myoshell/anim/scene_parser.h"
#include "myoshell/anim/scene_player.h"
#include "myoshell/core/errors.h"
#include "myoshell/io/scene_face.h"  // buildSceneFace for the fixture
#include "myoshell/thesis/simulator.h"
#include "support/basis_cache.h"

namespace myo {
namespace {

SceneDesc smallScene() {
  return parseScene(R"({
    "name": "player_test",
    "model": "thesis",
    "muscles": {"use": ["zygomaticus_major_left", "zygomaticus_major_right"]},
    "gravity": {"enabled": true},
    "numerics": {"skin_modes": 10},
    "drags": [{"name": "cheek", "vertex": 205, "radius": 1.0}],
    "duration": 0.3, "fps": 20,
    "timeline": {
      "activations": {"zygomaticus_major_left": [{"t": 0, "value": 0, "interp": "smooth"}, {"t": 0.2, "value": 1}],
                      "zygomaticus_major_right": [{"t": 0, "value": 0.5}]},
      "gravity": [{"t": 0, "value": 0}, {"t": 0.3, "value": 1}],
      "drags": {"cheek": [{"t": 0, "value": [0, 0, 0]}, {"t": 0.3, "value": [3000, 0, 0]}]}}
  })",
                    "player_test.json");
}

std::shared_ptr<const FaceModel> smallFace() {  // built once: the eigen-solves are the slow part
  static const auto model = buildThesisFace(smallScene(), test::sharedBasisCache());
  return model;
}

TEST(ScenePlayer, FrameCountIsOneFormulaAndFrameTimesAreKOverFps) {
  EXPECT_EQ(ScenePlayer::frameCount(1.0, 30.0), 31);
  EXPECT_EQ(ScenePlayer::frameCount(0.5, 7.0), 4);     // 3.5 frames of time: 0, 1/7, 2/7, 3/7
  EXPECT_EQ(ScenePlayer::frameCount(0.29, 100.0), 30); // 0.29·100 = 28.999999999999996 counts as 29
  EXPECT_EQ(ScenePlayer::frameCount(0.1, 30.0), 4);    // 3.0000000000000004
  EXPECT_EQ(ScenePlayer::frameCount(0.01, 30.0), 1);   // shorter than a frame: frame 0 only
  ScenePlayer player(smallScene(), smallFace());
  EXPECT_EQ(player.frameCount(), 7);
  EXPECT_DOUBLE_EQ(player.frameTime(0), 0.0);
  EXPECT_DOUBLE_EQ(player.frameTime(3), 3.0 / 20.0);
  // Advancing lands within half a step of the frame's time.
  const double dt = smallFace()->settings().dt;
  ASSERT_TRUE(player.advanceTo(3));
  EXPECT_NEAR(player.time(), 0.15, 0.5 * dt + 1e-12);
  EXPECT_EQ(player.simulator().stepCount(), std::llround(0.15 / dt));
}

TEST(ScenePlayer, AdvancingEqualsSteppingByHandBitForBit) {
  const SceneDesc scene = smallScene();
  ScenePlayer player(scene, smallFace());
  Simulator sim(smallFace());
  const double dt = smallFace()->settings().dt;
  for (int k = 0; k < player.frameCount(); ++k) {
    ASSERT_TRUE(player.advanceTo(k));
    while (sim.time() < k / scene.fps - 0.5 * dt) {  // the timeline by name, at the step's time
      for (const auto& [name, track] : scene.activations) sim.setActivation(name, track.at(sim.time()));
      sim.setGravity(scene.gravity.at(sim.time()));
      sim.setDragForce(0, scene.dragForces.at("cheek").at(sim.time()));
      sim.step();
    }
    const FrameSnapshot& snap = player.snapshot();
    ASSERT_EQ(snap.positions.rows(), sim.skinPositions().rows());
    EXPECT_TRUE((snap.positions.array() == sim.skinPositions().array()).all()) << "frame " << k;
    EXPECT_EQ(snap.time, sim.time());
  }
  EXPECT_GT(player.snapshot().maxDisplacement, 0.0);
}

TEST(ScenePlayer, CancellationStopsAtTheNextStep) {
  ScenePlayer player(smallScene(), smallFace());
  std::atomic<bool> stop{false};
  player.watch(&stop);
  int steps = 0;
  player.setControls([&](FaceStepper&) {
    if (++steps == 3) stop = true;  // seen before the 4th step
  });
  EXPECT_FALSE(player.advanceTo(player.frameCount() - 1));
  EXPECT_EQ(player.simulator().stepCount(), 3);
  EXPECT_FALSE(player.advanceTo(player.frameCount() - 1));  // stays cancelled
  EXPECT_EQ(player.simulator().stepCount(), 3);
  stop = false;
  player.cancel();  // the player's own flag
  EXPECT_FALSE(player.playTo(1.0));
  EXPECT_EQ(player.simulator().stepCount(), 3);
  player.resetCancel();
  EXPECT_TRUE(player.advanceTo(player.frameCount() - 1));
  EXPECT_EQ(player.snapshot().steps, player.simulator().stepCount() - 3);
}

TEST(ScenePlayer, UnknownNamesAreRejectedWithTheExactMessage) {
  SceneDesc scene = smallScene();
  scene.activations["buccinator"] = ScalarTrack({{0.0, 1.0}}, "activation of buccinator");
  try {
    ScenePlayer player(scene, smallFace());
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.message(),
              "timeline.activations: unknown muscle 'buccinator' (this face has: zygomaticus_major_left, "
              "zygomaticus_major_right)");
    EXPECT_EQ(e.file(), "player_test.json");
  }
  scene = smallScene();
  scene.dragForces["chin"] = VectorTrack({{0.0, Vec3(1, 0, 0)}}, "drag chin");
  try {
    ScenePlayer player(scene, smallFace());
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.message(), "timeline.drags: unknown drag 'chin' (this face has: cheek)");
  }
}

TEST(ScenePlayer, SnapshotMaximaEqualTheChannelFieldsMaxima) {
  ScenePlayer player(smallScene(), smallFace());
  ASSERT_TRUE(player.advanceTo(player.frameCount() - 1));
  const FrameSnapshot& snap = player.snapshot();
  const auto& sim = dynamic_cast<const Simulator&>(player.simulator());
  ASSERT_EQ(snap.channelMax.size(), smallFace()->channels().size());
  for (size_t c = 0; c < snap.channelMax.size(); ++c) {
    EXPECT_EQ(snap.channelMax[c], sim.channelDisplacement(static_cast<int>(c)).rowwise().norm().maxCoeff());
    EXPECT_GT(snap.channelMax[c], 0.0) << smallFace()->channels()[c].name;  // every channel is loaded
  }
  EXPECT_EQ(snap.maxDisplacement, sim.skinDisplacement().rowwise().norm().maxCoeff());
  ASSERT_EQ(snap.muscles.size(), 2u);
  EXPECT_TRUE((snap.muscles[1].array() == sim.musclePositions(1).array()).all());
  // A second snapshot reuses the buffers.
  const double* buffer = snap.positions.data();
  EXPECT_EQ(player.snapshot().positions.data(), buffer);
}

}  // namespace
}  // namespace myo
