// PC2 and GLB animation exports: round trips, the GLB's exact frames (base + weighted morph
// targets), metres, seams and frame rate, and atomic failures.
#include <fmt/core.h>
#include <gtest/gtest.h>
#include <tiny_gltf.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "myoshell/core/errors.h"
#include "myoshell/head/head_checks.h"
#include "myoshell/io/animation_export.h"
#include "myoshell/io/animation_exporter.h"
#include "myoshell/io/morph_compression.h"
#include "myoshell/mesh/obj_reader.h"
#include "support/grid_animation.h"
#include "support/scratch_folder.h"
#include "support/uv_seam_mesh.h"

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

// The GLB read back with tinygltf, and every frame as a player computes it: base + Σ_k s_fk T_k at
// key f, in the file's unit (metres).
struct PlayedGlb {
  tinygltf::Model model;
  std::vector<float> times;
  std::vector<MatX3> frames;  // metres
  std::vector<float> weights;  // F × k, key-major
  int targets = 0;
};

PlayedGlb play(const fs::path& path) {
  PlayedGlb g;
  tinygltf::TinyGLTF loader;
  std::string err, warn;
  EXPECT_TRUE(loader.LoadBinaryFromFile(&g.model, &err, &warn, path.string())) << err;
  const tinygltf::Model& m = g.model;
  const tinygltf::Primitive& prim = m.meshes.at(0).primitives.at(0);
  g.targets = static_cast<int>(prim.targets.size());
  const std::vector<float> base = floats(m, prim.attributes.at("POSITION"));
  std::vector<std::vector<float>> targets;
  for (const auto& t : prim.targets) targets.push_back(floats(m, t.at("POSITION")));
  const tinygltf::AnimationSampler& s = m.animations.at(0).samplers.at(0);
  EXPECT_EQ(s.interpolation, "LINEAR");
  g.times = floats(m, s.input);
  g.weights = floats(m, s.output);
  EXPECT_EQ(g.weights.size(), g.times.size() * targets.size());
  const size_t n = base.size() / 3;
  for (size_t f = 0; f < g.times.size(); ++f) {
    MatX3 P(n, 3);
    for (size_t i = 0; i < 3 * n; ++i) {
      double x = base[i];
      for (size_t k = 0; k < targets.size(); ++k) x += double(g.weights[f * targets.size() + k]) * targets[k][i];
      P.data()[i] = x;
    }
    g.frames.push_back(P);
  }
  return g;
}

// Largest vertex distance between the played frames (m) and the frames (cm) over the first n vertices, mm.
double maxErrorMm(const PlayedGlb& g, const std::vector<MatX3>& frames) {
  double worst = 0;
  for (size_t f = 0; f < frames.size(); ++f)
    worst = std::max(worst, (g.frames[f].topRows(frames[f].rows()) - 0.01 * frames[f]).rowwise().norm().maxCoeff());
  return 1e3 * worst;
}

// A 12×10 grid (120 vertices) moved by three fixed fields with their own time curves: 120 frames
// of rank 3.
AnimationFrames lowRankAnimation(int frameCount) {
  const int nx = 12, ny = 10;
  std::vector<MatX3> fields(3, MatX3(nx * ny, 3));
  for (int v = 0; v < nx * ny; ++v) {
    fields[0].row(v) << 0, 0, std::sin(0.3 * v);
    fields[1].row(v) << 0.2 * std::cos(0.1 * v), 0, 0;
    fields[2].row(v) << 0, 0.1 * (v % 7), 0.05 * (v % 5);
  }
  const double fps = 30.0;
  return test::gridAnimation(
      "lowrank", fps, nx, ny, frameCount, [](int i, int j) { return Vec3(0.5 * i, 0.5 * j, 0.05 * i * j); },
      [&](int f, MatX3& P) {
        const double time = f / fps;
        P += std::sin(3 * time) * fields[0] + (1 - std::cos(2 * time)) * fields[1] + time * time * fields[2];
      });
}

