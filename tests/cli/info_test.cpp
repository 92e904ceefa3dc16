// `myoshell info`: the library numbers and the CLI's JSON, exit codes and error text.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "myoshell/mesh/mesh_stats.h"
#include "myoshell/mesh/obj_reader.h"
#include "support/cli_runner.h"

namespace myo {
namespace {

using ::testing::HasSubstr;
namespace fs = std::filesystem;

// The CLI's stdout and stderr together.
test::CliResult runInfoCli(const std::string& args) {
  test::CliResult r = test::runCli(args);
  r.out = r.merged;
  return r;
}

std::string ictHead() { return (test::sharedDataDir() / "ict" / "head_skin.obj").string(); }

TEST(InfoCommand, IctHeadLibraryNumbers) {
  MYO_REQUIRE_SHARED_DATA();
  MeshReport report;
  const TriMesh head = readObjLenient(ictHead(), report);
  EXPECT_TRUE(report.faults.empty());
  const MeshStats s = meshStats(head);
  EXPECT_EQ(s.vertices, 11248);
  EXPECT_EQ(s.triangles, 22288);
  EXPECT_EQ(s.boundaryEdges, 212);
  EXPECT_EQ(s.boundaryLoops, 4);
  EXPECT_EQ(s.components, 1);
}

TEST(InfoCommand, IctHeadJson) {
  MYO_REQUIRE_SHARED_DATA();
  const test::CliResult r = runInfoCli("info --json '" + ictHead() + "'");
  ASSERT_EQ(r.exitCode, 0) << r.out;
  const auto j = nlohmann::json::parse(r.out);
  for (const char* key : {"vertices", "triangles", "edges", "interior_edges", "boundary_edges",
                          "boundary_loops", "components", "non_manifold_edges", "degenerate_triangles",
                          "bbox_min", "bbox_max", "area"})
    EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_EQ(j["vertices"], 11248);
  EXPECT_EQ(j["triangles"], 22288);
  EXPECT_EQ(j["boundary_edges"], 212);
  EXPECT_EQ(j["boundary_loops"], 4);
  EXPECT_EQ(j["components"], 1);
  EXPECT_EQ(j["non_manifold_edges"], 0);
  EXPECT_EQ(j["degenerate_triangles"], 0);
  EXPECT_EQ(j["interior_edges"].get<int>() + j["boundary_edges"].get<int>(), j["edges"].get<int>());
  EXPECT_EQ(j["bbox_min"].size(), 3u);
  EXPECT_LT(j["bbox_min"][1].get<double>(), j["bbox_max"][1].get<double>());
  EXPECT_GT(j["area"].get<double>(), 0.0);
  EXPECT_TRUE(j["faults"].empty());
}

TEST(InfoCommand, IctHeadTable) {
  MYO_REQUIRE_SHARED_DATA();
  const test::CliResult r = runInfoCli("info '" + ictHead() + "'");
  ASSERT_EQ(r.exitCode, 0) << r.out;
  EXPECT_THAT(r.out, HasSubstr("11248"));
  EXPECT_THAT(r.out, HasSubstr("22288"));
  EXPECT_THAT(r.out, HasSubstr("faults"));
}

// An OBJ has no unit: info printed "bbox (cm)" for a head in metres. It must claim none.
TEST(InfoCommand, TheTableClaimsNoUnitForAnObj) {
  const std::string metres = (test::sourceDir() / "tests" / "bad_inputs" / "head_in_metres.obj").string();
  const test::CliResult r = runInfoCli("info '" + metres + "'");
  EXPECT_THAT(r.out, HasSubstr("(the file's units)")) << r.out;
  EXPECT_THAT(r.out, ::testing::Not(HasSubstr("cm"))) << r.out;
}

TEST(InfoCommand, FaultyMeshReportsEveryFaultAndExitsThree) {
  const fs::path path = fs::temp_directory_path() / ("myo_info_faulty_" + std::to_string(::getpid()) + ".obj");
  std::ofstream(path) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 2 0 0\nv 1 zz 0\n"
                         "f 1 2 3\nf 1 2 4\nf 1 2 9\nf 2 1 3\n";
  const test::CliResult r = runInfoCli("info --json '" + path.string() + "'");
  fs::remove(path);
  ASSERT_EQ(r.exitCode, 3) << r.out;
  const auto j = nlohmann::json::parse(r.out);
  std::map<std::string, int> counts;
  for (const auto& f : j["faults"]) counts[f["kind"]] = f["count"];
  EXPECT_EQ(counts["unreadable_number"], 1);
  EXPECT_EQ(counts["index_out_of_range"], 1);
  EXPECT_EQ(counts["degenerate_triangle"], 1);       // f 1 2 4: collinear
  EXPECT_EQ(counts["non_manifold_edge"], 1);         // edge (0, 1) in three faces
  EXPECT_EQ(counts["inconsistent_orientation"], 1);  // line 7 runs 0→1 like line 6
  EXPECT_EQ(j["triangles"], 3);
  EXPECT_EQ(j["vertices"], 5);
}

TEST(InfoCommand, MissingFileExitsTwoWithMessage) {
  const test::CliResult r = runInfoCli("info /nonexistent/head.obj");
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_THAT(r.out, HasSubstr("myoshell: error: /nonexistent/head.obj: cannot open"));
}

}  // namespace
}  // namespace myo
