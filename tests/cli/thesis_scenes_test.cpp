// The thesis's experiments (section VII, Figs. 17–27) as scenes in scenes/thesis/: every scene is
// run on its head and shows the effect the thesis reports. Behaviour only — speed lives in
// `myoshell bench` (docs/PERFORMANCE.md). Models are built through a basis cache in the test's
// temporary folder and shared between tests that use the same scene.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "myoshell/anim/scene_player.h"
#include "myoshell/io/basis_cache_file.h"
#include "myoshell/io/scene_face.h"
#include "myoshell/thesis/simulator.h"
#include "support/cli_runner.h"
#include "support/test_data.h"

namespace myo {
namespace {

namespace fs = std::filesystem;

fs::path sceneDir() { return test::sourceDir() / "scenes" / "thesis"; }
std::string scenePath(const std::string& name) { return (sceneDir() / (name + ".json")).string(); }

fs::path cacheDir() {
  static const fs::path dir = [] {
    const fs::path d = fs::path(testing::TempDir()) / "myo_thesis_cache";
    fs::create_directories(d);
    return d;
  }();
  return dir;
}

FileBasisCache& cache() {
  static FileBasisCache c(cacheDir());
  return c;
}

// One model per scene file (and stiffness scale), built once per test program.
std::shared_ptr<const FaceModel> modelFor(const SceneDesc& scene, const std::string& key) {
  static std::map<std::string, std::shared_ptr<const FaceModel>> models;
  auto it = models.find(key);
  if (it != models.end()) return it->second;
  auto m = buildThesisFace(scene, &cache());
  models[key] = m;
  return m;
}


// Nearest skin vertex to a point (cm).
int nearestSkinVertex(const FaceModel& model, const Vec3& p) {
  const MatX3& V = model.head().mesh.V;
  int best = 0;
  (V.rowwise() - p.transpose()).rowwise().squaredNorm().minCoeff(&best);
  return best;
}

// The skin vertex above a muscle's insertion.
int insertionSkinVertex(const FaceModel& model, const std::string& muscle) {
  return nearestSkinVertex(model, model.muscles()[static_cast<size_t>(model.muscleIndex(muscle))].muscle.insertionPoint);
}

Vec3 displacementAt(const Simulator& sim, int v) { return sim.skinDisplacement().row(v).transpose(); }
Vec3 up(const FaceModel& model) { return model.head().frame().axes.col(1); }
int landmark(const FaceModel& model, const std::string& name) { return model.head().landmarks.vertex(name); }

// Distance (cm) from a muscle's insertion ring centre (current positions) to its origin point.
double insertionToOrigin(const Simulator& sim, int m) {
  const Muscle& mu = sim.model().muscles()[static_cast<size_t>(m)].muscle;
  const MatX3 P = sim.musclePositions(m);
  const int ring = mu.def.ringNodes, last = mu.def.stations - 1;
  Vec3 c = Vec3::Zero();
  for (int k = 0; k < ring; ++k) c += P.row(last * ring + k).transpose();
  return (c / ring - mu.originPoint).norm();
}

double restInsertionToOrigin(const FaceModel& model, int m) {
  const Muscle& mu = model.muscles()[static_cast<size_t>(m)].muscle;
  return (mu.insertionPoint - mu.originPoint).norm();
}

// ---------------------------------------------------------------------------------------------
// Every scene file is valid (`myoshell check`), and one runs end to end through `myoshell run`.

// The CLI's stdout and stderr together.
test::CliResult runThesisCli(const std::string& args) {
  test::CliResult r = test::runCli(args);
  r.out = r.merged;
  return r;
}

TEST(ThesisScenes, EverySceneChecks) {
  const char* names[] = {"fig17_contract", "fig17_relax",    "fig18_zygomaticus", "fig18_depressor_labii",
                         "fig18_depressor_anguli", "fig20_corrugator", "fig22_gravity_sweep", "fig23_combined",
                         "fig25_drag",     "fig26_transition", "fig27_ict_head"};
  for (const char* n : names) {
    // Fig. 27's head is ICT's, from the shared data: without it that scene is left out, said here.
    if (std::string(n) == "fig27_ict_head" && !test::haveSharedData()) {
      std::printf("ThesisScenes.EverySceneChecks: %s left out: shared data not found at %s\n", n,
                  test::sharedDataDir().string().c_str());
      continue;
    }
    const test::CliResult r = runThesisCli("check '" + scenePath(n) + "'");
    EXPECT_EQ(r.exitCode, 0) << n << ": " << r.out;
  }
}

TEST(ThesisScenes, Fig17RunsThroughTheCli) {
  const fs::path out = fs::path(testing::TempDir()) / "myo_thesis_run_fig17";
  fs::remove_all(out);
  const test::CliResult r =
      runThesisCli("run '" + scenePath("fig17_contract") + "' --out '" + out.string() + "' --json --cache '" +
             cacheDir().string() + "'");
  ASSERT_EQ(r.exitCode, 0) << r.out;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["scene"], "fig17_contract");
  EXPECT_EQ(j["muscles"].size(), 8u);
  EXPECT_EQ(j["channels"].size(), 8u);  // one skin channel per muscle, no gravity
  EXPECT_TRUE(fs::exists(out / "stats.json"));
  fs::remove_all(out);
}

// ---------------------------------------------------------------------------------------------
// Fig. 17: the eight muscles alone contract (insertion towards the origin) and relax (away).

TEST(ThesisScenes, Fig17MusclesContractAndRelax) {
  const SceneDesc contract = readScene(scenePath("fig17_contract"));
  const SceneDesc relax = readScene(scenePath("fig17_relax"));
  const auto model = modelFor(contract, "fig17");  // both scenes describe the same face
  ASSERT_EQ(model->muscles().size(), 8u);
  ScenePlayer pa(contract, model), pb(relax, model);
  pa.playTo(0.6);
  pb.playTo(0.6);
  const auto& a = dynamic_cast<const Simulator&>(pa.simulator());
  const auto& b = dynamic_cast<const Simulator&>(pb.simulator());
  for (int m = 0; m < 8; ++m) {
    const double rest = restInsertionToOrigin(*model, m);
    const std::string& name = model->muscles()[static_cast<size_t>(m)].muscle.def.name;
    EXPECT_LT(insertionToOrigin(a, m), rest - 0.05 * rest) << name << " contracts";
    EXPECT_GT(insertionToOrigin(b, m), rest + 0.05 * rest) << name << " relaxes";
  }
}

// ---------------------------------------------------------------------------------------------
// Fig. 18: right side only (t < 1 s), then both sides.

// Σ|u| (cm) over the skin vertices on the subject's right (x < −0.3 cm in the face frame) and left.
std::pair<double, double> sideSums(const Simulator& sim) {
  const FaceModel& model = sim.model();
  const FaceFrame f = model.head().frame();
  const MatX3& V = model.head().mesh.V;
  double right = 0.0, left = 0.0;
  for (int v = 0; v < V.rows(); ++v) {
    const double x = (V.row(v).transpose() - f.origin).dot(f.axes.col(0));
    const double u = sim.skinDisplacement().row(v).norm();
    if (x < -0.3) right += u;
    if (x > 0.3) left += u;
  }
  return {right, left};
}

// The most displaced skin vertex on one side (sign −1: right, +1: left).
int mostDisplaced(const Simulator& sim, double sign) {
  const FaceFrame f = sim.model().head().frame();
  const MatX3& V = sim.model().head().mesh.V;
  int best = -1;
  double bestU = -1.0;
  for (int v = 0; v < V.rows(); ++v) {
    const double x = (V.row(v).transpose() - f.origin).dot(f.axes.col(0));
    const double u = sim.skinDisplacement().row(v).norm();
    if (sign * x > 0.3 && u > bestU) bestU = u, best = v;
  }
  return best;
}

// Right only until 1 s: the right half of the face moves (the way the muscle pulls, upSign: +1 up,
// −1 down), the left half hardly (the lower lip is one flap: some motion crosses the midline);
// then both sides: both halves move alike.
void checkRightThenBoth(const std::string& sceneName, double upSign) {
  const SceneDesc scene = readScene(scenePath(sceneName));
  const auto model = modelFor(scene, sceneName);
  ScenePlayer player(scene, model);
  auto& sim = dynamic_cast<Simulator&>(player.simulator());
  const Vec3 y = up(*model);
  player.playTo(0.95);
  const auto [r1, l1] = sideSums(sim);
  EXPECT_GT(r1, 1.0) << sceneName << ": the right side moves";
  EXPECT_LT(l1, 0.3 * r1) << sceneName << ": the left side stays (nearly)";
  const int vr = mostDisplaced(sim, -1.0);
  EXPECT_GT(upSign * displacementAt(sim, vr).dot(y), 0.05) << sceneName << ": direction of the right side";
  player.playTo(2.0);
  const auto [r2, l2] = sideSums(sim);
  EXPECT_GT(l2, 0.7 * r2) << sceneName << ": both sides move";
  EXPECT_LT(l2, 1.4 * r2) << sceneName << ": both sides move alike";
  const int vl = mostDisplaced(sim, +1.0);
  EXPECT_GT(upSign * displacementAt(sim, vl).dot(y), 0.05) << sceneName << ": direction of the left side";
}

TEST(ThesisScenes, Fig18ZygomaticusRightThenBoth) {
  checkRightThenBoth("fig18_zygomaticus", +1.0);
}
TEST(ThesisScenes, Fig18DepressorLabiiRightThenBoth) {
  checkRightThenBoth("fig18_depressor_labii", -1.0);
}
TEST(ThesisScenes, Fig18DepressorAnguliRightThenBoth) {
  checkRightThenBoth("fig18_depressor_anguli", -1.0);
}

// ---------------------------------------------------------------------------------------------
// Fig. 20: the corrugators contract (to 1 s), then relax (activation −1, to 2 s).

TEST(ThesisScenes, Fig20CorrugatorContractsThenRelaxes) {
  const SceneDesc scene = readScene(scenePath("fig20_corrugator"));
  const auto model = modelFor(scene, "fig20_corrugator");
  ScenePlayer player(scene, model);
  auto& sim = dynamic_cast<Simulator&>(player.simulator());
  const int m = model->muscleIndex("corrugator_supercilii_right");
  const double rest = restInsertionToOrigin(*model, m);
  const int v = insertionSkinVertex(*model, "corrugator_supercilii_right");
  player.playTo(0.95);
  EXPECT_LT(insertionToOrigin(sim, m), rest);
  const Vec3 contracted = displacementAt(sim, v);
  EXPECT_GT(contracted.norm(), 0.02);
  player.playTo(2.0);
  EXPECT_GT(insertionToOrigin(sim, m), rest);
  const Vec3 relaxed = displacementAt(sim, v);
  EXPECT_GT(relaxed.norm(), 0.02);
  EXPECT_LT(contracted.dot(relaxed), 0.0) << "relaxation moves the brow the other way";
}

// ---------------------------------------------------------------------------------------------
// Fig. 22: the same gravity on a skin ever softer: the sag grows as the stiffness falls.

TEST(ThesisScenes, Fig22GravitySagGrowsAsStiffnessFalls) {
  const SceneDesc base = readScene(scenePath("fig22_gravity_sweep"));
  double previous = 0.0;
  for (double scale : {1.0, 0.5, 0.25}) {
    SceneDesc scene = base;
    scene.model.skin.kA *= scale;
    scene.model.skin.kL *= scale;
    scene.model.skin.kB *= scale;
    const auto model = modelFor(scene, "fig22@" + std::to_string(scale));
    ASSERT_GE(model->gravityChannel(), 0);
    ScenePlayer player(scene, model);
    auto& sim = dynamic_cast<Simulator&>(player.simulator());
    player.playTo(scene.duration);
    const MatX3 u = sim.channelDisplacement(model->gravityChannel());
    const double sag = u.rowwise().norm().maxCoeff();
    const double meanDown = -(u * up(*model)).mean();
    EXPECT_GT(meanDown, 0.0) << "gravity pulls the skin down (scale " << scale << ")";
    EXPECT_GT(sag, previous * 1.2) << "stiffness scale " << scale;
    previous = sag;
  }
}

// ---------------------------------------------------------------------------------------------
// Fig. 23: zygomaticus major + depressor labii inferioris: the lower lip down, the corners up.

TEST(ThesisScenes, Fig23CombinedSmileOpensTheLowerLip) {
  const SceneDesc scene = readScene(scenePath("fig23_combined"));
  const auto model = modelFor(scene, "fig23_combined");
  ScenePlayer player(scene, model);
  auto& sim = dynamic_cast<Simulator&>(player.simulator());
  player.playTo(scene.duration);
  const Vec3 y = up(*model);
  EXPECT_LT(displacementAt(sim, insertionSkinVertex(*model, "depressor_labii_inferioris_right")).dot(y), -0.02);
  EXPECT_LT(displacementAt(sim, insertionSkinVertex(*model, "depressor_labii_inferioris_left")).dot(y), -0.02);
  EXPECT_GT(displacementAt(sim, landmark(*model, "mouth_corner_right")).dot(y), 0.02);
  EXPECT_GT(displacementAt(sim, landmark(*model, "mouth_corner_left")).dot(y), 0.02);
}

// ---------------------------------------------------------------------------------------------
// Fig. 24–25: a drag on the right cheek plus the right zygomaticus major: the cheek moves along
// the force, the mouth corner rises.

TEST(ThesisScenes, Fig25DragMovesTheCheekAlongTheForce) {
  const SceneDesc scene = readScene(scenePath("fig25_drag"));
  const auto model = modelFor(scene, "fig25_drag");
  ASSERT_EQ(scene.drags.size(), 1u);
  ScenePlayer player(scene, model);
  auto& sim = dynamic_cast<Simulator&>(player.simulator());
  player.playTo(scene.duration);
  const Vec3 force = scene.dragForces.at(scene.drags[0].name).at(scene.duration);
  int dragChannel = -1;
  for (size_t c = 0; c < model->channels().size(); ++c)
    if (model->channels()[c].kind == ChannelKind::Drag) dragChannel = static_cast<int>(c);
  ASSERT_GE(dragChannel, 0);
  const int v = scene.drags[0].vertex;
  const Vec3 uDrag = sim.channelDisplacement(dragChannel).row(v).transpose();
  EXPECT_GT(uDrag.dot(force.normalized()), 0.1) << "the cheek follows the drag";
  EXPECT_GT(displacementAt(sim, v).dot(force.normalized()), 0.1);
  EXPECT_GT(displacementAt(sim, landmark(*model, "mouth_corner_right")).dot(up(*model)), 0.02);
}

// ---------------------------------------------------------------------------------------------
// Fig. 26: t0→t1 the zygomaticus lifts the corner, t1→t2 it relaxes back to neutral, t2→t3 the
// depressor anguli oris pulls it down.

TEST(ThesisScenes, Fig26TransitionUpNeutralDown) {
  const SceneDesc scene = readScene(scenePath("fig26_transition"));
  const auto model = modelFor(scene, "fig26_transition");
  ScenePlayer player(scene, model);
  auto& sim = dynamic_cast<Simulator&>(player.simulator());
  const int corner = landmark(*model, "mouth_corner_right");
  const Vec3 y = up(*model);
  player.playTo(0.6);
  const Vec3 t1 = displacementAt(sim, corner);
  EXPECT_GT(t1.dot(y), 0.03) << "t1: corner up";
  player.playTo(1.2);
  const Vec3 t2 = displacementAt(sim, corner);
  EXPECT_LT(t2.norm(), 0.25 * t1.norm()) << "t2: back near rest";
  player.playTo(1.8);
  EXPECT_LT(displacementAt(sim, corner).dot(y), -0.03) << "t3: corner down";
}

// ---------------------------------------------------------------------------------------------
// Fig. 27: the same on the ICT head (a user's mesh).

TEST(ThesisScenes, Fig27IctHeadSmileFrownAndCombined) {
  MYO_REQUIRE_SHARED_DATA();
  const SceneDesc scene = readScene(scenePath("fig27_ict_head"));
  const auto model = modelFor(scene, "fig27_ict_head");
  EXPECT_GT(model->skin().vertexCount(), 10000);
  ScenePlayer player(scene, model);
  auto& sim = dynamic_cast<Simulator&>(player.simulator());
  const int corner = landmark(*model, "mouth_corner_right");
  const Vec3 y = up(*model);
  player.playTo(0.6);
  EXPECT_GT(displacementAt(sim, corner).dot(y), 0.02) << "zygomaticus major: corner up";
  player.playTo(1.5);
  EXPECT_LT(displacementAt(sim, corner).dot(y), -0.02) << "depressor anguli oris: corner down";
  player.playTo(scene.duration);
  EXPECT_GT(displacementAt(sim, corner).dot(y), 0.02) << "combined: corner up";
  EXPECT_LT(displacementAt(sim, insertionSkinVertex(*model, "depressor_labii_inferioris_right")).dot(y), -0.02)
      << "combined: lower lip down";
}

}  // namespace
}  // namespace myo
