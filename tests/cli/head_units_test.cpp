// Heads checked where they are loaded (docs/heads.md, "Checks on load"): ICT written in metres is
// refused with the --units proposal, accepted with --units m (the same head and the same motion as
// in cm, its OBJ frames and PC2 written in metres), and the built-in head's landmarks on ICT's mesh are refused naming a landmark.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "myoshell/head/head.h"
#include "myoshell/io/animation_export.h"
#include "myoshell/io/obj_writer.h"
#include "myoshell/mesh/obj_reader.h"
#include "support/cli_runner.h"

namespace myo {
namespace {

using ::testing::HasSubstr;
namespace fs = std::filesystem;

fs::path unitsScratch(const std::string& name) {
  const fs::path p = fs::path(testing::TempDir()) / ("myo_head_units_" + name);
  fs::remove_all(p);
  fs::create_directories(p);
  return p;
}

fs::path ictDir() { return test::sharedDataDir() / "ict"; }

// Copies an OBJ with every vertex position multiplied by `factor` (17 significant digits).
void writeScaledObj(const fs::path& from, const fs::path& to, double factor) {
  std::ifstream in(from);
  std::ofstream out(to);
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("v ", 0) == 0) {
      std::istringstream s(line.substr(2));
      double x, y, z;
      s >> x >> y >> z;
      char buf[128];
      std::snprintf(buf, sizeof buf, "v %.17g %.17g %.17g", x * factor, y * factor, z * factor);
      out << buf << "\n";
    } else {
      out << line << "\n";
    }
  }
}

// The vertex positions of an OBJ, in file order.
std::vector<double> objVertices(const fs::path& p) {
  std::ifstream in(p);
  std::vector<double> v;
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("v ", 0) == 0) {
      std::istringstream s(line.substr(2));
      double x, y, z;
      s >> x >> y >> z;
      v.insert(v.end(), {x, y, z});
    }
  return v;
}

// max |a − b| / max |b|.
double relativeDifference(const std::vector<double>& a, const std::vector<double>& b) {
  EXPECT_EQ(a.size(), b.size());
  double diff = 0.0, scale = 0.0;
  for (size_t i = 0; i < a.size() && i < b.size(); ++i) {
    diff = std::max(diff, std::abs(a[i] - b[i]));
    scale = std::max(scale, std::abs(b[i]));
  }
  return diff / scale;
}

TEST(HeadUnits, IctInMetresIsRefusedThenAcceptedWithUnitsM) {
  MYO_REQUIRE_SHARED_DATA();
  const fs::path dir = unitsScratch("ict_m");
  writeScaledObj(ictDir() / "head_skin.obj", dir / "ict_m.obj", 0.01);
  const std::string lm = " --landmarks '" + (ictDir() / "landmarks_multipie68.json").string() + "'";

  const test::CliResult refused = test::runCli("head '" + (dir / "ict_m.obj").string() + "'" + lm + " --json");
  EXPECT_EQ(refused.exitCode, 2) << refused.merged;
  EXPECT_THAT(refused.err, HasSubstr("ict_m.obj: head scale: outer-canthus distance (right_eye_outer to "
                                     "left_eye_outer) is 0.0892 cm with the mesh read in cm"));
  EXPECT_THAT(refused.err, HasSubstr("in m it would be 8.92 cm"));
  EXPECT_THAT(refused.err, HasSubstr("--units m|mm|cm (scene key head.units): probably --units m"));
  EXPECT_EQ(refused.out, "");

  // With --units m the loaded head is ICT in cm (to the digits the OBJ writer keeps).
  const test::CliResult cm = test::runCli("head '" + (ictDir() / "head_skin.obj").string() + "'" + lm +
                                          " --json --write-obj '" + (dir / "cm.obj").string() + "'");
  const test::CliResult m = test::runCli("head '" + (dir / "ict_m.obj").string() + "'" + lm +
                                         " --units m --json --write-obj '" + (dir / "m.obj").string() + "'");
  ASSERT_EQ(cm.exitCode, 0) << cm.merged;
  ASSERT_EQ(m.exitCode, 0) << m.merged;
  EXPECT_LE(relativeDifference(objVertices(dir / "m.obj"), objVertices(dir / "cm.obj")), 1e-6);
  const auto jm = nlohmann::json::parse(m.out), jcm = nlohmann::json::parse(cm.out);
  EXPECT_NEAR(jm["frame"]["scale"].get<double>(), jcm["frame"]["scale"].get<double>(),
              1e-6 * jcm["frame"]["scale"].get<double>());
}

