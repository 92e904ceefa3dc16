// writeObj: exact round trips through readObj, and no temporary file left behind. writeObjLikeFile:
// only the positions of a user's file change.
#include "myoshell/io/obj_writer.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "myoshell/core/errors.h"
#include "myoshell/mesh/obj_reader.h"
#include "myoshell/mesh/primitives.h"
#include "support/uv_seam_mesh.h"

namespace myo {
namespace {

namespace fs = std::filesystem;

class ObjDir {
 public:
  ObjDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = fs::temp_directory_path() /
            (std::string("myo_objw_") + info->test_suite_name() + "_" + info->name() + "_" + std::to_string(::getpid()));
    fs::create_directories(path_);
  }
  ~ObjDir() {
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

TEST(WriteObj, RoundTripKeepsQuadsUvsAndExactPositions) {
  ObjDir dir;
  const std::string src = dir.write(
      "quad.obj",
      "v 0.1 0.2 0.3\nv 1.0000000000000002 0 0\nv 1 1 1e-300\nv 0 1 0\nv 2 0.5 0\n"
      "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvt 0.5 0.5\n"
      "f 1/1 2/2 3/3 4/4\nf 2/2 5/5 3/3\n");
  const TriMesh m = readObj(src);
  const std::string out = (dir.path() / "out.obj").string();
  writeObj(out, m);
  const TriMesh back = readObj(out);
  EXPECT_TRUE(back.V == m.V);  // bitwise: shortest round-trip formatting
  EXPECT_TRUE(back.UV == m.UV);
  EXPECT_EQ(back.polygons, m.polygons);
  EXPECT_TRUE(back.F == m.F);

  MatX3 moved = m.V;
  moved.col(2).array() += 1.5;
  writeObj(out, m, &moved);
  EXPECT_TRUE(readObj(out).V == moved);
  for (const auto& entry : fs::directory_iterator(dir.path()))
    EXPECT_EQ(entry.path().string().find(".tmp"), std::string::npos) << "temporary file left behind";

  // Without polygons the triangles are written as they are.
  TriMesh grid = gridMesh(1, 1, 2, 1);
  grid.polygons.clear();
  writeObj(out, grid);
  EXPECT_TRUE(readObj(out).F == grid.F);
}

TEST(WriteObjLikeFile, ReplacesOnlyThePositions) {
  ObjDir dir;
  // Seam UVs (vertex 2 has two), a quad, a group, a comment, CRLF lines, a vertex colour, tabs.
  const std::string before = "# my head\r\nv 0.1 0.2 0.3 1 0 0\r\nv\t1 0 0\r\n  v 1 1 0\r\nv 0 1 0\r\nv 2 0.5 0\r\n"
                             "vt 0 0\r\nvt 1 0\r\nvt 1 1\r\nvt 0 1\r\nvt 0.9 0.9\r\ng skin\r\n"
                             "f 1/1 2/2 3/3 4/4\r\nf 2/5 5/5 3/3\r\n";
  const std::string src = dir.write("src.obj", before);
  const TriMesh m = readObj(src);
  MatX3 moved = m.V;
  moved.col(0).array() += 0.1;
  moved(3, 2) = -1e-300;
  const std::string out = (dir.path() / "out.obj").string();
  ASSERT_TRUE(writeObjLikeFile(out, src, moved));
  std::ifstream in(out, std::ios::binary);
  const std::string after((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  auto replace = [](std::string s, const std::string& from, const std::string& to) {
    const size_t at = s.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    return at == std::string::npos ? s : s.replace(at, from.size(), to);
  };
  std::string expected = replace(before, "v 0.1 0.2 0.3 1", "v 0.2 0.2 0.3 1");
  expected = replace(expected, "v\t1 0 0", "v\t1.1 0 0");
  expected = replace(expected, "  v 1 1 0", "  v 1.1 1 0");
  expected = replace(expected, "v 0 1 0", "v 0.1 1 -1e-300");
  expected = replace(expected, "v 2 0.5 0", "v 2.1 0.5 0");
  EXPECT_EQ(after, expected);
  const TriMesh back = readObj(out);
  EXPECT_TRUE(back.V == moved);  // bitwise
  EXPECT_EQ(back.polygons, m.polygons);

  // Another vertex count: nothing written, the caller falls back to writeObj.
  const std::string none = (dir.path() / "none.obj").string();
  EXPECT_FALSE(writeObjLikeFile(none, src, moved.topRows(3)));
  EXPECT_FALSE(fs::exists(none));
  EXPECT_THROW(writeObjLikeFile(none, (dir.path() / "missing.obj").string(), moved), InputError);
}

// A mesh read from an OBJ with UV seams is written with its corners' own texture coordinates (the
// distinct ones, in order of first appearance), so reading it back gives the same corner UVs.
TEST(WriteObj, KeepsUvSeams) {
  ObjDir dir;
  const TriMesh m = readObjFromString(test::kUvSeamObj, "seam.obj");
  const std::string out = (dir.path() / "seam.obj").string();
  writeObj(out, m);
  std::ifstream in(out);
  const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  EXPECT_NE(text.find("vt 0 0\nvt 0.4 0\nvt 0.4 1\nvt 0 1\nvt 0.6 0\nvt 1 0\nvt 0.6 1\nvt 1 1\nf"), std::string::npos)
      << text;
  EXPECT_NE(text.find("f 1/1 2/2 5/3 4/4\nf 2/5 3/6 6/8 5/7\nf 3/6 7/1 6/8\n"), std::string::npos) << text;
  const TriMesh back = readObj(out);
  EXPECT_EQ(back.polygons, m.polygons);
  EXPECT_EQ(back.F, m.F);
  EXPECT_EQ(back.cornerUV, m.cornerUV);
  EXPECT_EQ(back.UV, m.UV);

  // Without polygons the triangles carry the corner UVs.
  TriMesh triangles = m;
  triangles.polygons.clear();
  triangles.sourcePolygon.clear();
  writeObj(out, triangles);
  EXPECT_EQ(readObj(out).cornerUV, m.cornerUV);
}

TEST(WriteObj, UnwritableDirectoryIsAnInputError) {
  EXPECT_THROW(writeObj("/nonexistent/dir/out.obj", gridMesh(1, 1, 1, 1)), InputError);
}

}  // namespace
}  // namespace myo
