// The anatomical model played by the one frame loop: a scene run through `myoshell run` gives, bit
// for bit, the positions of an AnatomicalSkin stepped by hand with AnatomicalStepper (same
// activations, drag force, upright gravity); the head pose turns gravity (face-down moves the face
// along the face frame's +z); thesis-only keys and relaxing activations are refused at the CLI.
// The built-in head with few modes keeps the two builds (CLI and here) short.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "myoshell/anatomy/anatomical_face.h"
#include "myoshell/anatomy/eyelids.h"
#include "myoshell/anim/scene_player.h"
#include "myoshell/io/animation_export.h"
#include "myoshell/io/scene_face.h"
#include "support/cli_runner.h"

namespace myo {
namespace {

namespace fs = std::filesystem;

const char* kScene = R"({
  "name": "anatomical_small",
  "model": "anatomical",
  "muscles": {"use": ["zygomaticus_major_left", "depressor_anguli_oris_right"]},
  "numerics": {"skin_modes": 6},
  "drags": [{"name": "cheek", "vertex": 205, "radius": 1.0}],
  "duration": 0.15, "fps": 20,
  "timeline": {
    "activations": {"zygomaticus_major_left": [{"t": 0, "value": 0, "interp": "smooth"}, {"t": 0.1, "value": 1}],
                    "depressor_anguli_oris_right": [{"t": 0, "value": 0.5}]},
    "drags": {"cheek": [{"t": 0, "value": [0, 0, 0]}, {"t": 0.15, "value": [2000, 500, 0]}]}}
})";

fs::path sceneScratch() {
  static const fs::path dir = [] {
    const fs::path d = fs::temp_directory_path() / ("myo_anatomical_scene_" + std::to_string(::getpid()));
    fs::remove_all(d);
    fs::create_directories(d);
    std::ofstream(d / "scene.json") << kScene;
    return d;
  }();
  return dir;
}

TEST(AnatomicalScene, RunGivesTheHandSteppedSkinBitForBit) {
  const fs::path dir = sceneScratch();
  const auto r = test::runCli("run '" + (dir / "scene.json").string() + "' --out '" + (dir / "out").string() +
                              "' --format pc2 --json --cache '" + (dir / "cache").string() + "'");
  ASSERT_EQ(r.exitCode, 0) << r.merged;
  const PointCache cache = readPc2(dir / "out" / "anatomical_small.pc2");

  // By hand: the scene's head, muscles and settings, the skin built and stepped directly.
  const SceneDesc scene = readScene((dir / "scene.json").string());
  ASSERT_EQ(scene.modelKind, FaceModelKind::Anatomical);
  const SceneInputs in = readSceneInputs(scene);
  auto built = std::make_unique<AnatomicalSkin>(in.head, in.muscles, scene.anatomical);
  built->addDrag(205, 1.0);
  const std::shared_ptr<const AnatomicalSkin> skin = std::move(built);
  AnatomicalStepper stepper(skin);
  SkinLoads loads;
  loads.activations = VecX::Zero(2);
  loads.gravity = skin->restGravity();  // upright, gravity on: no gravity load
  loads.drags.assign(1, Vec3::Zero());
  loads.contact = scene.anatomical.contact;  // as the playing face: the contact penalty (docs/mouth_contact.md)
  const int zyg = skin->muscleIndex("zygomaticus_major_left"), dao = skin->muscleIndex("depressor_anguli_oris_right");
  const double dt = skin->settings().dt;
  const int frames = ScenePlayer::frameCount(scene.duration, scene.fps);
  ASSERT_EQ(static_cast<int>(cache.samples.size()), frames);
  const LidRig lids = lidRig(in.head.mesh, in.head.landmarks);
  double t = 0.0;
  double moved = 0.0;
  for (int k = 0; k < frames; ++k) {
    while (t < k / scene.fps - 0.5 * dt) {
      loads.activations(zyg) = scene.activations.at("zygomaticus_major_left").at(t);
      loads.activations(dao) = scene.activations.at("depressor_anguli_oris_right").at(t);
      loads.drags[0] = scene.dragForces.at("cheek").at(t);
      stepper.step(loads);
      t += dt;
    }
    // The built-in head has open eyes: rest + u, then its eyeballs push out what the skin pressed
    // into them (eyelids.h; neither muscle drives a lid, so the lids' pose is zero).
    MatX3 positions = skin->head().mesh.V + stepper.displacement();
    applyLids(lids, LidPose{}, positions);
    const MatX3 stored = positions.cast<float>().cast<double>();
    EXPECT_TRUE((cache.samples[static_cast<size_t>(k)].array() == stored.array()).all()) << "frame " << k;
    moved = std::max(moved, stepper.displacement().rowwise().norm().maxCoeff());
  }
  EXPECT_GT(moved, 0.05);  // cm: the muscles and the drag moved the face

  std::ifstream statsIn(dir / "out" / "stats.json");
  const auto stats = nlohmann::json::parse(statsIn);
  EXPECT_EQ(stats["model"], "anatomical");
  ASSERT_EQ(stats["channels"].size(), 1u);
  EXPECT_EQ(stats["channels"][0]["name"], "skin");
  EXPECT_NEAR(stats["channels"][0]["max_displacement_cm"].get<double>(), moved, 1e-12);
}