TEST(HeadUnits, IctInMetresMovesAsInCentimetres) {
  MYO_REQUIRE_SHARED_DATA();
  const fs::path dir = unitsScratch("ict_motion");
  writeScaledObj(ictDir() / "head_skin.obj", dir / "ict_m.obj", 0.01);
  auto scene = [&](const std::string& obj, const std::string& units) {
    nlohmann::json j = {
        {"name", "u"},
        {"model", "thesis"},
        {"head", {{"obj", obj}, {"landmarks", (ictDir() / "landmarks_multipie68.json").string()},
                  {"gravity_pins", (ictDir() / "rigid_vertices.json").string()}}},
        {"muscles", {{"use", {"zygomaticus_major_left"}}}},
        {"gravity", {{"enabled", false}}},
        {"numerics", {{"skin_modes", 6}, {"precision", "double"}}},
        {"duration", 0.1},
        {"fps", 10},
        {"timeline", {{"activations", {{"zygomaticus_major_left", {{{"t", 0}, {"value", 1}}}}}}}}};
    if (!units.empty()) j["head"]["units"] = units;
    const fs::path p = dir / ("scene_" + (units.empty() ? std::string("cm") : units) + ".json");
    std::ofstream(p) << j.dump(2);
    return p;
  };
  const fs::path sceneCm = scene((ictDir() / "head_skin.obj").string(), "");
  const fs::path sceneM = scene((dir / "ict_m.obj").string(), "m");
  for (const auto& [s, out] : {std::pair{sceneCm, dir / "out_cm"}, std::pair{sceneM, dir / "out_m"}}) {
    const test::CliResult r = test::runCli("run '" + s.string() + "' --out '" + out.string() + "' --cache '" +
                                           (dir / "cache").string() + "' --format obj,pc2,glb");
    ASSERT_EQ(r.exitCode, 0) << r.merged;
  }
  // The OBJ frames and the PC2 are in the head's own unit: the run in metres writes the run in cm's
  // positions × 0.01; the last frame's displacement from the rest head agrees to 1e-6 relative.
  auto lastFrame = [&](const fs::path& out) {
    std::vector<fs::path> frames;
    for (const auto& e : fs::directory_iterator(out / "obj")) frames.push_back(e.path());
    std::sort(frames.begin(), frames.end());
    return objVertices(frames.back());
  };
  const std::vector<double> restCm = objVertices(ictDir() / "head_skin.obj"), restM = objVertices(dir / "ict_m.obj");
  const std::vector<double> lastCm = lastFrame(dir / "out_cm"), lastM = lastFrame(dir / "out_m");
  ASSERT_EQ(lastM.size(), lastCm.size());
  std::vector<double> uCm(lastCm.size()), uMinCm(lastM.size()), lastCmInM(lastCm.size());
  for (size_t i = 0; i < lastCm.size(); ++i) {
    uCm[i] = lastCm[i] - restCm[i];
    uMinCm[i] = 100.0 * (lastM[i] - restM[i]);
    lastCmInM[i] = 0.01 * lastCm[i];
  }
  double peak = 0.0;
  for (double x : uCm) peak = std::max(peak, std::abs(x));
  EXPECT_GT(peak, 0.01);  // the muscle moved the skin (cm)
  EXPECT_LE(relativeDifference(uMinCm, uCm), 1e-6);
  EXPECT_LE(relativeDifference(lastM, lastCmInM), 1e-9);
  // The PC2, every frame (float32: to 1e-6 relative).
  const PointCache pcCm = readPc2(dir / "out_cm" / "u.pc2"), pcM = readPc2(dir / "out_m" / "u.pc2");
  ASSERT_EQ(pcM.samples.size(), pcCm.samples.size());
  for (size_t f = 0; f < pcCm.samples.size(); ++f)
    EXPECT_LE((pcM.samples[f] - 0.01 * pcCm.samples[f]).cwiseAbs().maxCoeff(), 1e-6 * 0.01 * pcCm.samples[f].cwiseAbs().maxCoeff())
        << "frame " << f;
  // stats.json names the unit; the GLB is in metres for both.
  for (const auto& [out, unit] : {std::pair{dir / "out_cm", "cm"}, std::pair{dir / "out_m", "m"}}) {
    std::ifstream statsFile(out / "stats.json");
    const nlohmann::json stats = nlohmann::json::parse(statsFile);
    EXPECT_EQ(stats["units"], unit);
    EXPECT_LE(stats["glb"]["max_error_mm"].get<double>(), 0.05);
  }
}

