// `myoshell run`, `check` and `demo`: outputs, pictures, and errors that name file, line and key.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "myoshell/mesh/obj_reader.h"
#include "support/cli_runner.h"
#include "support/scratch_folder.h"

namespace myo {
namespace {

namespace fs = std::filesystem;

using RunCommand = test::ScratchFolderTest;
using test::kSmallScene;

TEST_F(RunCommand, WritesObjFramesStatsAndPictures) {
  const std::string scene = write("small.json", kSmallScene);
  const auto r = test::runCli("run '" + scene + "' --out '" + (dir_ / "out").string() + "' --render --size 64 --json" + cacheArg());
  ASSERT_EQ(r.exitCode, 0) << r.out;
  for (int f = 0; f < 3; ++f) {
    EXPECT_TRUE(fs::exists(dir_ / "out" / "obj" / ("small_000" + std::to_string(f) + ".obj"))) << f;
    EXPECT_TRUE(fs::exists(dir_ / "out" / "png" / ("small_000" + std::to_string(f) + ".png"))) << f;
  }
  EXPECT_FALSE(fs::exists(dir_ / "out" / "obj" / "small_0003.obj"));
  EXPECT_TRUE(fs::exists(dir_ / "out" / "small_sheet.png"));
  for (const auto& e : fs::recursive_directory_iterator(dir_ / "out"))
    EXPECT_NE(e.path().extension(), ".tmp") << "half-written file left: " << e.path();

  std::ifstream in(dir_ / "out" / "stats.json");
  const auto stats = nlohmann::json::parse(in);
  EXPECT_EQ(stats["frames"], 3);
  EXPECT_EQ(stats["channels"].size(), 1u);
  EXPECT_EQ(stats["channels"][0]["name"], "zygomaticus_major_left");
  EXPECT_GT(stats["channels"][0]["max_displacement_cm"].get<double>(), 0.0);
  EXPECT_EQ(stats["per_frame"].size(), 3u);
  EXPECT_GE(stats["muscles"][0]["stretch_participation"].get<double>(), 0.5);

  // The last frame is the head's mesh, displaced: same vertex count and order as the rest head.
  const TriMesh first = readObj((dir_ / "out" / "obj" / "small_0000.obj").string());
  const TriMesh last = readObjLike((dir_ / "out" / "obj" / "small_0002.obj").string(), first);
  EXPECT_GT((last.V - first.V).rowwise().norm().maxCoeff(), 0.01);

  // A second run loads every basis from the cache.
  const auto again = test::runCli("run '" + scene + "' --out '" + (dir_ / "out2").string() + "' --json" + cacheArg());
  ASSERT_EQ(again.exitCode, 0) << again.out;
  EXPECT_EQ(nlohmann::json::parse(again.out)["cache_hits"], 2);
}

TEST_F(RunCommand, CheckPrintsTheSceneWithDefaults) {
  const std::string scene = write("small.json", kSmallScene);
  const auto r = test::runCli("check '" + scene + "'");
  ASSERT_EQ(r.exitCode, 0) << r.out;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["name"], "small");
  EXPECT_EQ(j["numerics"]["skin_modes"], 8);
  EXPECT_EQ(j["numerics"]["stepper"], "exact");
  EXPECT_EQ(j["springs"]["model"], "thesis");
}

TEST_F(RunCommand, BadScenesExitTwoNamingFileLineAndKey) {
  const std::string scene = write("bad.json", "{\n  \"fps\": 30,\n  \"numerics\": {\"skin_mode\": 8}\n}\n");
  const auto r = test::runCli("check '" + scene + "'");
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.merged.find(scene + ":3:16: key 'numerics.skin_mode': unknown key"), std::string::npos) << r.merged;

  const auto missing = test::runCli("run '" + (dir_ / "nope.json").string() + "' --out '" + (dir_ / "o").string() + "'");
  EXPECT_EQ(missing.exitCode, 2);
  EXPECT_NE(missing.merged.find("nope.json: cannot open scene file"), std::string::npos) << missing.merged;

  const std::string file = write("not_a_folder", "x");
  const std::string good = write("small.json", kSmallScene);
  const auto notDir = test::runCli("run '" + good + "' --out '" + file + "'" + cacheArg());
  EXPECT_EQ(notDir.exitCode, 2);
  EXPECT_NE(notDir.merged.find("output path exists and is not a folder"), std::string::npos) << notDir.merged;
}

}  // namespace
}  // namespace myo
