// OBJ reading: triangulation rules, order, groups, UVs, indices, every strict error with its line,
// lenient fault counts, writing.
#include "myoshell/mesh/obj_reader.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "myoshell/core/errors.h"
#include "myoshell/mesh/primitives.h"
#include "support/test_data.h"

namespace myo {
namespace {

using ::testing::HasSubstr;
namespace fs = std::filesystem;

// A scratch directory removed at the end of the test.
class TempDir {
 public:
  TempDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = fs::temp_directory_path() /
            (std::string("myo_obj_") + info->test_suite_name() + "_" + info->name() + "_" +
             std::to_string(::getpid()));
    fs::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  std::string write(const std::string& name, const std::string& text) const {
    const fs::path p = path_ / name;
    std::ofstream(p, std::ios::binary) << text;
    return p.string();
  }
  fs::path path() const { return path_; }

 private:
  fs::path path_;
};

// Expects a strict read of text to throw an InputError at `line` whose message contains `what`.
void expectError(const std::string& text, int line, const std::string& what) {
  try {
    readObjFromString(text, "t.obj");
    FAIL() << "expected an InputError containing '" << what << "'";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "t.obj");
    EXPECT_EQ(e.line(), line) << e.what();
    EXPECT_THAT(e.message(), HasSubstr(what));
    if (line > 0) EXPECT_THAT(std::string(e.what()), HasSubstr("t.obj:" + std::to_string(line) + ": "));
  }
}

std::vector<std::array<int, 3>> triangles(const TriMesh& m) {
  std::vector<std::array<int, 3>> out;
  for (int t = 0; t < m.triangleCount(); ++t) out.push_back({m.F(t, 0), m.F(t, 1), m.F(t, 2)});
  return out;
}

using Tris = std::vector<std::array<int, 3>>;

const char* kTwoTriangles =
    "v 0 0 0\n"
    "v 1 0 0\n"
    "v 1 1 0\n"
    "v 0 1 0\n"
    "f 1 2 3\n"
    "f 1 3 4\n";

TEST(ObjReader, ReadsTrianglesInFileOrder) {
  const TriMesh m = readObjFromString(kTwoTriangles);
  ASSERT_EQ(m.vertexCount(), 4);
  EXPECT_EQ(m.V.row(2), Vec3(1, 1, 0).transpose());
  EXPECT_EQ(triangles(m), (Tris{{0, 1, 2}, {0, 2, 3}}));
  EXPECT_EQ(m.sourcePolygon, (std::vector<int>{0, 1}));
  EXPECT_EQ(m.polygons, (std::vector<std::vector<int>>{{0, 1, 2}, {0, 2, 3}}));
  EXPECT_EQ(m.UV.rows(), 0);
  EXPECT_TRUE(m.groups.empty());
}

TEST(ObjReader, QuadSplitsAlongShorterDiagonal) {
  // Rhombus long along x: v1–v3 (length 2) is shorter than v0–v2 (length 4).
  const TriMesh a = readObjFromString("v -2 0 0\nv 0 -1 0\nv 2 0 0\nv 0 1 0\nf 1 2 3 4\n");
  EXPECT_EQ(triangles(a), (Tris{{0, 1, 3}, {1, 2, 3}}));
  // The same rhombus with the first vertex moved along: now v0–v2 is the shorter one.
  const TriMesh b = readObjFromString("v 0 -1 0\nv 2 0 0\nv 0 1 0\nv -2 0 0\nf 1 2 3 4\n");
  EXPECT_EQ(triangles(b), (Tris{{0, 1, 2}, {0, 2, 3}}));
  EXPECT_EQ(b.sourcePolygon, (std::vector<int>{0, 0}));
  EXPECT_EQ(b.polygons, (std::vector<std::vector<int>>{{0, 1, 2, 3}}));
}

TEST(ObjReader, QuadTieTakesV0V2Diagonal) {
  const TriMesh m = readObjFromString("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n");
  EXPECT_EQ(triangles(m), (Tris{{0, 1, 2}, {0, 2, 3}}));
}

TEST(ObjReader, LargerPolygonsFanFromFirstVertex) {
  const TriMesh m = readObjFromString(
      "v 1 0 0\nv 0.31 0.95 0\nv -0.81 0.59 0\nv -0.81 -0.59 0\nv 0.31 -0.95 0\nf 1 2 3 4 5\n");
  EXPECT_EQ(triangles(m), (Tris{{0, 1, 2}, {0, 2, 3}, {0, 3, 4}}));
  EXPECT_EQ(m.sourcePolygon, (std::vector<int>{0, 0, 0}));
}

TEST(ObjReader, TexturedCornersKeepVertexOrderAndTakeFirstUv) {
  // Faces list vertices out of order and with vt/vn: positions must stay in file order.
  const TriMesh m = readObjFromString(
      "v 10 0 0\nv 11 0 0\nv 12 1 0\nv 13 1 0\n"
      "vt 0.1 0.2\nvt 0.3 0.4\nvt 0.5 0.6\nvt 0.7 0.8\nvt 0.9 1.0\n"
      "vn 0 0 1\n"
      "f 3/1/1 1/2/1 2/3/1\n"
      "f 3/4/1 2/3/1 4/5/1\n");
  ASSERT_EQ(m.vertexCount(), 4);
  for (int i = 0; i < 4; ++i) EXPECT_EQ(m.V(i, 0), 10 + i);
  EXPECT_EQ(triangles(m), (Tris{{2, 0, 1}, {2, 1, 3}}));
  ASSERT_EQ(m.UV.rows(), 4);
  EXPECT_EQ(m.UV.row(2), Vec2(0.1, 0.2).transpose());  // first corner wins over vt 4
  EXPECT_EQ(m.UV.row(0), Vec2(0.3, 0.4).transpose());
  EXPECT_EQ(m.UV.row(1), Vec2(0.5, 0.6).transpose());
  EXPECT_EQ(m.UV.row(3), Vec2(0.9, 1.0).transpose());
}

TEST(ObjReader, SingleNumberTexcoordHasZeroV) {
  const TriMesh m = readObjFromString("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0.5\nf 1/1 2/1 3/1\n");
  EXPECT_EQ(m.UV.row(1), Vec2(0.5, 0.0).transpose());
}

TEST(ObjReader, NegativeIndicesAreRelative) {
  const TriMesh rel = readObjFromString(
      "v 0 0 0\nv 1 0 0\nv 1 1 0\nf -3 -2 -1\nv 0 1 0\nf -4 -2 -1\n");
  EXPECT_EQ(triangles(rel), (Tris{{0, 1, 2}, {0, 2, 3}}));
  const TriMesh tex = readObjFromString(
      "v 0 0 0\nv 1 0 0\nv 1 1 0\nvt 0.5 0.5\nvt 0.25 0.75\nf -3/-1 -2/-2 -1/-1\n");
  EXPECT_EQ(tex.UV.row(0), Vec2(0.25, 0.75).transpose());
  EXPECT_EQ(tex.UV.row(1), Vec2(0.5, 0.5).transpose());
}

TEST(ObjReader, ForwardReferencesAndCrlfAndCommentsAreAccepted) {
  const TriMesh m = readObjFromString(
      "# exported faces first\r\nf 1 2 3\r\n\r\n  v 0 0 0 # origin\r\nv 1 0 0\r\nv 0 1 0\r\n");
  EXPECT_EQ(m.vertexCount(), 3);
  EXPECT_EQ(triangles(m), (Tris{{0, 1, 2}}));
}

TEST(ObjReader, GroupsBecomeVertexSets) {
  const TriMesh m = readObjFromString(
      "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 0 0\nv 2 1 0\n"
      "g left\nf 1 2 3\nf 1 3 4\n"
      "g right shared\nf 2 5 6\nf 2 6 3\n"
      "o lip object\nv 1 2 0\nf 3 6 7\n");
  ASSERT_EQ(m.groups.size(), 4u);
  EXPECT_EQ(m.groups.at("left"), (std::vector<int>{0, 1, 2, 3}));
  EXPECT_EQ(m.groups.at("right"), (std::vector<int>{1, 2, 4, 5}));
  EXPECT_EQ(m.groups.at("shared"), (std::vector<int>{1, 2, 4, 5}));
  EXPECT_EQ(m.groups.at("lip object"), (std::vector<int>{2, 5, 6}));  // `o` ends the `g` groups
}

TEST(ObjReader, ReadObjLikeReusesRestTriangulation) {
  TempDir dir;
  // Rest: v1–v3 is the shorter diagonal. Deformed: v0–v2 would be shorter, but the rest wins.
  const std::string rest = dir.write("rest.obj", "v -2 0 0\nv 0 -1 0\nv 2 0 0\nv 0 1 0\nf 1 2 3 4\n");
  const std::string pose = dir.write("pose.obj", "v -1 0 0\nv 0 -3 0\nv 1 0 0\nv 0 3 0\nf 1 2 3 4\n");
  const TriMesh r = readObj(rest);
  const TriMesh p = readObjLike(pose, r);
  EXPECT_EQ(triangles(p), triangles(r));
  EXPECT_EQ(triangles(p), (Tris{{0, 1, 3}, {1, 2, 3}}));
  EXPECT_EQ(p.V(1, 1), -3.0);
  EXPECT_EQ(p.sourcePath, pose);

  const std::string other = dir.write("other.obj", "v -1 0 0\nv 0 -3 0\nv 1 0 0\nv 0 3 0\n\nf 1 2 4 3\n");
  try {
    readObjLike(other, r);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.line(), 6);
    EXPECT_THAT(e.message(), HasSubstr("differs from the rest mesh"));
  }
  // A triangulation of the rest polygons (either diagonal) is accepted too.
  const std::string split = dir.write("split.obj", "v -1 0 0\nv 0 -3 0\nv 1 0 0\nv 0 3 0\nf 1 2 3\nf 1 3 4\n");
  EXPECT_EQ(triangles(readObjLike(split, r)), triangles(r));
  const std::string flipped = dir.write("flipped.obj", "v -1 0 0\nv 0 -3 0\nv 1 0 0\nv 0 3 0\nf 1 2 3\nf 1 4 3\n");
  EXPECT_THROW(readObjLike(flipped, r), InputError);
  const std::string fewer = dir.write("fewer.obj", "v -1 0 0\nv 0 -3 0\nv 1 0 0\nf 1 2 3\n");
  try {
    readObjLike(fewer, r);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_THAT(e.message(), HasSubstr("has 3 vertices but the rest mesh"));
  }
}

