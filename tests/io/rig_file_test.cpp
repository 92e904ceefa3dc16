// The glTF rig reader (io/rig_file.h): ICT's rig against its OBJs, a hand-built rig with a node
// hierarchy, a sparse target and a seam copy, and the exact errors of bad files.
#include "myoshell/io/rig_file.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "myoshell/core/errors.h"
#include "myoshell/mesh/obj_reader.h"
#include "support/scratch_folder.h"
#include "support/test_data.h"

namespace myo {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

// ---- building tiny rigs by hand ---------------------------------------------------------------

void putU32(std::string& s, std::uint32_t v) { s.append(reinterpret_cast<const char*>(&v), 4); }
void putF32(std::string& s, float v) { s.append(reinterpret_cast<const char*>(&v), 4); }

std::string glb(const std::string& jsonText, const std::string& bin) {
  std::string j = jsonText, b = bin;
  while (j.size() % 4) j.push_back(' ');
  while (b.size() % 4) b.push_back('\0');
  std::string out;
  putU32(out, 0x46546C67);
  putU32(out, 2);
  putU32(out, static_cast<std::uint32_t>(12 + 8 + j.size() + (b.empty() ? 0 : 8 + b.size())));
  putU32(out, static_cast<std::uint32_t>(j.size()));
  putU32(out, 0x4E4F534A);
  out += j;
  if (!b.empty()) {
    putU32(out, static_cast<std::uint32_t>(b.size()));
    putU32(out, 0x004E4942);
    out += b;
  }
  return out;
}

std::string base64(const std::string& data) {
  static const char* k = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  std::size_t i = 0;
  for (; i + 2 < data.size(); i += 3) {
    const std::uint32_t v = (std::uint8_t(data[i]) << 16) | (std::uint8_t(data[i + 1]) << 8) | std::uint8_t(data[i + 2]);
    for (int s = 18; s >= 0; s -= 6) out.push_back(k[(v >> s) & 63]);
  }
  if (i + 1 == data.size()) {
    const std::uint32_t v = std::uint8_t(data[i]) << 16;
    out += {k[(v >> 18) & 63], k[(v >> 12) & 63], '=', '='};
  } else if (i + 2 == data.size()) {
    const std::uint32_t v = (std::uint8_t(data[i]) << 16) | (std::uint8_t(data[i + 1]) << 8);
    out += {k[(v >> 18) & 63], k[(v >> 12) & 63], k[(v >> 6) & 63], '='};
  }
  return out;
}

// A unit quad (metres) in z = 0 whose corner (1, 1, 0) is split at a seam: vertex 4 copies vertex 2.
// Target "lift" (sparse, no bufferView) raises both copies of that corner by 0.5 m; target "push"
// (dense) moves vertex 0 by (0.25, 0, 0) m. The mesh's node (translation, rotation, scale) is the
// child of a node translated by (0, 0, 1) m.
struct Tiny {
  json doc;
  std::string bin;
};

Tiny tinyRig() {
  Tiny t;
  const float pos[5][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {1, 1, 0}};
  for (const auto& p : pos)
    for (float c : p) putF32(t.bin, c);  // bytes 0..60: positions
  for (std::uint32_t i : {0u, 1u, 2u, 0u, 4u, 3u}) putU32(t.bin, i);  // 60..84: indices
  for (std::uint32_t i : {2u, 4u}) putU32(t.bin, i);  // 84..92: sparse indices
  for (int k = 0; k < 2; ++k)
    for (float c : {0.0f, 0.0f, 0.5f}) putF32(t.bin, c);  // 92..116: sparse values
  for (int v = 0; v < 5; ++v)
    for (float c : {v == 0 ? 0.25f : 0.0f, 0.0f, 0.0f}) putF32(t.bin, c);  // 116..176: dense deltas
  const double h = std::sqrt(0.5);
  t.doc = {
      {"asset", {{"version", "2.0"}}},
      {"scene", 0},
      {"scenes", {{{"nodes", {0}}}}},
      {"nodes",
       {{{"name", "root"}, {"translation", {0, 0, 1}}, {"children", {1}}},
        {{"name", "head"}, {"mesh", 0}, {"translation", {1, 2, 3}}, {"rotation", {0, 0, h, h}}, {"scale", {2, 2, 2}}}}},
      {"meshes",
       {{{"primitives",
          {{{"attributes", {{"POSITION", 0}}}, {"indices", 1}, {"mode", 4}, {"targets", {{{"POSITION", 2}}, {{"POSITION", 3}}}}}}},
         {"extras", {{"targetNames", {"lift", "push"}}}}}}},
      {"buffers", {{{"byteLength", t.bin.size()}}}},
      {"bufferViews",
       {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 60}},
        {{"buffer", 0}, {"byteOffset", 60}, {"byteLength", 24}},
        {{"buffer", 0}, {"byteOffset", 84}, {"byteLength", 8}},
        {{"buffer", 0}, {"byteOffset", 92}, {"byteLength", 24}},
        {{"buffer", 0}, {"byteOffset", 116}, {"byteLength", 60}}}},
      {"accessors",
       {{{"bufferView", 0}, {"componentType", 5126}, {"count", 5}, {"type", "VEC3"}},
        {{"bufferView", 1}, {"componentType", 5125}, {"count", 6}, {"type", "SCALAR"}},
        {{"componentType", 5126},
         {"count", 5},
         {"type", "VEC3"},
         {"sparse",
          {{"count", 2},
           {"indices", {{"bufferView", 2}, {"componentType", 5125}}},
           {"values", {{"bufferView", 3}}}}}},
        {{"bufferView", 4}, {"componentType", 5126}, {"count", 5}, {"type", "VEC3"}}}}};
  return t;
}

