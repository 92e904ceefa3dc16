// `myoshell bench`: the rows of the thesis's Tables 2–4 with their settings and channel facts.
// Asserts the report's shape and content, never the speed (docs/PERFORMANCE.md holds numbers).
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "support/cli_runner.h"

namespace myo {
namespace {

using ::testing::HasSubstr;
namespace fs = std::filesystem;

test::CliResult bench(const std::string& args, bool mergeStderr = false) {
  const fs::path cache = fs::path(testing::TempDir()) / "myo_thesis_cache";
  const fs::path scenes = test::sourceDir() / "scenes" / "thesis";
  test::CliResult r = test::runCli("bench --scenes '" + scenes.string() + "' --cache '" + cache.string() + "' " + args);
  if (mergeStderr) r.out = r.merged;
  return r;
}

TEST(BenchCommand, ReportsRowsWithSettingsChannelsAndThesisFps) {
  const test::CliResult r = bench(
      "--json --seconds 0.02 --runs 3 --heads default --no-reference --threads 4 --diagnostics "
      "--rows t2_all8,t3_zygomaticus_right,t4_gravity,t4_muscle_and_drag");
  ASSERT_EQ(r.exitCode, 0) << r.out;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["threads"], 1);
  ASSERT_EQ(j["notes"].size(), 1u);
  EXPECT_THAT(j["notes"][0].get<std::string>(), HasSubstr("single-threaded"));
  EXPECT_TRUE(j["machine"].contains("cpu"));
  ASSERT_EQ(j["rows"].size(), 4u);
  EXPECT_TRUE(j["reference"].empty());

  const auto& all8 = j["rows"][0];
  EXPECT_EQ(all8["table"], "2");
  EXPECT_EQ(all8["timed"], "muscle phase");
  EXPECT_EQ(all8["muscles"], 8);
  EXPECT_EQ(all8["thesis_fps"], 200.0);
  EXPECT_EQ(all8["channels"].size(), 8u);

  const auto& right = j["rows"][1];
  EXPECT_EQ(right["id"], "t3_zygomaticus_right");
  EXPECT_EQ(right["timed"], "whole step");
  EXPECT_EQ(right["thesis_fps"], 95.0);
  EXPECT_EQ(right["d"], 30);
  EXPECT_NEAR(right["dt"].get<double>(), 1.0 / 240.0, 1e-12);

  const auto& gravity = j["rows"][2];
  bool haveGravity = false;
  for (const auto& c : gravity["channels"])
    if (c["name"] == "gravity") {
      haveGravity = true;
      EXPECT_GT(c["free_vertices"].get<int>(), 6000);
      EXPECT_GT(c["load_participation"].get<double>(), 0.0);
      EXPECT_LE(c["load_participation"].get<double>(), 1.0 + 1e-9);
    }
  EXPECT_TRUE(haveGravity);

