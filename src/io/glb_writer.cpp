// GLB exports: an animation (every frame as base + weighted morph targets, scheme in
// io/animation_export.h) and a rig (io/rig_export.h), both through one mesh writer.
#include <tiny_gltf.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <sstream>

#include <fmt/core.h>

#include "export_file.h"
#include "myoshell/core/atomic_file.h"
#include "myoshell/core/check.h"
#include "myoshell/core/errors.h"
#include "myoshell/io/animation_export.h"
#include "myoshell/io/morph_compression.h"
#include "myoshell/io/rig_export.h"
#include "myoshell/mesh/geometry.h"
#include "myoshell/mesh/uv_seams.h"

namespace myo {
namespace {

constexpr int kArrayBuffer = 34962;         // glTF bufferView.target ARRAY_BUFFER
constexpr int kElementArrayBuffer = 34963;  // glTF bufferView.target ELEMENT_ARRAY_BUFFER

// The single binary buffer and its views/accessors, appended as the model is assembled.
class BufferBuilder {
 public:
  explicit BufferBuilder(tinygltf::Model& model) : model_(model) { model_.buffers.emplace_back(); }

  // Appends raw bytes as a new buffer view (4-byte aligned); returns the view index.
  int addView(const void* data, size_t bytes, int target) {
    auto& buf = model_.buffers[0].data;
    buf.resize((buf.size() + 3) & ~size_t(3), 0);
    tinygltf::BufferView view;
    view.buffer = 0;
    view.byteOffset = buf.size();
    view.byteLength = bytes;
    view.target = target;
    const auto* p = static_cast<const unsigned char*>(data);
    buf.insert(buf.end(), p, p + bytes);
    model_.bufferViews.push_back(view);
    return static_cast<int>(model_.bufferViews.size()) - 1;
  }

  int addAccessor(int view, size_t byteOffset, int componentType, size_t count, int type,
                  std::vector<double> minValues = {}, std::vector<double> maxValues = {}) {
    tinygltf::Accessor a;
    a.bufferView = view;
    a.byteOffset = byteOffset;
    a.componentType = componentType;
    a.count = count;
    a.type = type;
    a.minValues = std::move(minValues);
    a.maxValues = std::move(maxValues);
    model_.accessors.push_back(a);
    return static_cast<int>(model_.accessors.size()) - 1;
  }

