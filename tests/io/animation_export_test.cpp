// PC2 and GLB animation exports: round trips, the GLB morph-target scheme, and atomic failures.
#include <gtest/gtest.h>
#include <tiny_gltf.h>
#include <unistd.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "myoshell/core/errors.h"
#include "myoshell/io/animation_export.h"
#include "support/scratch_folder.h"

namespace myo {
namespace {

namespace fs = std::filesystem;

// A unit square (two triangles) in z = 0 whose vertices wave along z, frame k at time k / fps.
AnimationFrames waveAnimation(int frameCount) {
  AnimationFrames a;
  a.name = "wave";
  a.fps = 24.0;
  a.rest.resize(4, 3);
  a.rest << 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0;
  a.triangles.resize(2, 3);
  a.triangles << 0, 1, 2, 0, 2, 3;
  for (int k = 0; k < frameCount; ++k) {
    MatX3 P = a.rest;
    for (int i = 0; i < 4; ++i) {
      P(i, 2) = 0.3 * std::sin(0.7 * k + i);
      P(i, 0) += 0.01 * k * i;
    }
    a.positions.push_back(P);
  }
  return a;
}

using AnimationExport = test::ScratchFolderTest;
TEST_F(AnimationExport, Pc2RoundTrip) {
  const AnimationFrames a = waveAnimation(7);
  const fs::path path = dir_ / "wave.pc2";
  writePc2(path, a);
  EXPECT_EQ(fs::file_size(path), 32u + 7u * 4u * 3u * 4u);
  // The header, byte by byte.
  std::ifstream in(path, std::ios::binary);
  char head[32];
  in.read(head, 32);
  EXPECT_EQ(std::string(head, 12), std::string("POINTCACHE2\0", 12));
  int32_t version, points, samples;
  float start, rate;
  std::memcpy(&version, head + 12, 4);
  std::memcpy(&points, head + 16, 4);
  std::memcpy(&start, head + 20, 4);
  std::memcpy(&rate, head + 24, 4);
  std::memcpy(&samples, head + 28, 4);
  EXPECT_EQ(version, 1);
  EXPECT_EQ(points, 4);
  EXPECT_EQ(start, 0.0f);
  EXPECT_EQ(rate, 1.0f);
  EXPECT_EQ(samples, 7);

  const PointCache pc = readPc2(path);
  EXPECT_EQ(pc.numPoints, 4);
  EXPECT_EQ(pc.startFrame, 0.0f);
  EXPECT_EQ(pc.sampleRate, 1.0f);
  ASSERT_EQ(pc.samples.size(), 7u);
  for (int k = 0; k < 7; ++k) EXPECT_LT((pc.samples[k] - a.positions[k]).cwiseAbs().maxCoeff(), 1e-6) << k;
  EXPECT_FALSE(fs::exists(path.string() + ".tmp"));
}

TEST_F(AnimationExport, Pc2ReaderRejectsOtherFiles) {
  const fs::path path = dir_ / "not.pc2";
  std::ofstream(path) << "hello, not a point cache at all, no signature here";
  try {
    readPc2(path);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("POINTCACHE2"), std::string::npos) << e.what();
  }
  writePc2(path, waveAnimation(2));
  fs::resize_file(path, fs::file_size(path) - 4);  // truncated
  EXPECT_THROW(readPc2(path), InputError);
}

// Reads accessor a of the model as floats.
std::vector<float> floats(const tinygltf::Model& m, int a) {
  const tinygltf::Accessor& acc = m.accessors[a];
  const tinygltf::BufferView& view = m.bufferViews[acc.bufferView];
  const int comps = acc.type == TINYGLTF_TYPE_VEC3 ? 3 : 1;
  EXPECT_EQ(acc.componentType, TINYGLTF_COMPONENT_TYPE_FLOAT);
  std::vector<float> out(acc.count * comps);
  std::memcpy(out.data(), m.buffers[view.buffer].data.data() + view.byteOffset + acc.byteOffset, out.size() * 4);
  return out;
}

TEST_F(AnimationExport, GlbHasOneHotMorphTargetsThatRebuildTheFrames) {
  const AnimationFrames a = waveAnimation(9);
  const fs::path path = dir_ / "wave.glb";
  writeGlb(path, a);
  EXPECT_FALSE(fs::exists(path.string() + ".tmp"));

  tinygltf::Model m;
  tinygltf::TinyGLTF loader;
  std::string err, warn;
  ASSERT_TRUE(loader.LoadBinaryFromFile(&m, &err, &warn, path.string())) << err;
  EXPECT_TRUE(err.empty()) << err;
  ASSERT_EQ(m.meshes.size(), 1u);
  ASSERT_EQ(m.meshes[0].primitives.size(), 1u);
  const tinygltf::Primitive& prim = m.meshes[0].primitives[0];
  EXPECT_EQ(prim.mode, TINYGLTF_MODE_TRIANGLES);
  const int pos = prim.attributes.at("POSITION");
  EXPECT_EQ(m.accessors[pos].count, 4u);
  EXPECT_EQ(m.accessors[prim.indices].count, 6u);
  ASSERT_EQ(prim.targets.size(), 9u);
  EXPECT_EQ(m.meshes[0].weights.size(), 9u);

  // Every POSITION accessor has min/max bounding its values.
  auto checkBounds = [&](int acc) {
    const auto& A = m.accessors[acc];
    ASSERT_EQ(A.minValues.size(), 3u);
    ASSERT_EQ(A.maxValues.size(), 3u);
    const std::vector<float> v = floats(m, acc);
    for (size_t i = 0; i < v.size(); ++i) {
      EXPECT_GE(v[i], A.minValues[i % 3]);
      EXPECT_LE(v[i], A.maxValues[i % 3]);
    }
  };
  checkBounds(pos);
  for (const auto& t : prim.targets) checkBounds(t.at("POSITION"));

  // The animation: one weights channel, keyframe k at k / fps with weight 1 on target k only.
  ASSERT_EQ(m.animations.size(), 1u);
  const tinygltf::Animation& anim = m.animations[0];
  ASSERT_EQ(anim.channels.size(), 1u);
  EXPECT_EQ(anim.channels[0].target_path, "weights");
  EXPECT_EQ(anim.channels[0].target_node, 0);
  EXPECT_EQ(m.nodes[0].mesh, 0);
  const tinygltf::AnimationSampler& s = anim.samplers[anim.channels[0].sampler];
  const std::vector<float> times = floats(m, s.input);
  const std::vector<float> weights = floats(m, s.output);
  ASSERT_EQ(times.size(), 9u);
  ASSERT_EQ(weights.size(), 81u);
  for (int k = 0; k < 9; ++k) {
    EXPECT_NEAR(times[k], k / 24.0, 1e-6) << k;
    for (int j = 0; j < 9; ++j) EXPECT_EQ(weights[9 * k + j], j == k ? 1.0f : 0.0f) << k << " " << j;
  }

  // rest + target k is frame k.
  const std::vector<float> rest = floats(m, pos);
  for (int k : {0, 3, 8}) {
    const std::vector<float> d = floats(m, prim.targets[k].at("POSITION"));
    for (int i = 0; i < 4; ++i)
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(rest[3 * i + c] + d[3 * i + c], a.positions[k](i, c), 1e-5) << k;
  }
}

TEST_F(AnimationExport, GlbStridesLongAnimations) {
  EXPECT_EQ(glbFrameIndices(5, 240), (std::vector<int>{0, 1, 2, 3, 4}));
  EXPECT_EQ(glbFrameIndices(7, 3), (std::vector<int>{0, 3, 6}));
  EXPECT_EQ(glbFrameIndices(8, 3), (std::vector<int>{0, 3, 6, 7}));  // the last frame is always kept
  const AnimationFrames a = waveAnimation(8);
  writeGlb(dir_ / "strided.glb", a, 3);
  tinygltf::Model m;
  tinygltf::TinyGLTF loader;
  std::string err, warn;
  ASSERT_TRUE(loader.LoadBinaryFromFile(&m, &err, &warn, (dir_ / "strided.glb").string())) << err;
  EXPECT_EQ(m.meshes[0].primitives[0].targets.size(), 4u);
  const std::vector<float> times = floats(m, m.animations[0].samplers[0].input);
  ASSERT_EQ(times.size(), 4u);
  EXPECT_NEAR(times[2], 6 / 24.0, 1e-6);
  EXPECT_NEAR(times[3], 7 / 24.0, 1e-6);
}

// TEXCOORD_0 only when the frames carry UVs: VEC2 floats, one per vertex, v flipped to glTF's
// top-left origin; UVs of the wrong row count are a CheckError and write nothing.
TEST_F(AnimationExport, GlbTexcoordsOnlyWhenTheHeadHasUvs) {
  AnimationFrames a = waveAnimation(3);
  auto load = [](const fs::path& path, tinygltf::Model& m) {
    tinygltf::TinyGLTF loader;
    std::string err, warn;
    ASSERT_TRUE(loader.LoadBinaryFromFile(&m, &err, &warn, path.string())) << err;
  };
  writeGlb(dir_ / "plain.glb", a);
  tinygltf::Model plain;
  load(dir_ / "plain.glb", plain);
  EXPECT_EQ(plain.meshes.at(0).primitives.at(0).attributes.count("TEXCOORD_0"), 0u);
  std::ifstream bytes(dir_ / "plain.glb", std::ios::binary);
  const std::string raw((std::istreambuf_iterator<char>(bytes)), std::istreambuf_iterator<char>());
  EXPECT_EQ(raw.find("TEXCOORD"), std::string::npos);

  a.uv.resize(4, 2);
  a.uv << 0.1, 0.2, 0.9, 0.25, 0.8, 0.95, 0.05, 0.7;
  writeGlb(dir_ / "uv.glb", a);
  tinygltf::Model m;
  load(dir_ / "uv.glb", m);
  const auto& attrs = m.meshes.at(0).primitives.at(0).attributes;
  ASSERT_EQ(attrs.count("TEXCOORD_0"), 1u);
  const tinygltf::Accessor& acc = m.accessors[attrs.at("TEXCOORD_0")];
  EXPECT_EQ(acc.type, TINYGLTF_TYPE_VEC2);
  EXPECT_EQ(acc.componentType, TINYGLTF_COMPONENT_TYPE_FLOAT);
  ASSERT_EQ(acc.count, 4u);
  const tinygltf::BufferView& view = m.bufferViews[acc.bufferView];
  std::vector<float> uv(8);
  std::memcpy(uv.data(), m.buffers[view.buffer].data.data() + view.byteOffset + acc.byteOffset, 32);
  for (int i = 0; i < 4; ++i) {
    EXPECT_FLOAT_EQ(uv[2 * i], static_cast<float>(a.uv(i, 0))) << i;
    EXPECT_FLOAT_EQ(uv[2 * i + 1], static_cast<float>(1.0 - a.uv(i, 1))) << i;
  }

  a.uv.conservativeResize(3, 2);
  EXPECT_THROW(writeGlb(dir_ / "bad.glb", a), CheckError);
  EXPECT_FALSE(fs::exists(dir_ / "bad.glb"));
}

TEST_F(AnimationExport, WritingIntoAMissingFolderFailsAndLeavesNoFile) {
  const AnimationFrames a = waveAnimation(3);
  const fs::path missing = dir_ / "no_such_folder";
  EXPECT_THROW(writeGlb(missing / "x.glb", a), InputError);
  EXPECT_THROW(writePc2(missing / "x.pc2", a), InputError);
  EXPECT_FALSE(fs::exists(missing));
  EXPECT_TRUE(fs::is_empty(dir_));
}

}  // namespace
}  // namespace myo
