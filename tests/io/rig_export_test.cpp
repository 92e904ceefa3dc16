// Rigs written by writeRigGlb (io/rig_export.h) read back by tinygltf (Debian libtinygltf-dev, a
// reader we do not use for reading) and by our own reader (io/rig_file.h): names in
// meshes[0].extras.targetNames, dense float targets in metres, the vertex order kept; a failed
// write leaves no file.
#include <gtest/gtest.h>
#include <tiny_gltf.h>
#include <unistd.h>

#include <cstring>
#include <filesystem>

#include "myoshell/core/errors.h"
#include "myoshell/io/rig_export.h"
#include "myoshell/io/rig_file.h"
#include "myoshell/mesh/geometry.h"
#include "myoshell/mesh/obj_reader.h"
#include "myoshell/mesh/uv_seams.h"
#include "support/seam_rig.h"
#include "support/uv_seam_mesh.h"

namespace myo {
namespace {

namespace fs = std::filesystem;

// A bent strip of 10 vertices (8 triangles) and three named targets.
RigExport strip() {
  RigExport rig;
  rig.name = "strip";
  rig.rest.resize(10, 3);
  for (int i = 0; i < 5; ++i) {
    rig.rest.row(2 * i) << i, 0.1 * i * i, 10;
    rig.rest.row(2 * i + 1) << i, 0.1 * i * i + 1, 10.5;
  }
  rig.triangles.resize(8, 3);
  for (int i = 0; i < 4; ++i) {
    rig.triangles.row(2 * i) << 2 * i, 2 * i + 2, 2 * i + 3;
    rig.triangles.row(2 * i + 1) << 2 * i, 2 * i + 3, 2 * i + 1;
  }
  rig.names = {"mouthSmileLeft", "browInnerUp", "tongueOut"};
  for (int k = 0; k < 3; ++k) {
    MatX3 d = MatX3::Zero(10, 3);
    if (k < 2)
      for (int v = 0; v < 10; ++v) d.row(v) << 0.01 * v * (k + 1), -0.02 * k, 0.3 * (v % 2);
    rig.deltas.push_back(d);
  }
  return rig;
}

fs::path scratch() {
  const fs::path dir = fs::temp_directory_path() / ("myo_rig_export_" + std::to_string(::getpid()) + "_" +
                                                    ::testing::UnitTest::GetInstance()->current_test_info()->name());
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// The float VEC3 data of an accessor (dense, tightly packed or strided by 12).
MatX3 accessorData(const tinygltf::Model& m, int index) {
  const tinygltf::Accessor& a = m.accessors[static_cast<size_t>(index)];
  const tinygltf::BufferView& v = m.bufferViews[static_cast<size_t>(a.bufferView)];
  const unsigned char* p = m.buffers[static_cast<size_t>(v.buffer)].data.data() + v.byteOffset + a.byteOffset;
  MatX3 out(static_cast<Eigen::Index>(a.count), 3);
  for (size_t i = 0; i < a.count; ++i)
    for (int c = 0; c < 3; ++c) {
      float f;
      std::memcpy(&f, p + 12 * i + 4 * static_cast<size_t>(c), 4);
      out(static_cast<Eigen::Index>(i), c) = f;
    }
  return out;
}

TEST(RigExport, TinyGltfReadsTheNamesAndTheTargetsInMetres) {
  const fs::path dir = scratch();
  const RigExport rig = strip();
  writeRigGlb(dir / "rig.glb", rig);
  tinygltf::TinyGLTF loader;
  tinygltf::Model model;
  std::string err, warn;
  ASSERT_TRUE(loader.LoadBinaryFromFile(&model, &err, &warn, (dir / "rig.glb").string())) << err;
  ASSERT_EQ(model.meshes.size(), 1u);
  const tinygltf::Mesh& mesh = model.meshes[0];
  const tinygltf::Value& names = mesh.extras.Get("targetNames");
  ASSERT_TRUE(names.IsArray());
  ASSERT_EQ(names.ArrayLen(), 3u);
  for (int k = 0; k < 3; ++k) EXPECT_EQ(names.Get(k).Get<std::string>(), rig.names[static_cast<size_t>(k)]);
  ASSERT_EQ(mesh.primitives.size(), 1u);
  const tinygltf::Primitive& prim = mesh.primitives[0];
  EXPECT_LT((accessorData(model, prim.attributes.at("POSITION")) - rig.rest * 0.01).cwiseAbs().maxCoeff(), 1e-7);
  ASSERT_EQ(prim.targets.size(), 3u);
  for (size_t k = 0; k < 3; ++k) {
    const tinygltf::Accessor& a = model.accessors[static_cast<size_t>(prim.targets[k].at("POSITION"))];
    EXPECT_FALSE(a.sparse.isSparse);
    EXPECT_LT((accessorData(model, prim.targets[k].at("POSITION")) - rig.deltas[k] * 0.01).cwiseAbs().maxCoeff(), 1e-8) << k;
  }
  EXPECT_EQ(mesh.weights, std::vector<double>(3, 0.0));
  ASSERT_EQ(model.nodes.size(), 1u);
  EXPECT_TRUE(model.nodes[0].scale.empty());
  EXPECT_TRUE(model.nodes[0].matrix.empty());
  fs::remove_all(dir);
}

TEST(RigExport, OurReaderGetsTheRigBackInCentimetres) {
  const fs::path dir = scratch();
  const RigExport rig = strip();
  writeRigGlb(dir / "rig.glb", rig);
  const RigFile back = readRig((dir / "rig.glb").string());
  EXPECT_EQ(back.names, rig.names);
  ASSERT_EQ(back.vertexCount(), 10);
  EXPECT_LT((back.base.V - rig.rest).cwiseAbs().maxCoeff(), 1e-5);
  EXPECT_EQ(back.base.F, rig.triangles);
  for (size_t k = 0; k < 3; ++k) EXPECT_LT((back.delta(rig.names[k]) - rig.deltas[k]).cwiseAbs().maxCoeff(), 1e-5) << k;
  fs::remove_all(dir);
}

using test::seamRig;  // the seam head as a rig with two targets

// The float VEC2 data of a tightly packed accessor.
MatX2 accessorVec2(const tinygltf::Model& m, int index) {
  const tinygltf::Accessor& a = m.accessors[static_cast<size_t>(index)];
  const tinygltf::BufferView& v = m.bufferViews[static_cast<size_t>(a.bufferView)];
  const unsigned char* p = m.buffers[static_cast<size_t>(v.buffer)].data.data() + v.byteOffset + a.byteOffset;
  MatX2 out(static_cast<Eigen::Index>(a.count), 2);
  for (size_t i = 0; i < 2 * a.count; ++i) {
    float f;
    std::memcpy(&f, p + 4 * i, 4);
    out(static_cast<Eigen::Index>(i / 2), static_cast<Eigen::Index>(i % 2)) = f;
  }
  return out;
}

// The UNSIGNED_INT triangle indices of a primitive.
MatX3i triangleIndices(const tinygltf::Model& m, const tinygltf::Primitive& prim) {
  const tinygltf::Accessor& a = m.accessors[static_cast<size_t>(prim.indices)];
  EXPECT_EQ(a.componentType, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT);
  const tinygltf::BufferView& v = m.bufferViews[static_cast<size_t>(a.bufferView)];
  const unsigned char* p = m.buffers[static_cast<size_t>(v.buffer)].data.data() + v.byteOffset + a.byteOffset;
  MatX3i out(static_cast<Eigen::Index>(a.count / 3), 3);
  for (size_t i = 0; i < a.count; ++i) {
    uint32_t k;
    std::memcpy(&k, p + 4 * i, 4);
    out(static_cast<Eigen::Index>(i / 3), static_cast<Eigen::Index>(i % 3)) = static_cast<int>(k);
  }
  return out;
}

// With corner UVs the file holds the head's 7 vertices then its 2 seam duplicates (of vertices 1
// and 4): same position, normal (the unsplit mesh's) and deltas, their own UV (v flipped for glTF);
// the triangles use them where their corners' UVs differ.
TEST(RigExport, SeamDuplicatesCopyTheirVertexAndCarryTheirOwnUv) {
  const fs::path dir = scratch();
  const TriMesh mesh = readObjFromString(test::kUvSeamObj, "seam.obj");
  const RigExport rig = seamRig(mesh);
  writeRigGlb(dir / "rig.glb", rig);
  tinygltf::TinyGLTF loader;
  tinygltf::Model model;
  std::string err, warn;
  ASSERT_TRUE(loader.LoadBinaryFromFile(&model, &err, &warn, (dir / "rig.glb").string())) << err;
  const tinygltf::Primitive& prim = model.meshes.at(0).primitives.at(0);
  const std::vector<int> source{0, 1, 2, 3, 4, 5, 6, 1, 4};
  auto copied = [&](const MatX3& perVertex) {
    MatX3 out(9, 3);
    for (int i = 0; i < 9; ++i) out.row(i) = perVertex.row(source[static_cast<size_t>(i)]);
    return out;
  };
  const MatX3 positions = accessorData(model, prim.attributes.at("POSITION"));
  ASSERT_EQ(positions.rows(), 9);
  EXPECT_LT((positions - copied(rig.rest) * 0.01).cwiseAbs().maxCoeff(), 1e-7);
  const MatX3 normals = accessorData(model, prim.attributes.at("NORMAL"));
  EXPECT_LT((normals - copied(vertexNormals(mesh.V, mesh.F))).cwiseAbs().maxCoeff(), 1e-6);
  const MatX2 uv = accessorVec2(model, prim.attributes.at("TEXCOORD_0"));
  const SeamSplit split = splitUvSeams(mesh);
  ASSERT_EQ(uv.rows(), 9);
  for (int i = 0; i < 9; ++i) {
    EXPECT_FLOAT_EQ(uv(i, 0), static_cast<float>(split.uv(i, 0))) << i;
    EXPECT_FLOAT_EQ(uv(i, 1), static_cast<float>(1.0 - split.uv(i, 1))) << i;
  }
  EXPECT_EQ(uv(7, 0), 0.6f);  // vertex 1's second UV
  MatX3i F(5, 3);
  F << 0, 1, 4, 0, 4, 3, 7, 2, 8, 2, 5, 8, 2, 6, 5;
  EXPECT_EQ(triangleIndices(model, prim), F);
  ASSERT_EQ(prim.targets.size(), 2u);
  for (size_t k = 0; k < 2; ++k)
    EXPECT_LT((accessorData(model, prim.targets[k].at("POSITION")) - copied(rig.deltas[k]) * 0.01).cwiseAbs().maxCoeff(),
              1e-8)
        << k;
  fs::remove_all(dir);
}

// Our reader welds the duplicates back: the head's 7 vertices in order, its triangles, its deltas.
TEST(RigExport, ARigWithSeamDuplicatesReadsBackToTheHeadsVertices) {
  const fs::path dir = scratch();
  const TriMesh mesh = readObjFromString(test::kUvSeamObj, "seam.obj");
  const RigExport rig = seamRig(mesh);
  writeRigGlb(dir / "rig.glb", rig);
  const RigFile back = readRig((dir / "rig.glb").string());
  ASSERT_EQ(back.vertexCount(), mesh.vertexCount());
  EXPECT_EQ(back.weldedIndex, (std::vector<int>{0, 1, 2, 3, 4, 5, 6, 1, 4}));
  EXPECT_LT((back.base.V - mesh.V).cwiseAbs().maxCoeff(), 1e-5);
  EXPECT_EQ(back.base.F, mesh.F);
  EXPECT_EQ(back.names, rig.names);
  for (size_t k = 0; k < 2; ++k) EXPECT_LT((back.delta(rig.names[k]) - rig.deltas[k]).cwiseAbs().maxCoeff(), 1e-5) << k;
  fs::remove_all(dir);
}

TEST(RigExport, CornerUvsOfTheWrongSizeAreACheckError) {
  const fs::path dir = scratch();
  RigExport rig = seamRig(readObjFromString(test::kUvSeamObj, "seam.obj"));
  rig.cornerUV.conservativeResize(rig.cornerUV.rows() - 1, 2);
  EXPECT_THROW(writeRigGlb(dir / "rig.glb", rig), CheckError);
  EXPECT_FALSE(fs::exists(dir / "rig.glb"));
  fs::remove_all(dir);
}

TEST(RigExport, AFailedWriteLeavesNoFile) {
  const fs::path dir = scratch();
  EXPECT_THROW(writeRigGlb(dir / "missing" / "rig.glb", strip()), InputError);
  EXPECT_FALSE(fs::exists(dir / "missing"));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace myo
