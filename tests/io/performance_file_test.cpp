// readPerformanceFile over the bad performance files waiting for `myoshell drive`
// (tests/bad_inputs/performance_cases.json, cases.json's layout): each fails with its message,
// naming the file by the path it was given. The readers themselves: tests/anim/performance_test.cpp.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "myoshell/core/errors.h"
#include "myoshell/io/performance_file.h"
#include "support/test_data.h"

namespace myo {
namespace {

namespace fs = std::filesystem;

TEST(PerformanceFile, EveryPendingBadInputFailsWithItsMessage) {
  const fs::path dir = test::sourceDir() / "tests" / "bad_inputs";
  std::ifstream in(dir / "performance_cases.json");
  ASSERT_TRUE(in.good());
  const auto catalogue = nlohmann::json::parse(in);
  int ran = 0;
  for (const auto& c : catalogue["cases"]) {
    const std::string name = c["name"];
    PerformanceOptions options;
    if (c.contains("options")) {
      const auto& o = c["options"];
      if (o.contains("input")) options.input = performanceInputFromString(o["input"]);
      if (o.contains("face")) options.face = o["face"];
      if (o.contains("au_scale")) options.auScale = o["au_scale"].get<double>();
      if (o.contains("input_fps")) options.inputFps = o["input_fps"].get<double>();
    }
    const std::string expect = c["expect"];
    // The CLI prints the path as given ('{dir}/file'); the fragment starts at the file's name.
    const std::string path = (dir / c["file"].get<std::string>()).string();
    std::string message = "(no error)";
    try {
      readPerformanceFile(path, options);
    } catch (const InputError& e) {
      message = e.what();
    }
    EXPECT_NE(message.find(expect), std::string::npos) << name << ": expected \"" << expect << "\" in: " << message;
    EXPECT_EQ(message.rfind(dir.string(), 0), 0u) << name << ": " << message;  // names the file as given
    EXPECT_EQ(c["exit"].get<int>(), 2) << name;
    ++ran;
  }
  EXPECT_GE(ran, 15);
}

TEST(PerformanceFile, AFolderIsNoPerformance) {
  const std::string dir = (test::sourceDir() / "tests" / "bad_inputs").string();
  try {
    readPerformanceFile(dir);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), dir + ": cannot open: is a directory");
  }
}

}  // namespace
}  // namespace myo