class RigFileTest : public test::ScratchFolderTest {
 protected:
  // The message of the InputError that reading `bytes` as `name` raises ("" when none).
  std::string error(const std::string& name, const std::string& bytes) {
    const std::string path = write(name, bytes);
    try {
      readRig(path);
    } catch (const InputError& e) {
      const std::string what = e.what();
      EXPECT_EQ(what.rfind(path + ": ", 0), 0u) << what;  // every message names the file
      return what.substr(path.size() + 2);
    }
    return "";
  }
};

// The world transform of the tiny rig, in cm: root (0,0,1) m, then T (1,2,3) m, Rz(90°), S 2.
Vec3 tinyWorld(const Vec3& p) {
  const Vec3 rotated(-2 * p.y(), 2 * p.x(), 2 * p.z());
  return 100.0 * (rotated + Vec3(1, 2, 4));
}

void expectTinyRig(const RigFile& rig) {
  ASSERT_EQ(rig.vertexCount(), 4);  // the seam copy is welded
  EXPECT_EQ(rig.weldedIndex, (std::vector<int>{0, 1, 2, 3, 2}));
  ASSERT_EQ(rig.base.F.rows(), 2);
  EXPECT_EQ(rig.base.F.row(0), (Eigen::RowVector3i(0, 1, 2)));
  EXPECT_EQ(rig.base.F.row(1), (Eigen::RowVector3i(0, 2, 3)));
  const Vec3 file[4] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  for (int v = 0; v < 4; ++v) EXPECT_LT((rig.base.V.row(v).transpose() - tinyWorld(file[v])).norm(), 1e-9) << v;
  ASSERT_EQ(rig.names, (std::vector<std::string>{"lift", "push"}));
  const MatX3 lift = rig.delta("lift");
  const MatX3 push = rig.delta("push");
  for (int v = 0; v < 4; ++v) {
    // A displacement turns and scales with the node (no translation): lift is 2 × 0.5 m up in z.
    const Vec3 expectLift = v == 2 ? Vec3(0, 0, 100) : Vec3::Zero();
    const Vec3 expectPush = v == 0 ? Vec3(0, 50, 0) : Vec3::Zero();  // x turned to y, doubled
    EXPECT_LT((lift.row(v).transpose() - expectLift).norm(), 1e-9) << v;
    EXPECT_LT((push.row(v).transpose() - expectPush).norm(), 1e-9) << v;
  }
}

TEST_F(RigFileTest, TinyGlbWithNodesSparseTargetAndSeamReadsInCentimetres) {
  const Tiny t = tinyRig();
  expectTinyRig(readRig(write("tiny.glb", glb(t.doc.dump(), t.bin))));
}

TEST_F(RigFileTest, TinyGltfWithDataUriAndSidecarBuffersReadsTheSame) {
  Tiny t = tinyRig();
  t.doc["buffers"][0]["uri"] = "data:application/octet-stream;base64," + base64(t.bin);
  expectTinyRig(readRig(write("tiny.gltf", t.doc.dump())));
  t.doc["buffers"][0]["uri"] = "tiny.bin";
  write("tiny.bin", t.bin);
  expectTinyRig(readRig(write("side.gltf", t.doc.dump())));
}