// Every frame, exact: a key at every frame, f / fps; base + Σ s T within 0.05 mm (the tolerance) of
// every frame; three targets for the rank-3 animation; weights in [0, 1]; no node transform.
TEST_F(AnimationExport, GlbPlaysEveryFrameWithinTheTolerance) {
  const AnimationFrames a = lowRankAnimation(120);
  const fs::path path = dir_ / "lowrank.glb";
  const GlbReport report = writeGlb(path, a);
  EXPECT_FALSE(fs::exists(path.string() + ".tmp"));
  EXPECT_EQ(report.targets, 3);
  EXPECT_TRUE(report.withinTolerance);
  EXPECT_LE(report.maxErrorCm, 0.005);
  EXPECT_EQ(report.frames, 120);
  EXPECT_EQ(report.fps, 30.0);
  EXPECT_EQ(report.vertices, 120);

  const PlayedGlb g = play(path);
  EXPECT_EQ(g.targets, 3);
  ASSERT_EQ(g.times.size(), 120u);
  for (int f = 0; f < 120; ++f) EXPECT_NEAR(g.times[f], f / 30.0, 1e-6) << f;
  for (const float w : g.weights) {
    EXPECT_GE(w, 0.0f);
    EXPECT_LE(w, 1.0f);
  }
  const double error = maxErrorMm(g, a.positions);
  EXPECT_LT(error, 0.05);
  EXPECT_NEAR(error, 10.0 * report.maxErrorCm, 1e-6);  // the report is the file's own error
  const tinygltf::Model& m = g.model;
  EXPECT_TRUE(m.nodes.at(0).scale.empty());  // metres in the accessors, no node scale
  EXPECT_EQ(m.meshes[0].weights.size(), 3u);
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
  const tinygltf::Primitive& prim = m.meshes[0].primitives[0];
  checkBounds(prim.attributes.at("POSITION"));
  for (const auto& t : prim.targets) checkBounds(t.at("POSITION"));
  ASSERT_EQ(m.animations.size(), 1u);
  EXPECT_EQ(m.animations[0].channels.at(0).target_path, "weights");
}

// The frame rate and frame count, where glTF can hold them: the animation's and the scene's extras.
TEST_F(AnimationExport, GlbCarriesTheFrameRateInExtras) {
  const AnimationFrames a = waveAnimation(9);  // 24 fps
  writeGlb(dir_ / "wave.glb", a);
  const PlayedGlb g = play(dir_ / "wave.glb");
  for (const tinygltf::Value* extras : {&g.model.animations.at(0).extras, &g.model.scenes.at(0).extras}) {
    ASSERT_TRUE(extras->IsObject());
    EXPECT_EQ(extras->Get("fps").GetNumberAsDouble(), 24.0);
    EXPECT_EQ(extras->Get("frames").GetNumberAsInt(), 9);
  }
  EXPECT_LT(maxErrorMm(g, a.positions), 0.05);  // full rank (9 frames, 9 targets at most): still exact
  EXPECT_LE(g.targets, 9);
}

// Metres: a still animation is the rest × 0.01, with one target that no frame weighs.
TEST_F(AnimationExport, GlbIsInMetres) {
  AnimationFrames a = waveAnimation(1);
  a.positions = {a.rest, a.rest};
  const GlbReport report = writeGlb(dir_ / "still.glb", a);
  EXPECT_EQ(report.targets, 1);
  EXPECT_LT(report.maxErrorCm, 1e-6);  // float32 round-off of the positions in metres
  const PlayedGlb g = play(dir_ / "still.glb");
  const std::vector<float> base = floats(g.model, g.model.meshes[0].primitives[0].attributes.at("POSITION"));
  for (int i = 0; i < 4; ++i)
    for (int c = 0; c < 3; ++c) EXPECT_FLOAT_EQ(base[3 * i + c], static_cast<float>(0.01 * a.rest(i, c))) << i;
  for (const float w : g.weights) EXPECT_EQ(w, 0.0f);
}

// More frames than the exact Gram path takes (io/morph_compression.h: the randomized range finder):
// still every frame within the tolerance, three targets.
TEST_F(AnimationExport, LongTakesAreExactToo) {
  const AnimationFrames a = lowRankAnimation(kExactRangeFrames + 100);
  const GlbReport report = writeGlb(dir_ / "long.glb", a);
  EXPECT_EQ(report.targets, 3);
  EXPECT_LT(maxErrorMm(play(dir_ / "long.glb"), a.positions), 0.05);
}

// The cap reached before the tolerance: the GLB keeps the cap's targets and says how far off it is.
TEST_F(AnimationExport, TheTargetCapIsReported) {
  const AnimationFrames a = lowRankAnimation(60);
  GlbOptions options;
  options.maxTargets = 2;
  const GlbReport report = writeGlb(dir_ / "capped.glb", a, options);
  EXPECT_EQ(report.targets, 2);
  EXPECT_FALSE(report.withinTolerance);
  const double error = maxErrorMm(play(dir_ / "capped.glb"), a.positions);
  EXPECT_GT(error, 0.05);
  EXPECT_NEAR(error, 10.0 * report.maxErrorCm, 1e-6);
}

