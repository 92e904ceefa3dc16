// Vertex sets from JSON: both forms, and errors naming file, line and fault.
#include "myoshell/io/vertex_set_file.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "myoshell/core/errors.h"
#include "support/test_data.h"

namespace myo {
namespace {

using ::testing::HasSubstr;

void expectError(const std::string& json, int n, int line, const std::string& what) {
  try {
    parseVertexSet(json, n, "set.json");
    FAIL() << "expected an InputError containing '" << what << "'";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "set.json");
    EXPECT_EQ(e.line(), line) << e.what();
    EXPECT_THAT(e.message(), HasSubstr(what));
    EXPECT_THAT(std::string(e.what()), HasSubstr("set.json:" + std::to_string(line)));
  }
}

TEST(VertexSet, ListAndObjectFormsGiveSortedUniqueIndices) {
  EXPECT_EQ(parseVertexSet("[12, 3, 8, 3]", 20), (std::vector<int>{3, 8, 12}));
  EXPECT_EQ(parseVertexSet(R"({"source": "hand-picked [1, 2]", "vertices": [5, 0]})", 6),
            (std::vector<int>{0, 5}));
  EXPECT_TRUE(parseVertexSet("[]", 0).empty());
}

TEST(VertexSet, IndexOutOfRangeNamesItsLine) {
  expectError("[\n  1,\n  2,\n  12000\n]\n", 11248, 4, "index 12000 out of range [0, 11248)");
  expectError("{\"vertices\": [0,\n 1, -1]}", 10, 2, "index -1 out of range [0, 10)");
  // A key holding a look-alike list before "vertices" must not confuse the line search.
  expectError("{\"note\": [\"a, b\", [1, 2]],\n \"vertices\": [0,\n\n 99]}", 10, 4,
              "index 99 out of range");
}

TEST(VertexSet, NonIntegersAreRejected) {
  expectError("[1,\n 2.5]", 10, 2, "expected a list of integer vertex indices");
  expectError("[1,\n\n \"7\"]", 10, 3, "expected a list of integer vertex indices");
  expectError("{\"vertices\": 3}", 10, 1, "expected a list of integer vertex indices");
  expectError("{\"pins\": [1, 2]}", 10, 1, "\"vertices\"");
  expectError("\"hello\"", 10, 1, "expected a list");
}

TEST(VertexSet, SyntaxErrorsNameTheLine) {
  expectError("[1,\n 2,\n 3,,\n 4]", 10, 3, "invalid JSON");
  expectError("{\"vertices\": [1, 2]\n", 10, 2, "invalid JSON");
}

TEST(VertexSet, MissingFile) {
  try {
    readVertexSet("/nonexistent/pins.json", 10);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("/nonexistent/pins.json: cannot open"));
  }
}

TEST(VertexSet, ReadsIctRigidVertices) {
  MYO_REQUIRE_SHARED_DATA();
  const auto set = readVertexSet((test::sharedDataDir() / "ict" / "rigid_vertices.json").string(), 11248);
  EXPECT_GT(set.size(), 100u);
  EXPECT_TRUE(std::is_sorted(set.begin(), set.end()));
  EXPECT_THROW(readVertexSet((test::sharedDataDir() / "ict" / "rigid_vertices.json").string(), 100),
               InputError);
}

}  // namespace
}  // namespace myo