TEST_F(RigFileTest, PrimitiveExtrasNamesAndMatrixNodeAndNonIndexedTriangles) {
  Tiny t = tinyRig();
  t.doc["meshes"][0]["primitives"][0]["extras"] = t.doc["meshes"][0]["extras"];
  t.doc["meshes"][0].erase("extras");
  t.doc["meshes"][0]["primitives"][0].erase("indices");  // 5 vertices: one triangle and 2 left over
  t.doc["accessors"][0]["count"] = 3;
  t.doc["accessors"][2]["count"] = 3;
  t.doc["accessors"][2]["sparse"]["count"] = 1;
  t.doc["accessors"][3]["count"] = 3;
  t.doc["nodes"] = {{{"mesh", 0}, {"matrix", {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0.5, 0, 0, 1}}}};
  const RigFile rig = readRig(write("plain.glb", glb(t.doc.dump(), t.bin)));
  ASSERT_EQ(rig.vertexCount(), 3);
  EXPECT_EQ(rig.base.F.row(0), (Eigen::RowVector3i(0, 1, 2)));
  EXPECT_LT((rig.base.V.row(1).transpose() - Vec3(150, 0, 0)).norm(), 1e-9);  // matrix column 3: x + 0.5 m
  EXPECT_LT((rig.delta("lift").row(2).transpose() - Vec3(0, 0, 50)).norm(), 1e-9);
}

TEST_F(RigFileTest, ShapeArgumentSplitsAtTheLastHashAndListsNamesWhenUnknown) {
  const Tiny t = tinyRig();
  const std::string path = write("tiny.glb", glb(t.doc.dump(), t.bin));
  EXPECT_EQ(splitRigShape("a#b.glb#smile").path, "a#b.glb");
  EXPECT_EQ(splitRigShape("a#b.glb#smile").shape, "smile");
  EXPECT_EQ(splitRigShape("rig.glb").shape, "");
  EXPECT_TRUE(isRigShapeArgument("x/RIG.GLB#jawOpen"));
  EXPECT_TRUE(isRigShapeArgument("x/rig.gltf#jawOpen"));
  EXPECT_FALSE(isRigShapeArgument("x/head.obj"));
  EXPECT_FALSE(isRigShapeArgument("x/rig.glb"));
  const MatX3 lift = rigShape(path + "#lift");
  EXPECT_DOUBLE_EQ(lift(2, 2), 400.0 + 100.0);
  try {
    rigShape(path + "#smile");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), path + ": no shape 'smile' (the rig has: lift, push)");
  }
  try {
    rigShape(path);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), path + ": name a shape after '#' (RIG.glb#shape)");
  }
}

