// readPerformanceFile: the file's own faults (the readers: tests/anim/performance_test.cpp; bad
// performance files through `myoshell drive`: the bad-input catalogue, tests/bad_inputs/cases.json).
#include <gtest/gtest.h>

#include "myoshell/core/errors.h"
#include "myoshell/io/performance_file.h"
#include "support/test_data.h"

namespace myo {
namespace {

TEST(PerformanceFile, AFolderIsNoPerformance) {
  const std::string dir = (test::sourceDir() / "tests" / "bad_inputs").string();
  try {
    readPerformanceFile(dir);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), dir + ": cannot open: is a directory");
  }
}

TEST(PerformanceFile, OptionsReachTheReader) {
  const std::string file = (test::sourceDir() / "tests" / "bad_inputs" / "performance_two_faces.csv").string();
  const Performance p = readPerformanceFile(file, {.face = 1});
  ASSERT_NE(p.find("AU12"), nullptr);
  EXPECT_EQ(p.find("AU12")->values, (std::vector<double>{0.4, 0.5}));  // face 1's 2.0 and 2.5 of 5
}

}  // namespace
}  // namespace myo
