// A scene name names the output files: one that would lead out of --out is refused.
#include <gtest/gtest.h>

#include <filesystem>

#include "support/cli_runner.h"
#include "support/scratch_folder.h"

namespace myo {
namespace {

namespace fs = std::filesystem;

using SceneName = test::ScratchFolderTest;

TEST_F(SceneName, ASceneNameThatLeavesTheOutputFolderIsRejected) {
  for (const char* name : {"../escape", "a/b", "a\\\\b", ".."}) {
    const std::string path = scene("bad.json", name, 0.1);
    const auto r = test::runCli("run '" + path + "' --out '" + (dir_ / "out").string() + "'" + cacheArg());
    EXPECT_EQ(r.exitCode, 2) << name << ": " << r.merged;
    EXPECT_NE(r.merged.find(path + ":1:10: key 'name': "), std::string::npos) << r.merged;
    EXPECT_NE(r.merged.find("must not contain '/', '\\', or '..'"), std::string::npos) << r.merged;
    EXPECT_FALSE(fs::exists(dir_ / "out"));
    EXPECT_FALSE(fs::exists(dir_ / "escape_0000.obj"));
  }
}

}  // namespace
}  // namespace myo
