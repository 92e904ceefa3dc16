// Where tests find the team's shared data (../shared beside the project) and the CLI binary.
// Tests that need shared data call MYO_REQUIRE_SHARED_DATA() and skip with a clear message when
// it is absent (a user's machine).
#pragma once

#include <filesystem>
#include <string>

namespace myo::test {

inline std::filesystem::path sharedDataDir() {
  if (const char* env = std::getenv("MYOSHELL_DATA")) return env;  // as the CLI's --data
  if (const char* env = std::getenv("MYOSHELL_SHARED_DATA")) return env;
  return std::filesystem::path(MYO_SHARED_DIR) / "data";
}

inline bool haveSharedData() { return std::filesystem::exists(sharedDataDir() / "ict" / "head_skin.obj"); }

inline std::string cliPath() { return MYO_CLI_PATH; }
inline std::filesystem::path sourceDir() { return MYO_SOURCE_DIR; }

}  // namespace myo::test

#define MYO_REQUIRE_SHARED_DATA()                                                          \
  do {                                                                                     \
    if (!::myo::test::haveSharedData())                                                    \
      GTEST_SKIP() << "shared data not found at " << ::myo::test::sharedDataDir()          \
                   << " (set MYOSHELL_SHARED_DATA or place ../shared beside the project)"; \
  } while (0)
