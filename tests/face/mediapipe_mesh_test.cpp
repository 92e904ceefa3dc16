#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include "myoshell/core/errors.h"
#include "myoshell/head/mediapipe_mesh.h"

namespace myo {
namespace {

// Tiny protobuf writer for the tests.
void putVarint(std::vector<std::uint8_t>& b, std::uint64_t v) {
  while (v >= 0x80) {
    b.push_back(static_cast<std::uint8_t>(v | 0x80));
    v >>= 7;
  }
  b.push_back(static_cast<std::uint8_t>(v));
}
void putKey(std::vector<std::uint8_t>& b, int field, int wire) { putVarint(b, (field << 3) | wire); }
void putFloat(std::vector<std::uint8_t>& b, float f) {
  std::uint32_t u;
  std::memcpy(&u, &f, 4);
  for (int k = 0; k < 4; ++k) b.push_back(static_cast<std::uint8_t>(u >> (8 * k)));
}
void putBytes(std::vector<std::uint8_t>& b, int field, const std::vector<std::uint8_t>& payload) {
  putKey(b, field, 2);
  putVarint(b, payload.size());
  b.insert(b.end(), payload.begin(), payload.end());
}

// A quad (4 vertices, 2 triangles) as a Mesh3d, packed or unpacked.
std::vector<std::uint8_t> quadMesh3d(bool packed) {
  const std::vector<float> xyzuv = {0, 0, 0, 0, 0,  1, 0, 0, 1, 0,  1, 1, 0, 1, 1,  0, 1, 0.5f, 0, 1};
  const std::vector<std::uint32_t> idx = {0, 1, 2, 0, 2, 300};  // 300: patched below for a range test
  std::vector<std::uint8_t> b;
  putKey(b, 1, 0);
  putVarint(b, 0);  // vertex_type VERTEX_PT
  putKey(b, 2, 0);
  putVarint(b, 0);  // primitive_type TRIANGLE
  putKey(b, 7, 2);  // an unknown field, skipped
  putVarint(b, 2);
  b.push_back(0xde);
  b.push_back(0xad);
  if (packed) {
    std::vector<std::uint8_t> f, i;
    for (float x : xyzuv) putFloat(f, x);
    for (std::uint32_t x : idx) putVarint(i, x == 300 ? 3 : x);
    putBytes(b, 3, f);
    putBytes(b, 4, i);
  } else {
    for (float x : xyzuv) {
      putKey(b, 3, 5);
      putFloat(b, x);
    }
    for (std::uint32_t x : idx) {
      putKey(b, 4, 0);
      putVarint(b, x == 300 ? 3 : x);
    }
  }
  return b;
}

void expectQuad(const TriMesh& m) {
  ASSERT_EQ(m.vertexCount(), 4);
  ASSERT_EQ(m.triangleCount(), 2);
  EXPECT_EQ(m.V(3, 2), 0.5);
  EXPECT_EQ(m.UV(2, 0), 1.0);
  EXPECT_EQ(m.UV(3, 1), 1.0);
  EXPECT_EQ(m.F(1, 2), 3);
}

TEST(MediapipeMesh, ReadsUnpackedAndPackedRepeatedFields) {
  const auto unpacked = quadMesh3d(false), packed = quadMesh3d(true);
  EXPECT_LT(packed.size(), unpacked.size());
  expectQuad(parseMesh3d(unpacked.data(), unpacked.size()));
  expectQuad(parseMesh3d(packed.data(), packed.size()));
  // Wrapped as field 1 of a GeometryPipelineMetadata, after another field.
  for (const auto& inner : {unpacked, packed}) {
    std::vector<std::uint8_t> outer;
    putKey(outer, 3, 0);
    putVarint(outer, 1);
    putBytes(outer, 1, inner);
    expectQuad(parseGeometryPipelineMetadata(outer.data(), outer.size()));
  }
}

TEST(MediapipeMesh, RejectsMalformedMessagesWithByteOffsets) {
  auto b = quadMesh3d(false);
  b.resize(b.size() - 1);  // truncated varint of the last index
  try {
    parseMesh3d(b.data(), b.size(), "quad.pb");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("quad.pb"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("truncated varint"), std::string::npos) << e.what();
  }
  std::vector<std::uint8_t> bad;
  putKey(bad, 4, 0);
  putVarint(bad, 0);
  putKey(bad, 4, 0);
  putVarint(bad, 1);
  putKey(bad, 4, 0);
  putVarint(bad, 2);
  try {
    parseMesh3d(bad.data(), bad.size(), "noverts.pb");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("out of range [0, 0)"), std::string::npos) << e.what();
  }
  std::vector<std::uint8_t> none;
  putKey(none, 3, 0);
  putVarint(none, 1);
  EXPECT_THROW(parseGeometryPipelineMetadata(none.data(), none.size()), InputError);
}

}  // namespace
}  // namespace myo