TEST_F(RigFileTest, BadFilesGiveTheFileThePointerAndTheFault) {
  const Tiny good = tinyRig();
  const std::string goodGlb = glb(good.doc.dump(), good.bin);
  EXPECT_EQ(error("magic.glb", "GLTF" + goodGlb.substr(4)), "bad magic: not a GLB file (it does not start with 'glTF')");
  EXPECT_EQ(error("short.glb", goodGlb.substr(0, 100)),
            "GLB truncated: the header says " + std::to_string(goodGlb.size()) + " bytes, the file has 100");
  {
    std::string chunk = goodGlb;
    const std::uint32_t huge = 1u << 30;
    std::memcpy(&chunk[12], &huge, 4);
    EXPECT_EQ(error("chunk.glb", chunk).rfind("GLB chunk 0 truncated (1073741824 bytes declared, ", 0), 0u);
  }
  EXPECT_EQ(error("empty.gltf", ""), "empty file (not glTF)");
  EXPECT_EQ(error("text.gltf", "{").rfind("not glTF: the JSON does not parse", 0), 0u);
  auto broken = [&](const std::string& name, void (*edit)(Tiny&)) {
    Tiny t = tinyRig();
    edit(t);
    return error(name, glb(t.doc.dump(), t.bin));
  };
  EXPECT_EQ(broken("nopos.glb", [](Tiny& t) { t.doc["meshes"][0]["primitives"][0]["attributes"].erase("POSITION"); }),
            "/meshes/0/primitives/0/attributes/POSITION: missing");
  EXPECT_EQ(broken("names.glb", [](Tiny& t) { t.doc["meshes"][0]["extras"]["targetNames"] = {"lift"}; }),
            "/meshes/0/extras/targetNames: 1 names for 2 targets");
  EXPECT_EQ(broken("nonames.glb", [](Tiny& t) { t.doc["meshes"][0].erase("extras"); }),
            "/meshes/0/extras/targetNames: missing (the rig's target names)");
  EXPECT_EQ(broken("range.glb", [](Tiny& t) { t.doc["accessors"][0]["count"] = 6; }),
            "/accessors/0: out of range: 6 elements need 72 bytes of bufferView 0, which has 60");
  EXPECT_EQ(broken("huge.glb", [](Tiny& t) { t.doc["accessors"][2]["count"] = 1 << 20; }),
            "/accessors/2/count: 1048576 out of range (limit 1048576)");
  EXPECT_EQ(broken("view.glb", [](Tiny& t) { t.doc["bufferViews"][4]["byteLength"] = 600; }),
            "/bufferViews/4: bytes 116..716 past the end of buffer 0 (176 bytes)");
  EXPECT_EQ(broken("ushort.glb", [](Tiny& t) { t.doc["accessors"][0]["componentType"] = 5123; }),
            "/accessors/0/componentType: 5123: positions must be FLOAT (5126)");
  EXPECT_EQ(broken("norm.glb", [](Tiny& t) { t.doc["accessors"][3]["normalized"] = true; }),
            "/accessors/3/normalized: normalized accessors are not read here (positions and indices are not normalized)");
  EXPECT_EQ(broken("strip.glb", [](Tiny& t) { t.doc["meshes"][0]["primitives"][0]["mode"] = 5; }),
            "/meshes/0/primitives/0/mode: 5: only triangles (4) are read");
  EXPECT_EQ(broken("index.glb", [](Tiny& t) { const std::uint32_t seven = 7; std::memcpy(&t.bin[64], &seven, 4); }),
            "/meshes/0/primitives/0/indices: index 7 at 1 out of range (5 vertices)");
  EXPECT_EQ(broken("sparse.glb", [](Tiny& t) { t.doc["accessors"][2]["count"] = 3; }),
            "/accessors/2/sparse/indices: index 4 out of range (count 3)");
  EXPECT_EQ(broken("twice.glb", [](Tiny& t) { t.doc["meshes"][0]["extras"]["targetNames"] = {"lift", "lift"}; }),
            "/meshes/0/extras/targetNames/1: 'lift' appears twice");
  EXPECT_EQ(broken("cycle.glb", [](Tiny& t) { t.doc["nodes"][1]["children"] = {0}; }), "/nodes: the node hierarchy has a cycle");
  EXPECT_EQ(broken("notargets.glb", [](Tiny& t) { t.doc["meshes"][0]["primitives"][0].erase("targets"); }),
            "/meshes: no mesh has morph targets (not a blendshape rig)");
  {
    Tiny t = tinyRig();
    const float nan = std::nanf("");
    std::memcpy(&t.bin[116 + 4], &nan, 4);
    EXPECT_EQ(error("nan.glb", glb(t.doc.dump(), t.bin)), "/accessors/3: non-finite value in element 0");
  }
  {
    Tiny t = tinyRig();
    t.doc["buffers"][0]["uri"] = "missing.bin";
    EXPECT_EQ(error("side.gltf", t.doc.dump()),
              (dir_ / "missing.bin").string() + ": cannot open the buffer file named by /buffers/0/uri");
  }
}

// ---- ICT's rig (../shared/data/ict) ----------------------------------------------------------

TEST(RigFileIct, ReadsIctsThirtySevenShapesInHeadSkinOrder) {
  MYO_REQUIRE_SHARED_DATA();
  const fs::path dir = test::sharedDataDir() / "ict";
  const RigFile rig = readRig((dir / "ict_arkit_rig.glb").string());
  ASSERT_EQ(rig.names.size(), 37u);
  EXPECT_EQ(rig.names.front(), "browInnerUp_L");
  EXPECT_EQ(rig.names.back(), "mouthUpperUp_R");
  const TriMesh skin = readObj((dir / "head_skin.obj").string());
  ASSERT_EQ(rig.vertexCount(), 11248);
  ASSERT_EQ(skin.V.rows(), 11248);
  EXPECT_LT((rig.base.V - skin.V).cwiseAbs().maxCoeff(), 1e-5);  // float metres × 100 vs the OBJ's cm
  const TriMesh smile = readObjLike((dir / "expression_mouthSmile_L.obj").string(), skin);
  EXPECT_LT((rig.shape("mouthSmile_L") - smile.V).cwiseAbs().maxCoeff(), 1e-4);
  EXPECT_GT((smile.V - skin.V).cwiseAbs().maxCoeff(), 0.5);  // the smile does move (cm)
}

}  // namespace
}  // namespace myo
