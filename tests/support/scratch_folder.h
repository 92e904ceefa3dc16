// A test's own folder, and the small scenes the CLI tests run in it: one fixture instead of a copy
// of the same SetUp, TearDown and scene writer in every test file that runs `myoshell`.
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace myo::test {

// The small thesis scene of the export and run tests: the left zygomaticus rising to 1 over 0.05 s
// of 0.1 s at 20 fps (3 frames), 8 skin modes, no gravity; named "small".
inline constexpr const char* kSmallScene = R"({
  "name": "small", "model": "thesis",
  "muscles": {"use": ["zygomaticus_major_left"]},
  "gravity": {"enabled": false},
  "numerics": {"skin_modes": 8},
  "duration": 0.1, "fps": 20,
  "timeline": {"activations": {"zygomaticus_major_left": [{"t": 0, "value": 0}, {"t": 0.05, "value": 1}]}}
})";

// An empty folder for each test, myo_SUITE_PID_TEST under the temporary folder (the process id: two
// runs of the same test at once do not share it), removed after the test.
class ScratchFolderTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const ::testing::TestInfo* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = std::filesystem::temp_directory_path() /
           ("myo_" + std::string(info->test_suite_name()) + "_" + std::to_string(::getpid()) + "_" + info->name());
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  // Writes `text` to the folder's file `name` (binary: bytes as given); returns its path.
  std::string write(const std::string& name, const std::string& text) const {
    std::ofstream(dir_ / name, std::ios::binary) << text;
    return (dir_ / name).string();
  }
  // A basis cache of the test's own, as CLI arguments.
  std::string cacheArg() const { return " --cache '" + (dir_ / "cache").string() + "'"; }
  // A thesis scene named `name` in `file`, `duration` s at 20 fps: the left zygomaticus rising to 1
  // over 0.2 s, 8 skin modes, no gravity. Returns its path.
  std::string scene(const std::string& file, const std::string& name, double duration) const {
    std::ostringstream text;
    text << R"({"name": ")" << name << R"(", "model": "thesis", "muscles": {"use": ["zygomaticus_major_left"]},
      "gravity": {"enabled": false}, "numerics": {"skin_modes": 8}, "duration": )"
         << duration << R"(, "fps": 20,
      "timeline": {"activations": {"zygomaticus_major_left": [{"t": 0, "value": 0}, {"t": 0.2, "value": 1}]}}})";
    return write(file, text.str());
  }

  std::filesystem::path dir_;
};

}  // namespace myo::test