TEST(AnatomicalScene, FaceDownHeadPoseMovesTheFaceAlongItsFrameZ) {
  const fs::path dir = sceneScratch();
  SceneDesc scene = readScene((dir / "scene.json").string());
  scene.activations.clear();
  scene.dragForces.clear();
  scene.duration = 0.6;
  // Upright at t = 0, face-down from 0.1 s on.
  scene.headPose = HeadPoseTrack({{0.0, Vec3(0, 0, 0)}, {0.1, Vec3(90, 0, 0)}}, "head pose");
  const auto face = buildSceneFace(scene);
  ScenePlayer player(scene, face);
  ASSERT_TRUE(player.advanceTo(player.frameCount() - 1));
  const FrameSnapshot& snap = player.snapshot(false);
  // Face-down, gravity points along the face frame's +z; only its change from the upright rest loads.
  const FaceFrame frame = face->head().frame();
  const double g = scene.anatomical.gravity;
  const Vec3 down = gravityForRotation(frame, scene.headPose.at(1.0), g);
  EXPECT_GT(down.dot(frame.axes.col(2)), 0.99 * g);  // the head's frame y is within a few degrees of its up
  const Vec3 change = (down - Vec3(0, -g, 0)).normalized();
  const Vec3 mean = snap.displacement.colwise().mean().transpose();
  EXPECT_GT(snap.maxDisplacement, 0.01);  // cm: the tissue sags towards the floor
  EXPECT_LT(snap.maxDisplacement, 1.0);
  EXPECT_GT(mean.dot(change), 0.8 * mean.norm());
}

TEST(AnatomicalScene, TheCliRefusesThesisKeysAndRelaxingNamingTheModel) {
  const fs::path dir = sceneScratch();
  std::ofstream(dir / "roi.json") << "{\n  \"roi_alpha\": 5\n}\n";
  auto r = test::runCli("check '" + (dir / "roi.json").string() + "'");
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.err.find("roi.json:2:16: key 'roi_alpha': only \"model\": \"thesis\" uses it (this scene's model is "
                       "anatomical, the default)"),
            std::string::npos)
      << r.err;
  std::ofstream(dir / "relax.json")
      << R"({"timeline": {"activations": {"zygomaticus_major_left": [{"t": 0, "value": -0.5}]}}})";
  r = test::runCli("run '" + (dir / "relax.json").string() + "' --out '" + (dir / "relax_out").string() + "'");
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.err.find("key 'timeline.activations.zygomaticus_major_left[0].value': must lie in [0, 1] under the "
                       "anatomical model (relaxing, a < 0, needs \"model\": \"thesis\") (got -0.5)"),
            std::string::npos)
      << r.err;
  EXPECT_FALSE(fs::exists(dir / "relax_out"));
}

}  // namespace
}  // namespace myo
