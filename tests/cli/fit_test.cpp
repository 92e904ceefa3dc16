// `myoshell fit`: activations from a target shape, a rig's shape or markers. The target of the
// recovery test is made by `pose` from known activations of three muscles in three regions; the
// markers test moves and turns 68 landmarks of that target. Bad arguments fail before the build.
// Every run shares ctest's basis cache ($MYOSHELL_CACHE): one model build for the file.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "myoshell/head/head.h"
#include "myoshell/mesh/obj_reader.h"
#include "support/cli_runner.h"
#include "support/test_data.h"

namespace myo {
namespace {

using ::testing::HasSubstr;
namespace fs = std::filesystem;

fs::path fitScratch(const std::string& name) {
  const fs::path p = fs::path(testing::TempDir()) / ("myo_fit_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(p);
  fs::create_directories(p);
  return p;
}

std::string fitQuoted(const fs::path& p) { return "'" + p.string() + "'"; }

// Three muscles in three regions of the face (mouth corner, brow, lower lip) at known activations.
const std::vector<std::pair<std::string, double>> kTruth = {
    {"zygomaticus_major_left", 0.6}, {"corrugator_supercilii_right", 0.3}, {"depressor_labii_inferioris_left", 0.5}};

// The target: pose at the true activations, gravity off (fit compares gravity-free shapes).
fs::path makeTarget(const fs::path& dir) {
  std::string sets;
  for (const auto& [name, a] : kTruth) sets += " --set " + name + "=" + std::to_string(a);
  const fs::path target = dir / "target.obj";
  const test::CliResult r = test::runCli("pose --gravity off" + sets + " --out " + fitQuoted(target));
  EXPECT_EQ(r.exitCode, 0) << r.merged;
  return target;
}

// The settled shape at a fit's activations (pose), minus the rest mesh: n×3, cm.
MatX3 poseOf(const nlohmann::json& activations, const fs::path& out, const TriMesh& rest) {
  std::string sets;
  for (const auto& [name, a] : activations.items()) {
    std::ostringstream value;
    value.precision(17);
    value << a.get<double>();
    sets += " --set " + name + "=" + value.str();
  }
  const test::CliResult r = test::runCli("pose --gravity off" + sets + " --out " + fitQuoted(out));
  EXPECT_EQ(r.exitCode, 0) << r.merged;
  return readObj(out.string()).V - rest.V;
}

TEST(Fit, RecoversKnownActivationsOfThreeMusclesFromTheirShape) {
  const fs::path dir = fitScratch("recover");
  const fs::path target = makeTarget(dir);
  const test::CliResult r = test::runCli("fit " + fitQuoted(target) + " --lambda 0 --json --out " + fitQuoted(dir / "fit.json"));
  ASSERT_EQ(r.exitCode, 0) << r.merged;
  const auto j = nlohmann::json::parse(r.out);
  // The file holds what was printed.
  std::ifstream in(dir / "fit.json");
  EXPECT_EQ(nlohmann::json::parse(in)["activations"], j["activations"]);
  ASSERT_EQ(j["activations"].size(), 40u);  // the whole face, the default
  for (const auto& [name, value] : j["activations"].items()) {
    double truth = 0.0;
    for (const auto& [n, a] : kTruth)
      if (n == name) truth = a;
    EXPECT_NEAR(value.get<double>(), truth, 0.02) << name;
  }
  EXPECT_LE(j["rms_mm"].get<double>(), 0.1);
  EXPECT_GT(j["cosine"].get<double>(), 0.999);
  EXPECT_NEAR(j["magnitude_ratio"].get<double>(), 1.0, 0.01);
  EXPECT_GT(j["condition_number"].get<double>(), 1.0);
  EXPECT_EQ(j["kind"], "obj");
  EXPECT_EQ(j["name"], "target");  // the keys of a fit-rig shape: name (the file's stem), reachable, reason
  EXPECT_EQ(j["reachable"], true);
  EXPECT_EQ(j["reason"], "");
  EXPECT_EQ(j["jaw"], nlohmann::json::object());
  RecordProperty("condition_number", std::to_string(j["condition_number"].get<double>()));
  RecordProperty("fit_seconds", std::to_string(j["fit_seconds"].get<double>()));

  // Fitting one muscle only leaves the others at zero.
  const test::CliResult one = test::runCli("fit " + fitQuoted(target) + " --muscles zygomaticus_major_left --json");
  ASSERT_EQ(one.exitCode, 0) << one.merged;
  const auto k = nlohmann::json::parse(one.out);
  for (const auto& [name, value] : k["activations"].items())
    if (name != "zygomaticus_major_left") EXPECT_EQ(value.get<double>(), 0.0) << name;
  EXPECT_GT(k["activations"]["zygomaticus_major_left"].get<double>(), 0.3);
}

TEST(Fit, SixtyEightMovedAndTurnedMarkersFitAlmostAsWellAsTheWholeShape) {
  const fs::path dir = fitScratch("markers");
  const fs::path target = makeTarget(dir);
  const Head head = loadDefaultHead();
  const TriMesh shape = readObj(target.string());
  const MatX3 e = shape.V - head.mesh.V;

  // The 68 landmark vertices where the target puts them, turned 12° about a tilted axis, moved, in mm.
  const Mat3 R = Eigen::AngleAxisd(12.0 * M_PI / 180.0, Vec3(0.3, 1.0, 0.2).normalized()).toRotationMatrix();
  const Vec3 t(1.5, -2.0, 4.0);  // cm
  nlohmann::json markers;
  markers["units"] = "mm";
  for (const int vertex : head.landmarks.multipie68) {
    const Vec3 p = R * shape.V.row(vertex).transpose() + t;
    markers["markers"].push_back({{"vertex", vertex}, {"position", {10 * p.x(), 10 * p.y(), 10 * p.z()}}});
  }
  ASSERT_EQ(markers["markers"].size(), 68u);
  std::ofstream(dir / "markers.json") << markers.dump(1);

  const test::CliResult dense = test::runCli("fit " + fitQuoted(target) + " --json");
  ASSERT_EQ(dense.exitCode, 0) << dense.merged;
  const test::CliResult sparse = test::runCli("fit " + fitQuoted(dir / "markers.json") + " --align rigid --json");
  ASSERT_EQ(sparse.exitCode, 0) << sparse.merged;
  const auto jd = nlohmann::json::parse(dense.out), jm = nlohmann::json::parse(sparse.out);
  EXPECT_EQ(jm["kind"], "markers");
  EXPECT_EQ(jm["markers"], 68);
  EXPECT_GT(jm["compared_vertices"].get<int>(), 0);  // the landmarks that move more than 0.5 mm
  EXPECT_LE(jm["compared_vertices"].get<int>(), 68);
  // The whole face at each fit's activations against the target: the markers' error within 1.5× of
  // the dense fit's (both fitted with the default sparsity weight).
  const MatX3 ud = poseOf(jd["activations"], dir / "dense.obj", head.mesh);
  const MatX3 um = poseOf(jm["activations"], dir / "markers.obj", head.mesh);
  const double errDense = std::sqrt((ud - e).squaredNorm() / static_cast<double>(e.rows()));
  const double errMarkers = std::sqrt((um - e).squaredNorm() / static_cast<double>(e.rows()));
  RecordProperty("dense_rms_all_vertices_mm", std::to_string(10 * errDense));
  RecordProperty("markers_rms_all_vertices_mm", std::to_string(10 * errMarkers));
  EXPECT_LE(errMarkers, 1.5 * errDense + 1e-4);
  EXPECT_LT(errMarkers, 0.1 * std::sqrt(e.squaredNorm() / static_cast<double>(e.rows())));
}

TEST(Fit, BadArgumentsFailBeforeTheBuildWithTheirMessage) {
  const fs::path dir = fitScratch("bad");
  std::ofstream(dir / "three.json") << R"({"units": "cm", "markers": [{"vertex": 1, "position": [0, 0, 0]},
    {"vertex": 2, "position": [0, 1, 0]}, {"vertex": 3, "position": [1, 0, 0]}]})";
  std::ofstream(dir / "far.json") << R"({"units": "cm", "markers": [{"vertex": 99999999, "position": [0, 0, 0]}]})";
  const std::string three = fitQuoted(dir / "three.json");
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"fit " + three + " --align affine", "myoshell: error: --align: 'affine' is not one of none, rigid, similarity\n"},
      {"fit " + three + " --lambda -1", "myoshell: error: --lambda: '-1' is not a number ≥ 0\n"},
      {"fit " + three + " --lambda x", "myoshell: error: --lambda: 'x' is not a number ≥ 0\n"},
      {"fit " + three + " --muscles a,,b", "myoshell: error: --muscles 'a,,b': an empty name (names are separated by single commas)\n"},
      {"fit " + three + " --align similarity",
       "myoshell: error: " + (dir / "three.json").string() + ": --align similarity needs at least 4 markers; the file has 3\n"},
      {"fit " + fitQuoted(dir / "none.obj"),
       "myoshell: error: " + (dir / "none.obj").string() + ": no such target file: give an OBJ of the head, RIG.glb#shape or a marker file\n"},
      {"fit " + three + " --out " + fitQuoted(dir / "no" / "fit.json"), "myoshell: error: --out: no such folder '" + (dir / "no").string() + "'\n"},
  };
  for (const auto& [args, message] : cases) {
    const test::CliResult r = test::runCli(args);
    EXPECT_EQ(r.exitCode, 2) << args;
    EXPECT_EQ(r.err, message) << args;
    EXPECT_EQ(r.out, "") << args;
  }
  const test::CliResult unknown = test::runCli("fit " + three + " --muscles orbicularis_oris");
  EXPECT_EQ(unknown.exitCode, 2);
  EXPECT_THAT(unknown.err, HasSubstr("--muscles: unknown muscle 'orbicularis_oris' (the anatomical model's muscles: "));
  const test::CliResult far = test::runCli("fit " + fitQuoted(dir / "far.json"));
  EXPECT_EQ(far.exitCode, 2);
  EXPECT_THAT(far.err, HasSubstr("far.json:1:40: key 'markers[0].vertex': vertex 99999999 is outside [0, "));
  EXPECT_FALSE(fs::exists(dir / "no"));
}

