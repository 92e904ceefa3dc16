// `myoshell validate --json`: structure of the JSON and the accuracy bounds of the validation issue.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <set>
#include <string>

#include "support/cli_runner.h"

namespace myo {
namespace {

using test::runCli;

const nlohmann::json& findCase(const nlohmann::json& j, const std::string& name) {
  for (const auto& c : j["cases"])
    if (c["name"] == name) return c;
  ADD_FAILURE() << "no case " << name;
  static const nlohmann::json empty = nlohmann::json::object();
  return empty;
}

TEST(ValidateCommand, JsonStructureAndBounds) {
  const test::CliResult r = runCli("validate --json");
  ASSERT_EQ(r.exitCode, 0) << r.out;
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_TRUE(j.contains("cases"));
  ASSERT_TRUE(j.contains("seconds"));
  EXPECT_GT(j["seconds"].get<double>(), 0.0);
  EXPECT_TRUE(j["all_passed"].get<bool>());
  ASSERT_EQ(j["cases"].size(), 5u);
  std::set<std::string> names;
  for (const auto& c : j["cases"]) {
    for (const char* key : {"name", "description", "d", "quantity", "reference", "warped", "linear", "metric",
                            "error_warped", "error_linear", "bound", "passed", "details"})
      EXPECT_TRUE(c.contains(key)) << key;
    EXPECT_EQ(c["d"].get<int>(), 20);
    EXPECT_TRUE(c["passed"].get<bool>()) << c.dump(2);
    EXPECT_GE(c["error_warped"].get<double>(), 0.0);
    names.insert(c["name"].get<std::string>());
  }
  EXPECT_EQ(names.size(), 5u);

  for (const char* name : {"cantilever_small_load_40x4", "cantilever_small_load_80x8"}) {
    const auto& c = findCase(j, name);
    EXPECT_LE(c["error_warped"].get<double>(), 0.02);
    EXPECT_LE(c["error_linear"].get<double>(), 0.02);
    EXPECT_LE(c["details"]["beam_tip_error"].get<double>(), 0.05);
    EXPECT_LE(c["details"]["omega1_error"].get<double>(), 0.05);
  }
  for (const char* name : {"cantilever_large_load_40x4", "cantilever_large_load_80x8"}) {
    const auto& c = findCase(j, name);
    EXPECT_GE(c["details"]["tip_rotation_deg_reference"].get<double>(), 45.0);
    EXPECT_GE(c["error_linear"].get<double>(), 3.0 * c["error_warped"].get<double>());
    EXPECT_GT(c["details"]["length_growth_linear"].get<double>(),
              std::abs(c["details"]["length_growth_warped"].get<double>()));
  }
  const auto& dyn = findCase(j, "released_tip_40x4");
  EXPECT_LE(dyn["error_warped"].get<double>(), 0.10);
  EXPECT_LE(dyn["error_warped"].get<double>(), dyn["error_linear"].get<double>());
}

TEST(ValidateCommand, RejectsBadModeCount) {
  const test::CliResult r = runCli("validate --modes 0");
  EXPECT_EQ(r.exitCode, 2);
}

}  // namespace
}  // namespace myo