TEST(ObjReader, ReadObjLikeOnIctExpressionShape) {
  MYO_REQUIRE_SHARED_DATA();
  const auto dir = test::sharedDataDir() / "ict";
  const TriMesh rest = readObj((dir / "head_skin.obj").string());
  const TriMesh smile = readObjLike((dir / "expression_mouthSmile_L.obj").string(), rest);
  EXPECT_EQ(smile.vertexCount(), rest.vertexCount());
  EXPECT_TRUE(smile.F == rest.F);
  EXPECT_GT((smile.V - rest.V).rowwise().norm().maxCoeff(), 0.1);  // the smile moves something (cm)
}

// ---- strict errors, each from a small inline file, naming the fault and its line ----

TEST(ObjReaderErrors, MissingFile) {
  try {
    readObj("/nonexistent/dir/face.obj");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "/nonexistent/dir/face.obj");
    EXPECT_THAT(e.what(), HasSubstr("/nonexistent/dir/face.obj: cannot open"));
  }
}

TEST(ObjReaderErrors, UnreadableNumbers) {
  expectError("v 0 0 0\nv 1 abc 0\nv 0 1 0\nf 1 2 3\n", 2, "unreadable number 'abc'");
  expectError("v 0 0 0\nv 1 0 0\nv 0 1 0x\nf 1 2 3\n", 3, "unreadable number '0x'");
  expectError("v 0 0 0\nv 1 0\nv 0 1 0\nf 1 2 3\n", 2, "expected at least 3");
  expectError("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 three\n", 4, "unreadable index 'three'");
  expectError("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2/1/1/1 3\n", 4, "unreadable face corner");
  expectError("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0.5 zero\nf 1 2 3\n", 4, "unreadable number 'zero'");
}