// (Without --head and --landmarks the rig's own base is the head, its landmarks found automatically:
// AutoLandmarksCli.AGltfRigsBaseWithoutLandmarksIsFoundKeptAndReused.)
TEST(Fit, AnIctRigShapeNeedsAShapeTheRigHasAndAHeadOfItsSize) {
  MYO_REQUIRE_SHARED_DATA();
  const fs::path rig = test::sharedDataDir() / "ict" / "ict_arkit_rig.glb";
  const test::CliResult units = test::runCli("fit '" + rig.string() + "#mouthSmile_L' --units mm");
  EXPECT_EQ(units.exitCode, 2);
  EXPECT_EQ(units.err, "myoshell: error: --units: a glTF rig is in metres by specification and read in cm; --units "
                       "applies to an OBJ head\n");
  const test::CliResult none = test::runCli("fit '" + rig.string() + "#mouthGrin_L' --head default");
  EXPECT_EQ(none.exitCode, 2);
  EXPECT_THAT(none.err, HasSubstr("no shape 'mouthGrin_L'"));
  const test::CliResult other = test::runCli("fit '" + rig.string() + "#mouthSmile_L' --head default");
  EXPECT_EQ(other.exitCode, 2);
  EXPECT_THAT(other.err, HasSubstr("the rig's base has 11248 vertices and the head "));
}

}  // namespace
}  // namespace myo