 private:
  tinygltf::Model& model_;
};

// Per-component min and max of n×3 float data (as stored, so they match the accessor exactly).
void bounds(const std::vector<float>& xyz, std::vector<double>& lo, std::vector<double>& hi) {
  lo.assign(3, std::numeric_limits<double>::infinity());
  hi.assign(3, -std::numeric_limits<double>::infinity());
  for (size_t i = 0; i < xyz.size(); ++i) {
    lo[i % 3] = std::min<double>(lo[i % 3], xyz[i]);
    hi[i % 3] = std::max<double>(hi[i % 3], xyz[i]);
  }
}

std::vector<float> toFloat(const MatX3& M) {
  std::vector<float> out(static_cast<size_t>(M.size()));
  for (Eigen::Index i = 0; i < M.rows(); ++i)
    for (int c = 0; c < 3; ++c) out[3 * i + c] = static_cast<float>(M(i, c));
  return out;
}

}  // namespace

namespace {

// The one mesh with its morph targets, in a single primitive: POSITION, NORMAL, TEXCOORD_0 (when
// there are UVs), UNSIGNED_INT indices, one POSITION target per delta named in
// meshes[0].extras.targetNames, the mesh's default weights, and the node (no transform) that
// places it. Positions and deltas are in metres as given. The normals are given (not computed from
// these triangles) so that a mesh split along its UV seams can carry the normals of the unsplit
// mesh: computed on the split one, a seam would show.
void addMorphMesh(tinygltf::Model& model, BufferBuilder& bb, const std::string& name, const MatX3& rest,
                  const MatX3i& triangles, const MatX2& uvs, const MatX3& normalsPerVertex,
                  const std::vector<MatX3>& deltas, const std::vector<std::string>& names,
                  const std::vector<double>& defaultWeights) {
  const auto n = static_cast<size_t>(rest.rows());
  const size_t T = deltas.size();

  // Indices.
  std::vector<uint32_t> indices(static_cast<size_t>(triangles.size()));
  for (Eigen::Index t = 0; t < triangles.rows(); ++t)
    for (int c = 0; c < 3; ++c) indices[3 * t + c] = static_cast<uint32_t>(triangles(t, c));
  const int indexAccessor =
      bb.addAccessor(bb.addView(indices.data(), indices.size() * 4, kElementArrayBuffer), 0,
                     TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, indices.size(), TINYGLTF_TYPE_SCALAR);

  // Rest positions and normals.
  std::vector<double> lo, hi;
  const std::vector<float> restFloats = toFloat(rest);
  bounds(restFloats, lo, hi);
  const int positionAccessor = bb.addAccessor(bb.addView(restFloats.data(), restFloats.size() * 4, kArrayBuffer), 0,
                                              TINYGLTF_COMPONENT_TYPE_FLOAT, n, TINYGLTF_TYPE_VEC3, lo, hi);
  MYO_CHECK_EQ(static_cast<size_t>(normalsPerVertex.rows()), n);
  const std::vector<float> normals = toFloat(normalsPerVertex);
  const int normalAccessor = bb.addAccessor(bb.addView(normals.data(), normals.size() * 4, kArrayBuffer), 0,
                                            TINYGLTF_COMPONENT_TYPE_FLOAT, n, TINYGLTF_TYPE_VEC3);

  // Texture coordinates, when the head has them: glTF's v runs down the image, OBJ's up.
  int texcoordAccessor = -1;
  if (uvs.rows() > 0) {
    std::vector<float> uv(2 * n);
    for (size_t i = 0; i < n; ++i) {
      uv[2 * i] = static_cast<float>(uvs(static_cast<Eigen::Index>(i), 0));
      uv[2 * i + 1] = static_cast<float>(1.0 - uvs(static_cast<Eigen::Index>(i), 1));
    }
    texcoordAccessor = bb.addAccessor(bb.addView(uv.data(), uv.size() * 4, kArrayBuffer), 0,
                                      TINYGLTF_COMPONENT_TYPE_FLOAT, n, TINYGLTF_TYPE_VEC2);
  }

  // Morph targets, all in one view.
  std::vector<float> targets;
  targets.reserve(T * 3 * n);
  std::vector<std::pair<std::vector<double>, std::vector<double>>> targetBounds;
  for (const MatX3& delta : deltas) {
    std::vector<float> d = toFloat(delta);
    bounds(d, lo, hi);
    targetBounds.emplace_back(lo, hi);
    targets.insert(targets.end(), d.begin(), d.end());
  }
  const int targetView = bb.addView(targets.data(), targets.size() * 4, kArrayBuffer);
  model.bufferViews[targetView].byteStride = 12;  // required: several vertex accessors share the view
  tinygltf::Primitive prim;
  prim.attributes["POSITION"] = positionAccessor;
  prim.attributes["NORMAL"] = normalAccessor;
  if (texcoordAccessor >= 0) prim.attributes["TEXCOORD_0"] = texcoordAccessor;
  prim.indices = indexAccessor;
  prim.mode = TINYGLTF_MODE_TRIANGLES;
  tinygltf::Value::Array targetNames;
  for (size_t k = 0; k < T; ++k) {
    const int a = bb.addAccessor(targetView, k * 3 * n * 4, TINYGLTF_COMPONENT_TYPE_FLOAT, n, TINYGLTF_TYPE_VEC3,
                                 targetBounds[k].first, targetBounds[k].second);
    prim.targets.push_back({{"POSITION", a}});
    targetNames.emplace_back(names[k]);
  }

  tinygltf::Mesh mesh;
  mesh.name = name;
  mesh.primitives.push_back(prim);
  MYO_CHECK_EQ(defaultWeights.size(), T);
  mesh.weights = defaultWeights;
  tinygltf::Value::Object extras;
  extras["targetNames"] = tinygltf::Value(std::move(targetNames));
  mesh.extras = tinygltf::Value(std::move(extras));
  model.meshes.push_back(mesh);

  tinygltf::Node node;
  node.name = name;
  node.mesh = 0;
  model.nodes.push_back(node);
  tinygltf::Scene scene;
  scene.name = name;
  scene.nodes = {0};
  model.scenes.push_back(scene);
  model.defaultScene = 0;
}

// The mesh as addMorphMesh writes it, split along its UV seams when cornerUV has rows (rigs and
// animations alike: mesh/uv_seams.h): the seam duplicates follow the head's own vertices and carry
// their originals' positions, normals of the unsplit mesh and deltas. `rest` and `deltas` in metres.
// Returns the vertex count written.
int addSeamSplitMesh(tinygltf::Model& model, BufferBuilder& bb, const std::string& name, const MatX3& rest,
                     const MatX3i& triangles, const MatX2& uv, const MatX2& cornerUV, const MatX3& normals,
                     const std::vector<MatX3>& deltas, const std::vector<std::string>& names,
                     const std::vector<double>& defaultWeights) {
  if (cornerUV.rows() == 0) {
    addMorphMesh(model, bb, name, rest, triangles, uv, normals, deltas, names, defaultWeights);
    return static_cast<int>(rest.rows());
  }
  const SeamSplit split = splitUvSeams(static_cast<int>(rest.rows()), triangles, uv, cornerUV);
  std::vector<MatX3> splitDeltas;
  splitDeltas.reserve(deltas.size());
  for (const MatX3& d : deltas) splitDeltas.push_back(expandToSplit(split, d));
  addMorphMesh(model, bb, name, expandToSplit(split, rest), split.triangles, split.uv, expandToSplit(split, normals),
               splitDeltas, names, defaultWeights);
  return split.vertexCount();
}

void checkMesh(const MatX3& rest, const MatX3i& triangles, const MatX2& uv, const MatX2& cornerUV) {
  const auto n = static_cast<size_t>(rest.rows());
  MYO_CHECK_GT(triangles.rows(), 0);
  MYO_CHECK(triangles.minCoeff() >= 0 && static_cast<size_t>(triangles.maxCoeff()) < n,
            "triangle indices must lie in [0, " << n << ")");
  MYO_CHECK(uv.rows() == 0 || static_cast<size_t>(uv.rows()) == n,
            "uv must have 0 or " << n << " rows (one per vertex), got " << uv.rows());
  MYO_CHECK(cornerUV.rows() == 0 || cornerUV.rows() == 3 * triangles.rows(),
            "cornerUV must have 0 or " << 3 * triangles.rows() << " rows (3 per triangle), got " << cornerUV.rows());
}

void writeModel(const std::filesystem::path& path, tinygltf::Model& model) {
  std::ostringstream out;
  tinygltf::TinyGLTF gltf;
  if (!gltf.WriteGltfSceneToStream(&model, out, false, true))
    throw InputError("cannot serialise the GLB", path.string());
  writeFileAtomically(path.string(), out.str());
}

}  // namespace

GlbOptions glbOptionsForTolerance(double toleranceMm, const std::string& what) {
  if (!(std::isfinite(toleranceMm) && toleranceMm > 0.0))
    throw InputError(fmt::format("{}: must be a number > 0 (mm), got {}", what, toleranceMm));
  GlbOptions options;
  options.toleranceMm = toleranceMm;
  return options;
}

GlbReport writeGlb(const std::filesystem::path& path, const AnimationFrames& frames, const GlbOptions& options) {
  MYO_CHECK(std::isfinite(options.toleranceMm) && options.toleranceMm > 0.0,
            "the GLB's tolerance must be finite and > 0 mm, got " << options.toleranceMm);
  detail::checkFrames(frames);
  MYO_CHECK(frames.fps > 0.0 && std::isfinite(frames.fps), "fps must be finite and > 0, got " << frames.fps);
  checkMesh(frames.rest, frames.triangles, frames.uv, frames.cornerUV);
  const auto F = static_cast<int>(frames.positions.size());

  // Every frame, exact to the tolerance, as base + Σ s_k T_k, in metres (glTF's unit).
  const MorphAnimation morph =
      compressToMorphTargets(frames.rest, frames.positions, options.toleranceMm / 10.0, options.maxTargets, 0.01);
  const auto T = static_cast<int>(morph.targets.size());
  std::vector<std::string> names;
  for (int k = 0; k < T; ++k) names.push_back(fmt::format("mode_{:02d}", k));
  std::vector<double> firstFrame(T);  // the mesh's default weights, as stored
  for (int k = 0; k < T; ++k) firstFrame[k] = static_cast<float>(morph.weights(0, k));

  tinygltf::Model model;
  model.asset.version = "2.0";
  model.asset.generator = "Myoshell";
  BufferBuilder bb(model);
  GlbReport report;
  report.vertices = addSeamSplitMesh(model, bb, frames.name, morph.base, frames.triangles, frames.uv, frames.cornerUV,
                                     vertexNormals(frames.rest, frames.triangles), morph.targets, names, firstFrame);

  // Animation: a key at every frame, f / fps, with that frame's T weights.
  std::vector<float> times(F), weights(static_cast<size_t>(F) * T);
  for (int f = 0; f < F; ++f) {
    times[f] = static_cast<float>(f / frames.fps);
    for (int k = 0; k < T; ++k) weights[static_cast<size_t>(f) * T + k] = static_cast<float>(morph.weights(f, k));
  }
  const int timeAccessor = bb.addAccessor(bb.addView(times.data(), times.size() * 4, 0), 0, TINYGLTF_COMPONENT_TYPE_FLOAT,
                                          times.size(), TINYGLTF_TYPE_SCALAR, {times.front()}, {times.back()});
  const int weightAccessor = bb.addAccessor(bb.addView(weights.data(), weights.size() * 4, 0), 0,
                                            TINYGLTF_COMPONENT_TYPE_FLOAT, weights.size(), TINYGLTF_TYPE_SCALAR);
  tinygltf::Animation anim;
  anim.name = frames.name;
  tinygltf::AnimationSampler sampler;
  sampler.input = timeAccessor;
  sampler.output = weightAccessor;
  sampler.interpolation = "LINEAR";
  anim.samplers.push_back(sampler);
  tinygltf::AnimationChannel channel;
  channel.sampler = 0;
  channel.target_node = 0;
  channel.target_path = "weights";
  anim.channels.push_back(channel);
  // glTF has no frame rate: players convert the keys' seconds at their own (docs/exports.md).
  tinygltf::Value::Object rate;
  rate["fps"] = tinygltf::Value(frames.fps);
  rate["frames"] = tinygltf::Value(F);
  anim.extras = tinygltf::Value(rate);
  model.scenes[0].extras = tinygltf::Value(rate);
  model.animations.push_back(anim);

  writeModel(path, model);
  report.targets = T;
  report.toleranceMm = options.toleranceMm;
  report.maxErrorCm = morph.maxError;
  report.withinTolerance = morph.withinTolerance;
  report.frames = F;
  report.fps = frames.fps;
  return report;
}

void writeRigGlb(const std::filesystem::path& path, const RigExport& rig) {
  checkMesh(rig.rest, rig.triangles, rig.uv, rig.cornerUV);
  MYO_CHECK_EQ(rig.names.size(), rig.deltas.size());
  for (const MatX3& d : rig.deltas)
    MYO_CHECK(d.rows() == rig.rest.rows() && d.allFinite(), "every delta must be n×3 and finite");
  tinygltf::Model model;
  model.asset.version = "2.0";
  model.asset.generator = "Myoshell";
  BufferBuilder bb(model);
  std::vector<MatX3> deltas;  // cm → m
  deltas.reserve(rig.deltas.size());
  for (const MatX3& d : rig.deltas) deltas.push_back(d * 0.01);
  // Normals of the unsplit mesh, so that both sides of a UV seam shade alike.
  addSeamSplitMesh(model, bb, rig.name, rig.rest * 0.01, rig.triangles, rig.uv, rig.cornerUV,
                   vertexNormals(rig.rest, rig.triangles), deltas, rig.names, std::vector<double>(deltas.size(), 0.0));
  writeModel(path, model);
}

}  // namespace myo
