// One set of --view names (front, three-quarter, profile, back) for `run`, `render` and `head`,
// checked before any work.
#include <gtest/gtest.h>

#include <filesystem>

#include "support/cli_runner.h"
#include "support/scratch_folder.h"

namespace myo {
namespace {

namespace fs = std::filesystem;

using ViewNames = test::ScratchFolderTest;

TEST_F(ViewNames, ViewNamesAreOneSetAndABadOneFailsBeforeAnyFolder) {
  const auto r = test::runCli("run '" + scene("v.json", "v", 0.1) + "' --out '" + (dir_ / "out").string() +
                              "' --render --view side" + cacheArg());
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.merged.find("unknown view 'side' (use front, three-quarter, profile or back)"), std::string::npos) << r.merged;
  EXPECT_FALSE(fs::exists(dir_ / "out"));
  EXPECT_FALSE(fs::exists(dir_ / "cache"));  // nothing built either
  const auto h = test::runCli("head --levels 0 --view threequarter --render '" + (dir_ / "h.png").string() + "'");
  EXPECT_EQ(h.exitCode, 2);
  EXPECT_NE(h.merged.find("unknown view 'threequarter' (use front, three-quarter, profile or back)"), std::string::npos)
      << h.merged;
  for (const char* view : {"front", "three-quarter", "profile", "back"}) {
    const fs::path png = dir_ / (std::string(view) + ".png");
    const auto ok = test::runCli(std::string("head --levels 0 --size 64 --view ") + view + " --render '" + png.string() + "'");
    EXPECT_EQ(ok.exitCode, 0) << view << ": " << ok.merged;
    EXPECT_TRUE(fs::exists(png)) << view;
  }
}

}  // namespace
}  // namespace myo
