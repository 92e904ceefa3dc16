// The library for other programs: `cmake --install` of this build, then examples/embed.cpp built
// against the installed tree with find_package(Myoshell), run, and checked.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "support/test_data.h"

namespace myo {
namespace {

namespace fs = std::filesystem;

int shell(const std::string& cmd) {
  const int status = std::system(cmd.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

TEST(Install, AnInstalledMyoshellBuildsAndRunsTheEmbedExample) {
  if (MYO_SANITIZED)
    GTEST_SKIP() << "a sanitized build installs libraries that only a sanitized program can link";
  const fs::path dir = fs::temp_directory_path() / ("myo_install_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  const std::string cmake = std::string("'") + MYO_CMAKE_COMMAND + "'";
  const fs::path prefix = dir / "prefix", build = dir / "build", log = dir / "log.txt";
  fs::create_directories(dir);
  const std::string quiet = " >> '" + log.string() + "' 2>&1";
  ASSERT_EQ(shell(cmake + " --install '" + std::string(MYO_BINARY_DIR) + "' --prefix '" + prefix.string() + "'" + quiet), 0)
      << "see " << log;
  EXPECT_TRUE(fs::exists(prefix / "include" / "myoshell" / "thesis" / "simulator.h"));
  EXPECT_TRUE(fs::exists(prefix / "lib" / "cmake" / "Myoshell" / "MyoshellConfig.cmake"));
  EXPECT_TRUE(fs::exists(prefix / "include" / "myoshell" / "verify" / "validation.h"));
  EXPECT_TRUE(fs::exists(prefix / "lib" / "libmyo_verify.a"));
  // The installed program finds the installed scenes, from any folder, and no data folder.
  EXPECT_TRUE(fs::exists(prefix / "share" / "myoshell" / "scenes" / "thesis" / "fig17_contract.json"));
  const fs::path pathsJson = dir / "paths.json";
  ASSERT_EQ(shell("cd / && env -u MYOSHELL_DATA '" + (prefix / "bin" / "myoshell").string() + "' paths --json > '" +
                  pathsJson.string() + "'"),
            0);
  std::ifstream in(pathsJson);
  const auto paths = nlohmann::json::parse(in);
  EXPECT_EQ(fs::path(paths["scenes"]["path"].get<std::string>()), prefix / "share" / "myoshell" / "scenes");
  EXPECT_EQ(paths["scenes"]["source"], "installed");
  EXPECT_EQ(paths["data"]["path"], "");
  ASSERT_EQ(shell(cmake + " -S '" + (test::sourceDir() / "examples").string() + "' -B '" + build.string() +
                  "' -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH='" + prefix.string() + "'" + quiet),
            0)
      << "see " << log;
  ASSERT_EQ(shell(cmake + " --build '" + build.string() + "'" + quiet), 0) << "see " << log;
  EXPECT_EQ(shell("'" + (build / "embed").string() + "'" + quiet), 0) << "see " << log;
  fs::remove_all(dir);
}

}  // namespace
}  // namespace myo
