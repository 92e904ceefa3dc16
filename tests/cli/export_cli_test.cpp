// `myoshell run --format`: GLB, PC2 and OBJ exports of one run agree; unknown formats are errors.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <tiny_gltf.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "myoshell/io/animation_export.h"
#include "myoshell/mesh/obj_reader.h"
#include "support/cli_runner.h"
#include "support/scratch_folder.h"

namespace myo {
namespace {

namespace fs = std::filesystem;

class ExportCommand : public test::ScratchFolderTest {
 protected:
  void SetUp() override {
    ScratchFolderTest::SetUp();
    write("small.json", test::kSmallScene);
  }
  std::string run(const std::string& out, const std::string& extra) const {
    return "run '" + (dir_ / "small.json").string() + "' --out '" + (dir_ / out).string() + "'" + cacheArg() + " " +
           extra;
  }
};

TEST_F(ExportCommand, WritesGlbPc2AndObjThatAgree) {
  const auto r = test::runCli(run("out", "--format glb,pc2,obj"));
  ASSERT_EQ(r.exitCode, 0) << r.merged;
  const fs::path out = dir_ / "out";
  ASSERT_TRUE(fs::exists(out / "small.glb"));
  ASSERT_TRUE(fs::exists(out / "small.pc2"));
  ASSERT_TRUE(fs::exists(out / "obj" / "small_0002.obj"));
  for (const auto& e : fs::recursive_directory_iterator(out))
    EXPECT_NE(e.path().extension(), ".tmp") << "half-written file left: " << e.path();

  const TriMesh first = readObj((out / "obj" / "small_0000.obj").string());
  const TriMesh last = readObjLike((out / "obj" / "small_0002.obj").string(), first);
  const PointCache pc = readPc2(out / "small.pc2");
  EXPECT_EQ(pc.numPoints, first.vertexCount());
  ASSERT_EQ(pc.samples.size(), 3u);
  EXPECT_LT((pc.samples.back() - last.V).cwiseAbs().maxCoeff(), 1e-5);
  EXPECT_GT((pc.samples.back() - pc.samples.front()).rowwise().norm().maxCoeff(), 0.01);

  tinygltf::Model m;
  tinygltf::TinyGLTF loader;
  std::string err, warn;
  ASSERT_TRUE(loader.LoadBinaryFromFile(&m, &err, &warn, (out / "small.glb").string())) << err;
  ASSERT_EQ(m.meshes.size(), 1u);
  EXPECT_EQ(m.accessors[m.meshes[0].primitives[0].attributes.at("POSITION")].count,
            static_cast<size_t>(first.vertexCount()));
  const size_t targets = m.meshes[0].primitives[0].targets.size();
  EXPECT_GE(targets, 1u);
  EXPECT_LE(targets, 3u);  // at most one per frame
  EXPECT_EQ(m.animations.size(), 1u);
  // stats.json (and --json) say what the GLB holds: its targets, every frame's largest error, the rate.
  std::ifstream statsFile(out / "stats.json");
  const nlohmann::json stats = nlohmann::json::parse(statsFile);
  ASSERT_TRUE(stats.contains("glb")) << stats.dump(2);
  EXPECT_EQ(stats["glb"]["targets"].get<size_t>(), targets);
  EXPECT_EQ(stats["glb"]["frames"].get<int>(), 3);
  EXPECT_EQ(stats["glb"]["fps"].get<double>(), m.animations[0].extras.Get("fps").GetNumberAsDouble());
  EXPECT_LE(stats["glb"]["max_error_mm"].get<double>(), 0.05);
  EXPECT_TRUE(stats["glb"]["within_tolerance"].get<bool>());
  EXPECT_EQ(stats["units"], "cm");
}

// --glb-tolerance trades the GLB's morph targets for its error: a loose bound keeps fewer targets, every
// frame still within it, and stats.json says which bound was asked for.
TEST_F(ExportCommand, GlbToleranceTradesTargetsForTheLargestError) {
  auto glb = [&](const std::string& out, const std::string& tolerance) {
    const auto r = test::runCli(run(out, "--format glb --glb-tolerance " + tolerance));
    EXPECT_EQ(r.exitCode, 0) << r.merged;
    std::ifstream statsFile(dir_ / out / "stats.json");
    return nlohmann::json::parse(statsFile)["glb"];
  };
  const nlohmann::json tight = glb("tight", "0.0001"), loose = glb("loose", "10");
  EXPECT_EQ(tight["tolerance_mm"].get<double>(), 0.0001);
  EXPECT_EQ(loose["tolerance_mm"].get<double>(), 10.0);
  EXPECT_LE(tight["max_error_mm"].get<double>(), 0.0001);
  EXPECT_LE(loose["max_error_mm"].get<double>(), 10.0);
  EXPECT_TRUE(tight["within_tolerance"].get<bool>() && loose["within_tolerance"].get<bool>());
  EXPECT_LT(loose["targets"].get<int>(), tight["targets"].get<int>()) << tight.dump() << loose.dump();
  EXPECT_GT(loose["max_error_mm"].get<double>(), tight["max_error_mm"].get<double>());
}

TEST_F(ExportCommand, ABadGlbToleranceExitsTwoNamingTheOption) {
  for (const std::string bad : {"0", "-1", "nan", "fine"}) {
    const auto r = test::runCli(run("out", "--format glb --glb-tolerance " + bad));
    EXPECT_EQ(r.exitCode, 2) << bad << ": " << r.merged;
    EXPECT_NE(r.merged.find("--glb-tolerance"), std::string::npos) << r.merged;
    EXPECT_NE(r.merged.find("> 0"), std::string::npos) << r.merged;
    EXPECT_FALSE(fs::exists(dir_ / "out")) << bad;
  }
}

TEST_F(ExportCommand, OnlyTheRequestedFormatsAreWritten) {
  const auto r = test::runCli(run("out", "--format pc2"));
  ASSERT_EQ(r.exitCode, 0) << r.merged;
  EXPECT_TRUE(fs::exists(dir_ / "out" / "small.pc2"));
  EXPECT_FALSE(fs::exists(dir_ / "out" / "small.glb"));
  EXPECT_FALSE(fs::exists(dir_ / "out" / "obj"));
  EXPECT_TRUE(fs::exists(dir_ / "out" / "stats.json"));
}

TEST_F(ExportCommand, UnknownFormatExitsTwoNamingIt) {
  const auto r = test::runCli(run("out", "--format glb,fbx"));
  EXPECT_EQ(r.exitCode, 2) << r.merged;
  EXPECT_NE(r.merged.find("unknown export format 'fbx'"), std::string::npos) << r.merged;
  EXPECT_FALSE(fs::exists(dir_ / "out" / "small.glb"));
}

}  // namespace
}  // namespace myo