// A head with UV seams (tests/support/uv_seam_mesh.h): the head's 7 vertices in order, then the two
// seam duplicates (of vertices 1 and 4), each at its original's place in every frame; each corner
// its OBJ's texture coordinate.
TEST_F(AnimationExport, GlbSplitsUvSeamsAsRigsDo) {
  const TriMesh head = readObjFromString(test::kUvSeamObj, "seam.obj");
  AnimationFrames a;
  a.name = "seam";
  a.rest = head.V;
  a.triangles = head.F;
  a.uv = head.UV;
  a.cornerUV = head.cornerUV;
  for (int f = 0; f < 5; ++f) {
    MatX3 P = head.V;
    for (int v = 0; v < P.rows(); ++v) P.row(v) += Vec3(0.1 * v * std::sin(f), -0.05 * v * f, 0.2 * ((v + f) % 3)).transpose();
    a.positions.push_back(P);
  }
  const GlbReport report = writeGlb(dir_ / "seam.glb", a);
  EXPECT_EQ(report.vertices, 9);
  const PlayedGlb g = play(dir_ / "seam.glb");
  const int source[9] = {0, 1, 2, 3, 4, 5, 6, 1, 4};
  for (int f = 0; f < 5; ++f) {
    ASSERT_EQ(g.frames[f].rows(), 9);
    for (int i = 0; i < 9; ++i)
      EXPECT_LT((g.frames[f].row(i) - 0.01 * a.positions[f].row(source[i])).norm(), 5e-5) << f << " " << i;
    EXPECT_LT((g.frames[f].row(7) - g.frames[f].row(1)).norm(), 1e-9) << f;  // a duplicate moves as its original
    EXPECT_LT((g.frames[f].row(8) - g.frames[f].row(4)).norm(), 1e-9) << f;
  }
  const tinygltf::Primitive& prim = g.model.meshes[0].primitives[0];
  const std::vector<float> uv = [&] {
    const tinygltf::Accessor& acc = g.model.accessors[prim.attributes.at("TEXCOORD_0")];
    const tinygltf::BufferView& view = g.model.bufferViews[acc.bufferView];
    std::vector<float> out(2 * acc.count);
    std::memcpy(out.data(), g.model.buffers[0].data.data() + view.byteOffset + acc.byteOffset, out.size() * 4);
    return out;
  }();
  const tinygltf::Accessor& idx = g.model.accessors[prim.indices];
  const tinygltf::BufferView& iv = g.model.bufferViews[idx.bufferView];
  std::vector<uint32_t> indices(idx.count);
  std::memcpy(indices.data(), g.model.buffers[0].data.data() + iv.byteOffset + idx.byteOffset, idx.count * 4);
  ASSERT_EQ(indices.size(), static_cast<size_t>(3 * head.F.rows()));
  for (size_t c = 0; c < indices.size(); ++c) {
    EXPECT_NEAR(uv[2 * indices[c]], head.cornerUV(c, 0), 1e-6) << c;
    EXPECT_NEAR(uv[2 * indices[c] + 1], 1.0 - head.cornerUV(c, 1), 1e-6) << c;
  }
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

// The exporter writes the OBJ frames and the PC2 in the head's own unit (cm positions × 0.01 for a
// head in metres, × 10 in mm), the GLB in metres whatever the unit.
TEST_F(AnimationExport, TheExporterWritesObjAndPc2InTheHeadsUnit) {
  const AnimationFrames a = waveAnimation(3);
  TriMesh mesh;
  mesh.V = a.rest;
  mesh.F = a.triangles;
  ExportFormats formats;
  formats.obj = formats.pc2 = formats.glb = true;
  for (const auto& [unit, perCm] : {std::pair{LengthUnit::cm, 1.0}, std::pair{LengthUnit::m, 0.01}, std::pair{LengthUnit::mm, 10.0}}) {
    const fs::path out = dir_ / lengthUnitName(unit);
    AnimationExporter exporter(out, formats, "wave", mesh, a.fps, 3, unit);
    for (int f = 0; f < 3; ++f) exporter.addFrame(f, a.positions[f]);
    exporter.finish();
    const PointCache pc = readPc2(out / "wave.pc2");
    for (int f = 0; f < 3; ++f) {
      EXPECT_LT((pc.samples[f] - perCm * a.positions[f]).cwiseAbs().maxCoeff(), 1e-6 * perCm) << f;
      const TriMesh obj = readObj((out / "obj" / fmt::format("wave_{:04d}.obj", f)).string());
      EXPECT_LT((obj.V - perCm * a.positions[f]).cwiseAbs().maxCoeff(), 1e-12 * perCm) << f;
    }
    ASSERT_NE(exporter.glbReport(), nullptr);
    EXPECT_LT(maxErrorMm(play(out / "wave.glb"), a.positions), 0.05);  // metres
  }
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