TEST(ObjReaderErrors, IndexOutOfRange) {
  expectError("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n", 4, "vertex index 9 is out of range: the file has 3");
  expectError("v 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -4\n", 4, "vertex index -4 is out of range");
  expectError("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n", 4, "index 0 is out of range");
  expectError("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/2 3/1\n", 5,
              "texture coordinate index 2 is out of range");
}

TEST(ObjReaderErrors, TooFewVertices) {
  expectError("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2\n", 5, "face has 2 vertices");
}

TEST(ObjReaderErrors, NonFiniteCoordinates) {
  expectError("v 0 0 0\nv 1 nan 0\nv 0 1 0\nf 1 2 3\n", 2, "vertex 1 has a non-finite coordinate");
  expectError("v 0 0 0\nv 1 0 0\nv 0 1e999 0\nf 1 2 3\n", 3, "vertex 2 has a non-finite coordinate");
  expectError("v 0 0 0\nv 1 0 0\nv 0 1 -inf\nf 1 2 3\n", 3, "non-finite");
}

TEST(ObjReaderErrors, DegenerateTriangle) {
  // Triangle 1 has three collinear corners.
  expectError("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 2 0 0\nf 1 2 3\n# a comment\nf 1 2 4\n", 7,
              "triangle 1 (face on line 7) is degenerate");
}

TEST(ObjReaderErrors, NonManifoldEdge) {
  expectError("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\n"
              "f 1 2 3\nf 2 1 4\nf 1 2 5\n",
              8, "edge (0, 1) is shared by more than two faces");
}

TEST(ObjReaderErrors, InconsistentOrientation) {
  expectError("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nf 1 2 3\nf 1 2 4\n", 6, "inconsistent orientation");
}