  for (const auto& row : j["rows"]) {
    EXPECT_EQ(row["head"], "default");
    EXPECT_EQ(row["skin_vertices"], 7152);
    EXPECT_EQ(row["runs_steps_per_second"].size(), 3u);
    EXPECT_GT(row["steps_per_second"].get<double>(), 0.0);
    EXPECT_NEAR(row["ratio"].get<double>(),
                row["steps_per_second"].get<double>() / row["thesis_fps"].get<double>(), 1e-9);
    for (const auto& c : row["channels"]) {
      EXPECT_GT(c["free_vertices"].get<int>(), 0);
      EXPECT_EQ(c["modes"], 30);
    }
  }
  // The drag row has a muscle channel and a drag channel.
  EXPECT_EQ(j["rows"][3]["channels"].size(), 2u);
}

// Every row reports its floor (its step time over one stream of the bases it reads) and its
// reference ratio (over one full-space step under the same loads): present, finite and positive, or
// null with a note where the reference is not defined. Values are not asserted: speed is measured.
TEST(BenchCommand, RowsReportFloorAndReferenceRatios) {
  const test::CliResult r =
      bench("--json --seconds 0.02 --runs 1 --heads default --reference-steps 1 --rows t2_corrugator,t3_corrugator_right");
  ASSERT_EQ(r.exitCode, 0) << r.out;
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_EQ(j["rows"].size(), 2u);
  for (const auto& row : j["rows"]) {
    for (const char* key : {"muscles", "floor_ratio", "floor_us", "floor_bytes", "reference_ratio", "reference_step_us"})
      EXPECT_TRUE(row.contains(key)) << row["id"] << " has no " << key;
    const double floor = row["floor_ratio"].get<double>();
    EXPECT_TRUE(std::isfinite(floor) && floor > 0.0) << row["id"] << ": " << floor;
    EXPECT_GT(row["floor_bytes"].get<double>(), 0.0);
    EXPECT_EQ(row["muscles"], 1);
    // Without --diagnostics the load participation is not measured.
    for (const auto& c : row["channels"]) EXPECT_TRUE(c["load_participation"].is_null());
  }
  const auto& muscleOnly = j["rows"][0];
  EXPECT_TRUE(muscleOnly["reference_ratio"].is_null());
  EXPECT_THAT(muscleOnly["reference_note"].get<std::string>(), HasSubstr("muscle-phase"));
  const auto& whole = j["rows"][1];
  const double ref = whole["reference_ratio"].get<double>();
  EXPECT_TRUE(std::isfinite(ref) && ref > 0.0) << ref;
  EXPECT_GT(whole["reference_step_us"].get<double>(), 0.0);
}

TEST(BenchCommand, TextTableNamesTheThesisColumns) {
  const test::CliResult r = bench("--seconds 0.01 --runs 1 --heads default --no-reference --rows t3_depressor_anguli_both");
  ASSERT_EQ(r.exitCode, 0) << r.out;
  EXPECT_THAT(r.out, HasSubstr("Depressor anguli oris, both sides"));
  EXPECT_THAT(r.out, HasSubstr("thesis   96"));
}

// The two models side by side (scenes/bench/, beside --scenes): eight muscles, gravity and one drag
// each; the cold precompute goes into an empty cache of the row's own, the cached start reads it.
TEST(BenchCommand, FullRowsRunBothModelsSideBySide) {
  const test::CliResult r =
      bench("--json --seconds 0.02 --runs 1 --heads default --reference-steps 1 --rows thesis_full,anatomical_full");
  ASSERT_EQ(r.exitCode, 0) << r.out;
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_EQ(j["rows"].size(), 2u);
  const auto& thesis = j["rows"][0];
  const auto& anatomical = j["rows"][1];
  EXPECT_EQ(thesis["id"], "thesis_full");
  EXPECT_EQ(thesis["model"], "thesis");
  EXPECT_EQ(anatomical["id"], "anatomical_full");
  EXPECT_EQ(anatomical["model"], "anatomical");
  for (const auto& row : j["rows"]) {
    EXPECT_EQ(row["scene"].get<std::string>().rfind("bench/full_", 0), 0u) << row["scene"];
    EXPECT_EQ(row["muscles"], 8);
    EXPECT_EQ(row["drags"], 1);
    EXPECT_EQ(row["gravity"], true);
    // Each model's own built-in head: the thesis's with its eyes closed, the anatomical's open.
    EXPECT_EQ(row["skin_vertices"], row["model"] == "thesis" ? 7152 : 6990);
    EXPECT_GT(row["steps_per_second"].get<double>(), 0.0);
    EXPECT_GT(row["cold_precompute_seconds"].get<double>(), 0.0);
    EXPECT_GT(row["cached_start_seconds"].get<double>(), 0.0);
    // From an empty cache a build reads back only what it stored itself (the thesis's gravity and
    // drag channels share one basis); the second build reads everything back.
    EXPECT_LT(row["cold_cache_hits"].get<int>(), row["cache_hits"].get<int>());
    for (const char* phase : {"muscles", "springs", "channels", "total"})
      EXPECT_GE(row["phase_us"][phase].get<double>(), 0.0) << phase;
    EXPECT_GT(row["read_us"].get<double>(), 0.0);  // an output frame's positions
    // All loads active at the window's end: a floor and a full-space reference step for both models
    // (the anatomical one with its attachment and couplings' stiffness).
    const double floor = row["floor_ratio"].get<double>(), ref = row["reference_ratio"].get<double>();
    EXPECT_TRUE(std::isfinite(floor) && floor > 0.0) << row["id"] << ": " << floor;
    EXPECT_TRUE(std::isfinite(ref) && ref > 0.0) << row["id"] << ": " << ref;
  }
  // Thesis: eight muscle channels, gravity and the drag; anatomical: one skin whose basis holds
  // the d modes and the static responses of the muscles, gravity (x, y, z), the drag (x, y, z) and
  // the lids' and lips' eight contact patterns (the built-in head has open eyes: docs/mouth_contact.md).
  EXPECT_EQ(thesis["channels"].size(), 10u);
  EXPECT_EQ(thesis["cache_hits"], 18);  // 8 muscles' modes + 10 skin channels
  ASSERT_EQ(anatomical["channels"].size(), 1u);
  EXPECT_EQ(anatomical["channels"][0]["name"], "skin");
  EXPECT_EQ(anatomical["channels"][0]["free_vertices"], 6990);
  EXPECT_GT(anatomical["channels"][0]["modes"].get<int>(), 30);
  EXPECT_LE(anatomical["channels"][0]["modes"].get<int>(), 30 + 8 + 3 + 3 + 8);
  EXPECT_EQ(thesis["cold_cache_hits"], 1);
  EXPECT_EQ(anatomical["cache_hits"], 1);
  EXPECT_EQ(anatomical["cold_cache_hits"], 0);
  ASSERT_EQ(j["full_side_by_side"].size(), 1u);
  EXPECT_EQ(j["full_side_by_side"][0]["head"], "default");
  EXPECT_NEAR(j["full_side_by_side"][0]["anatomical_over_thesis"].get<double>(),
              anatomical["steps_per_second"].get<double>() / thesis["steps_per_second"].get<double>(), 1e-9);
}

TEST(BenchCommand, BadArgumentsAreInputErrors) {
  test::CliResult r = bench("--rows no_such_row", true);
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_THAT(r.out, HasSubstr("unknown bench row 'no_such_row'"));
  r = bench("--heads moon", true);
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_THAT(r.out, HasSubstr("unknown head 'moon'"));
  r = bench("--seconds 0", true);
  EXPECT_EQ(r.exitCode, 2);
}

}  // namespace
}  // namespace myo
