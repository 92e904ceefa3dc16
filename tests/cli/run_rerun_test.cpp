// `myoshell run` into a folder a previous run wrote: the files of that run this one does not
// rewrite go (stale frames, an old GLB or PC2), and nothing else (the user's own files stay).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "support/cli_runner.h"
#include "support/scratch_folder.h"

namespace myo {
namespace {

namespace fs = std::filesystem;

using RunRerun = test::ScratchFolderTest;

TEST_F(RunRerun, AShorterRerunRemovesTheStaleFramesAndExportsButNotTheUsersFiles) {
  const fs::path out = dir_ / "out";
  auto r = test::runCli("run '" + scene("s.json", "s", 0.45) + "' --out '" + out.string() + "' --format obj,glb,pc2" + cacheArg());
  ASSERT_EQ(r.exitCode, 0) << r.merged;
  for (int f = 0; f < 10; ++f) ASSERT_TRUE(fs::exists(out / "obj" / ("s_000" + std::to_string(f) + ".obj"))) << f;
  ASSERT_TRUE(fs::exists(out / "s.glb"));
  std::ofstream(out / "notes.txt") << "mine";
  std::ofstream(out / "obj" / "mine.obj") << "# mine";
  r = test::runCli("run '" + scene("s.json", "s", 0.2) + "' --out '" + out.string() + "' --format obj" + cacheArg());
  ASSERT_EQ(r.exitCode, 0) << r.merged;
  for (int f = 0; f < 5; ++f) EXPECT_TRUE(fs::exists(out / "obj" / ("s_000" + std::to_string(f) + ".obj"))) << f;
  for (int f = 5; f < 10; ++f) EXPECT_FALSE(fs::exists(out / "obj" / ("s_000" + std::to_string(f) + ".obj"))) << f;
  EXPECT_FALSE(fs::exists(out / "s.glb"));
  EXPECT_FALSE(fs::exists(out / "s.pc2"));
  EXPECT_TRUE(fs::exists(out / "notes.txt"));
  EXPECT_TRUE(fs::exists(out / "obj" / "mine.obj"));
  EXPECT_TRUE(fs::exists(out / "stats.json"));
  std::ifstream in(out / ".myoshell-manifest.json");
  const nlohmann::json manifest = nlohmann::json::parse(in);
  EXPECT_EQ(manifest["files"].size(), 6u);  // five frames and stats.json
}

}  // namespace
}  // namespace myo