TEST(ObjReaderErrors, NoFaces) {
  expectError("v 0 0 0\nv 1 0 0\nv 0 1 0\n", 0, "no faces");
  expectError("", 0, "no faces");
}

TEST(ObjReaderErrors, LineLongerThan16MiB) {
  std::string text = "v 0 0 0\n# ";
  text.append(size_t{16} << 20, 'x');
  text += "\nv 1 0 0\n";
  expectError(text, 2, "line 2 is longer than 16 MiB");
  MeshReport report;
  EXPECT_THROW(readObjFromStringLenient(text, report), InputError);  // cannot be read at all
}

TEST(ObjReaderErrors, FirstFaultInFileOrderWins) {
  // The forward reference on line 4 is only known to be out of range at the end of the scan.
  expectError("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\nv 0 0 x\n", 4, "vertex index 7");
}

// ---- lenient reading ----

TEST(ObjReaderLenient, RecordsEveryFaultAndSkipsBadFaces) {
  const std::string text =
      "v 0 0 0\n"      // 1
      "v 1 0 0\n"      // 2
      "v 1 1 0\n"      // 3
      "v 0 1 0\n"      // 4
      "v 2 0 0\n"      // 5
      "v 2 q 0\n"      // 6  unreadable
      "v inf 0 0\n"    // 7  non-finite
      "v 3 0 0\n"      // 8
      "f 1 2 3\n"      // 9  ok
      "f 1 3 4\n"      // 10 ok
      "f 1 2 99\n"     // 11 out of range
      "f 1 2\n"        // 12 too few
      "f 2 5 8\n"      // 13 degenerate (collinear on the x axis)
      "f 3 1 5\n"      // 14 third face on edge (0, 2): non-manifold
      "f 2 x 3\n"      // 15 unreadable index
      "f 3 4 8\n";     // 16 runs edge 2→3 the same way as line 10: inconsistent
  MeshReport report;
  const TriMesh m = readObjFromStringLenient(text, report, "bad.obj");
  EXPECT_EQ(m.vertexCount(), 8);                     // no vertex dropped: order must hold
  EXPECT_TRUE(std::isnan(m.V(5, 1)));                // the unreadable vertex is kept as NaN
  EXPECT_TRUE(std::isinf(m.V(6, 0)));
  EXPECT_EQ(report.count("unreadable_number"), 2);   // line 6 and line 15
  EXPECT_EQ(report.count("non_finite_coordinate"), 1);
  EXPECT_EQ(report.count("index_out_of_range"), 1);
  EXPECT_EQ(report.count("too_few_vertices"), 1);
  EXPECT_EQ(report.count("degenerate_triangle"), 1);
  EXPECT_EQ(report.count("non_manifold_edge"), 1);
  EXPECT_EQ(report.count("inconsistent_orientation"), 1);
  EXPECT_EQ(m.triangleCount(), 5);  // lines 9, 10, 13, 14, 16
  for (size_t i = 1; i < report.faults.size(); ++i)
    EXPECT_LE(report.faults[i - 1].line, report.faults[i].line) << "faults must be in file order";
  EXPECT_EQ(report.faults.front().line, 6);
  EXPECT_EQ(report.faults.front().kind, "unreadable_number");
}

TEST(ObjReaderLenient, CleanMeshHasNoFaults) {
  MeshReport report;
  const TriMesh m = readObjFromStringLenient(kTwoTriangles, report);
  EXPECT_TRUE(report.faults.empty());
  EXPECT_EQ(m.triangleCount(), 2);
}

// ---- validateMesh on meshes built in memory ----

TEST(ValidateMesh, AcceptsPrimitivesAndNamesFaults) {
  EXPECT_NO_THROW(validateMesh(gridMesh(2, 1, 4, 3)));
  EXPECT_NO_THROW(validateMesh(icosphere(1, 2)));

  TriMesh nan = gridMesh(1, 1, 2, 2);
  nan.V(4, 2) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THAT([&] { validateMesh(nan); },
              ::testing::ThrowsMessage<InputError>(HasSubstr("vertex 4 has a non-finite coordinate")));

  TriMesh flipped = gridMesh(1, 1, 2, 2);
  std::swap(flipped.F(3, 1), flipped.F(3, 2));
  EXPECT_THAT([&] { validateMesh(flipped); },
              ::testing::ThrowsMessage<InputError>(HasSubstr("inconsistent orientation")));

  TriMesh flat = gridMesh(1, 1, 2, 2);
  flat.V.row(flat.F(0, 2)) = flat.V.row(flat.F(0, 0));
  EXPECT_THAT([&] { validateMesh(flat); },
              ::testing::ThrowsMessage<InputError>(HasSubstr("is degenerate")));
}

}  // namespace
}  // namespace myo