// `drive --units m`: the OBJ frames and the PC2 of a head in metres are in metres, the simulation's
// cm × 0.01 — each frame's largest displacement from the file's rest, × 100, is the cm figure
// stats.json reports for it — and the OBJ frames and the PC2 hold the same positions.
TEST(HeadUnits, DriveWithUnitsMWritesObjAndPc2InMetres) {
  const fs::path dir = unitsScratch("drive_m");
  const Head head = loadDefaultHead();
  const MatX3 metres = head.mesh.V * 0.01;
  writeObj((dir / "head_m.obj").string(), head.mesh, &metres);
  std::ofstream(dir / "landmarks.json") << defaultHeadLandmarkJson();
  {
    std::ofstream take(dir / "take.csv");
    take << "timestamp,AU12_r,AU04_r\n";
    for (int k = 0; k < 5; ++k) take << k / 30.0 << "," << 0.2 * k << "," << 0.1 * (4 - k) << "\n";
  }
  const test::CliResult r = test::runCli(
      "drive '" + (dir / "take.csv").string() + "' --head '" + (dir / "head_m.obj").string() + "' --landmarks '" +
      (dir / "landmarks.json").string() + "' --units m --library builtin --format obj,pc2,glb --out '" +
      (dir / "out").string() + "' --cache '" + (dir / "cache").string() + "' --json");
  ASSERT_EQ(r.exitCode, 0) << r.merged;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["units"], "m");
  EXPECT_LE(j["glb"]["max_error_mm"].get<double>(), 0.05);
  std::ifstream statsFile(dir / "out" / "stats.json");
  const nlohmann::json stats = nlohmann::json::parse(statsFile);
  const PointCache pc = readPc2(dir / "out" / "take.pc2");
  ASSERT_EQ(pc.samples.size(), 5u);
  ASSERT_EQ(stats["per_frame"].size(), 5u);
  double moved = 0.0;
  for (int f = 0; f < 5; ++f) {
    const MatX3 obj = readObj((dir / "out" / "obj" / ("take_000" + std::to_string(f) + ".obj")).string()).V;
    const double peakCm = stats["per_frame"][f]["max_displacement_cm"].get<double>();
    EXPECT_NEAR(100.0 * (obj - metres).rowwise().norm().maxCoeff(), peakCm, 1e-9 + 1e-6 * peakCm) << f;
    EXPECT_LT((pc.samples[f] - obj).cwiseAbs().maxCoeff(), 1e-7) << f;  // float32 of metres
    moved = std::max(moved, peakCm);
  }
  EXPECT_GT(moved, 0.05);  // the smile moved the skin (cm)
}

TEST(HeadUnits, TheBuiltInLandmarksOnTheIctMeshAreRefused) {
  MYO_REQUIRE_SHARED_DATA();
  const fs::path dir = unitsScratch("builtin_lm");
  ASSERT_EQ(test::runCli("head --write-landmarks '" + (dir / "builtin.json").string() + "'").exitCode, 0);
  const test::CliResult r = test::runCli("head '" + (ictDir() / "head_skin.obj").string() + "' --landmarks '" +
                                         (dir / "builtin.json").string() + "'");
  EXPECT_EQ(r.exitCode, 2) << r.merged;
  EXPECT_THAT(r.err, HasSubstr("builtin.json: landmark 'right_eye_inner' (vertex 133) does not fit mesh "));
  EXPECT_THAT(r.err, HasSubstr("is this the landmark file of another mesh?"));
}

TEST(HeadUnits, UnitsApplyToOBJHeadsOnly) {
  const test::CliResult r = test::runCli("head --units m");
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_THAT(r.err, HasSubstr("--landmarks, --pins and --units apply to an OBJ head, not the default head"));
}

}  // namespace
}  // namespace myo
