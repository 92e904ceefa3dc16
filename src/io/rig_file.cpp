// Reads glTF 2.0 blendshape rigs (include/myoshell/io/rig_file.h; docs/rigs.md). A hand reader on
// nlohmann_json rather than tinygltf: every accessor is decoded here anyway (sparse accessors, seam
// welding), and each fault must name its JSON pointer, which tinygltf's loader does not report.
#include "myoshell/io/rig_file.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>

#include "myoshell/core/close_names.h"
#include "myoshell/core/errors.h"
#include "myoshell/core/whole_file.h"

namespace myo {
namespace {

using json = nlohmann::json;
using Affine = Eigen::Matrix4d;

constexpr double kMetresToCm = 100.0;  // glTF 2.0 §3.5.1: units for linear distances are metres
constexpr std::uint32_t kGlbMagic = 0x46546C67;  // "glTF"
constexpr std::uint32_t kChunkJson = 0x4E4F534A;
constexpr std::uint32_t kChunkBin = 0x004E4942;

std::uint32_t readU32(std::string_view b, std::size_t at) {
  std::uint32_t v = 0;
  std::memcpy(&v, b.data() + at, 4);  // GLB is little-endian, as is every platform we build on
  return v;
}

class Reader {
 public:
  Reader(std::string_view bytes, std::string path) : bytes_(bytes), path_(std::move(path)) {}

  RigFile read();

 private:
  [[noreturn]] void fail(const std::string& pointer, const std::string& fault) const {
    throw InputError((pointer.empty() ? "" : pointer + ": ") + fault, path_);
  }
  const json& member(const json& obj, const std::string& key, const std::string& pointer) const;
  const json& element(const json& array, std::size_t i, const std::string& pointer) const;
  std::uint64_t index(const json& v, const std::string& pointer, std::uint64_t bound) const;
  std::uint64_t optIndex(const json& obj, const std::string& key, const std::string& pointer, std::uint64_t def,
                         std::uint64_t bound) const;
  double number(const json& v, const std::string& pointer) const;

  void parseContainer();
  const std::string& buffer(std::size_t i);
  // One accessor's elements as doubles (count × components), with its sparse substitution applied.
  std::vector<double> accessor(std::uint64_t i, bool positions);
  Affine nodeMatrix(std::size_t i) const;
  Affine worldMatrix(std::size_t node) const;

  std::string_view bytes_;
  std::string path_;
  json doc_;
  std::string glbBin_;
  bool hasGlbBin_ = false;
  std::map<std::size_t, std::string> buffers_;
};

const json& Reader::member(const json& obj, const std::string& key, const std::string& pointer) const {
  if (!obj.is_object()) fail(pointer, "expected an object");
  auto it = obj.find(key);
  if (it == obj.end()) fail(pointer + "/" + key, "missing");
  return *it;
}

const json& Reader::element(const json& array, std::size_t i, const std::string& pointer) const {
  if (!array.is_array()) fail(pointer, "expected an array");
  if (i >= array.size())
    fail(pointer + "/" + std::to_string(i), "out of range (the array has " + std::to_string(array.size()) + ")");
  return array[i];
}

std::uint64_t Reader::index(const json& v, const std::string& pointer, std::uint64_t bound) const {
  if (!v.is_number_integer() || (v.is_number_integer() && !v.is_number_unsigned() && v.get<std::int64_t>() < 0))
    fail(pointer, "expected a non-negative integer");
  const std::uint64_t x = v.get<std::uint64_t>();
  if (x >= bound) fail(pointer, std::to_string(x) + " out of range (limit " + std::to_string(bound) + ")");
  return x;
}

std::uint64_t Reader::optIndex(const json& obj, const std::string& key, const std::string& pointer,
                               std::uint64_t def, std::uint64_t bound) const {
  auto it = obj.find(key);
  if (it == obj.end()) return def;
  return index(*it, pointer + "/" + key, bound);
}

double Reader::number(const json& v, const std::string& pointer) const {
  if (!v.is_number()) fail(pointer, "expected a number");
  const double x = v.get<double>();
  if (!std::isfinite(x)) fail(pointer, "non-finite number");
  return x;
}

void Reader::parseContainer() {
  std::string_view text = bytes_;
  if (bytes_.size() >= 4 && readU32(bytes_, 0) == kGlbMagic) {
    // GLB (glTF 2.0 §4.4): 12-byte header, a JSON chunk, then an optional BIN chunk.
    if (bytes_.size() < 12) fail("", "GLB header truncated (" + std::to_string(bytes_.size()) + " bytes)");
    if (readU32(bytes_, 4) != 2) fail("", "GLB version " + std::to_string(readU32(bytes_, 4)) + " (only 2 is read)");
    const std::uint64_t total = readU32(bytes_, 8);
    if (total > bytes_.size())
      fail("", "GLB truncated: the header says " + std::to_string(total) + " bytes, the file has " +
                   std::to_string(bytes_.size()));
    std::uint64_t at = 12;
    int chunk = 0;
    bool haveJson = false;
    while (at < total) {
      if (total - at < 8) fail("", "GLB chunk " + std::to_string(chunk) + " header truncated");
      const std::uint64_t length = readU32(bytes_, at);
      const std::uint32_t type = readU32(bytes_, at + 4);
      if (length > total - at - 8)
        fail("", "GLB chunk " + std::to_string(chunk) + " truncated (" + std::to_string(length) + " bytes declared, " +
                     std::to_string(total - at - 8) + " left)");
      const std::string_view data = bytes_.substr(at + 8, length);
      if (chunk == 0) {
        if (type != kChunkJson) fail("", "GLB chunk 0 is not JSON");
        text = data;
        haveJson = true;
      } else if (chunk == 1 && type == kChunkBin) {
        glbBin_ = std::string(data);
        hasGlbBin_ = true;
      }
      at += 8 + length;
      ++chunk;
    }
    if (!haveJson) fail("", "GLB has no JSON chunk");
  } else if (bytes_.empty()) {
    fail("", "empty file (not glTF)");
  } else if (std::filesystem::path(path_).extension() == ".glb") {
    fail("", "bad magic: not a GLB file (it does not start with 'glTF')");
  }
  try {
    doc_ = json::parse(text.begin(), text.end());
  } catch (const json::exception& e) {
    fail("", std::string("not glTF: the JSON does not parse (") + e.what() + ")");
  }
  if (!doc_.is_object()) fail("", "not glTF: the JSON is not an object");
  const json& asset = member(doc_, "asset", "");
  const json& version = member(asset, "version", "/asset");
  if (!version.is_string() || version.get<std::string>().rfind("2.", 0) != 0)
    fail("/asset/version", "not glTF 2.x (" + version.dump() + ")");
}

int base64Value(char c) {
  if (c >= 'A' && c <= 'Z') return c - 'A';
  if (c >= 'a' && c <= 'z') return c - 'a' + 26;
  if (c >= '0' && c <= '9') return c - '0' + 52;
  if (c == '+') return 62;
  if (c == '/') return 63;
  return -1;
}

const std::string& Reader::buffer(std::size_t i) {
  auto found = buffers_.find(i);
  if (found != buffers_.end()) return found->second;
  const std::string pointer = "/buffers/" + std::to_string(i);
  const json& buf = element(member(doc_, "buffers", ""), i, "/buffers");
  const std::uint64_t byteLength = index(member(buf, "byteLength", pointer), pointer + "/byteLength", UINT64_MAX);
  std::string data;
  auto uri = buf.is_object() ? buf.find("uri") : buf.end();
  if (uri == buf.end()) {
    if (i != 0 || !hasGlbBin_) fail(pointer, "no uri and no GLB binary chunk");
    data = glbBin_;
  } else {
    if (!uri->is_string()) fail(pointer + "/uri", "expected a string");
    const std::string u = uri->get<std::string>();
    if (u.rfind("data:", 0) == 0) {
      const std::size_t comma = u.find(',');
      if (comma == std::string::npos || u.substr(0, comma).find(";base64") == std::string::npos)
        fail(pointer + "/uri", "a data URI that is not base64");
      int bits = 0;
      std::uint32_t acc = 0;
      for (std::size_t k = comma + 1; k < u.size(); ++k) {
        if (u[k] == '=') break;
        const int v = base64Value(u[k]);
        if (v < 0) fail(pointer + "/uri", "bad base64 character at offset " + std::to_string(k));
        acc = (acc << 6) | static_cast<std::uint32_t>(v);
        bits += 6;
        if (bits >= 8) {
          bits -= 8;
          data.push_back(static_cast<char>((acc >> bits) & 0xFF));
        }
      }
    } else {
      if (u.find("://") != std::string::npos || std::filesystem::path(u).is_absolute())
        fail(pointer + "/uri", "only data URIs and relative file names are read ('" + u + "')");
      const std::filesystem::path side = std::filesystem::path(path_).parent_path() / u;
      try {
        data = readWholeFile(side.string(), "cannot open the buffer file named by " + pointer + "/uri");
      } catch (const InputError& e) {
        throw InputError(e.what(), path_);
      }
    }
  }
  if (data.size() < byteLength)
    fail(pointer + "/byteLength", std::to_string(byteLength) + " bytes declared, the data has " +
                                      std::to_string(data.size()));
  data.resize(byteLength);
  return buffers_.emplace(i, std::move(data)).first->second;
}

std::size_t componentSize(std::uint64_t type) {
  switch (type) {
    case 5121: return 1;  // UNSIGNED_BYTE
    case 5123: return 2;  // UNSIGNED_SHORT
    case 5125: return 4;  // UNSIGNED_INT
    case 5126: return 4;  // FLOAT
    default: return 0;
  }
}

double readComponent(const char* p, std::uint64_t type) {
  switch (type) {
    case 5121: return static_cast<unsigned char>(*p);
    case 5123: { std::uint16_t v; std::memcpy(&v, p, 2); return v; }
    case 5125: { std::uint32_t v; std::memcpy(&v, p, 4); return v; }
    default: { float v; std::memcpy(&v, p, 4); return v; }
  }
}

std::vector<double> Reader::accessor(std::uint64_t i, bool positions) {
  const std::string pointer = "/accessors/" + std::to_string(i);
  const json& acc = element(member(doc_, "accessors", ""), i, "/accessors");
  if (!acc.is_object()) fail(pointer, "expected an object");
  const std::uint64_t ctype = index(member(acc, "componentType", pointer), pointer + "/componentType", UINT64_MAX);
  const json& typeJ = member(acc, "type", pointer);
  const std::string type = typeJ.is_string() ? typeJ.get<std::string>() : "";
  const std::size_t comps = positions ? 3 : 1;
  if (positions) {
    if (ctype != 5126) fail(pointer + "/componentType", std::to_string(ctype) + ": positions must be FLOAT (5126)");
    if (type != "VEC3") fail(pointer + "/type", typeJ.dump() + ": positions must be VEC3");
  } else {
    if (ctype != 5121 && ctype != 5123 && ctype != 5125)
      fail(pointer + "/componentType", std::to_string(ctype) + ": indices must be unsigned byte, short or int");
    if (type != "SCALAR") fail(pointer + "/type", typeJ.dump() + ": indices must be SCALAR");
  }
  auto normalized = acc.find("normalized");
  if (normalized != acc.end() && (!normalized->is_boolean() || normalized->get<bool>()))
    fail(pointer + "/normalized", "normalized accessors are not read here (positions and indices are not normalized)");
  // A count bound keeps a hostile file from asking for gigabytes or minutes: 2^20 vertices is far
  // beyond a head (ICT: 11,248).
  constexpr std::uint64_t kMaxCount = std::uint64_t{1} << 20;
  const std::uint64_t count = index(member(acc, "count", pointer), pointer + "/count", kMaxCount);
  if (count == 0) fail(pointer + "/count", "0 (at least 1 is needed)");
  const std::size_t csize = componentSize(ctype);
  const std::size_t elem = csize * comps;
  std::vector<double> out(count * comps, 0.0);  // no bufferView: zeros (§3.6.2.3), then sparse
  auto viewIt = acc.find("bufferView");
  if (viewIt != acc.end()) {
    const std::uint64_t v = index(*viewIt, pointer + "/bufferView", UINT64_MAX);
    const std::string vp = "/bufferViews/" + std::to_string(v);
    const json& view = element(member(doc_, "bufferViews", ""), v, "/bufferViews");
    if (!view.is_object()) fail(vp, "expected an object");
    const std::uint64_t b = index(member(view, "buffer", vp), vp + "/buffer", UINT64_MAX);
    const std::string& data = buffer(b);
    const std::uint64_t viewOffset = optIndex(view, "byteOffset", vp, 0, UINT64_MAX / 4);
    const std::uint64_t viewLength = index(member(view, "byteLength", vp), vp + "/byteLength", UINT64_MAX / 4);
    if (viewOffset + viewLength > data.size())
      fail(vp, "bytes " + std::to_string(viewOffset) + ".." + std::to_string(viewOffset + viewLength) +
                   " past the end of buffer " + std::to_string(b) + " (" + std::to_string(data.size()) + " bytes)");
    const std::uint64_t stride = optIndex(view, "byteStride", vp, elem, 253);
    if (stride < elem) fail(vp + "/byteStride", std::to_string(stride) + " is less than an element's " + std::to_string(elem) + " bytes");
    const std::uint64_t accOffset = optIndex(acc, "byteOffset", pointer, 0, UINT64_MAX / 4);
    if (accOffset % csize != 0) fail(pointer + "/byteOffset", "not a multiple of the component size");
    const std::uint64_t end = accOffset + stride * (count - 1) + elem;
    if (end > viewLength)
      fail(pointer, "out of range: " + std::to_string(count) + " elements need " + std::to_string(end) +
                        " bytes of bufferView " + std::to_string(v) + ", which has " + std::to_string(viewLength));
    const char* base = data.data() + viewOffset + accOffset;
    for (std::uint64_t k = 0; k < count; ++k)
      for (std::size_t c = 0; c < comps; ++c) out[k * comps + c] = readComponent(base + k * stride + c * csize, ctype);
  }
  auto sparseIt = acc.find("sparse");
  if (sparseIt != acc.end()) {
    const std::string sp = pointer + "/sparse";
    const json& sparse = *sparseIt;
    const std::uint64_t n = index(member(sparse, "count", sp), sp + "/count", count + 1);
    if (n == 0) fail(sp + "/count", "0 (at least 1 is needed)");
    auto readBlock = [&](const json& block, const std::string& bp, std::uint64_t blockType, std::size_t blockComps) {
      const std::uint64_t v = index(member(block, "bufferView", bp), bp + "/bufferView", UINT64_MAX);
      const std::string vp = "/bufferViews/" + std::to_string(v);
      const json& view = element(member(doc_, "bufferViews", ""), v, "/bufferViews");
      if (!view.is_object()) fail(vp, "expected an object");
      const std::string& data = buffer(index(member(view, "buffer", vp), vp + "/buffer", UINT64_MAX));
      const std::uint64_t viewOffset = optIndex(view, "byteOffset", vp, 0, UINT64_MAX / 4);
      const std::uint64_t viewLength = index(member(view, "byteLength", vp), vp + "/byteLength", UINT64_MAX / 4);
      if (viewOffset + viewLength > data.size()) fail(vp, "past the end of its buffer");
      const std::uint64_t off = optIndex(block, "byteOffset", bp, 0, UINT64_MAX / 4);
      const std::size_t size = componentSize(blockType);
      if (off + n * size * blockComps > viewLength)
        fail(bp, "out of range: " + std::to_string(n) + " elements past the end of bufferView " + std::to_string(v));
      std::vector<double> values(n * blockComps);
      const char* p = data.data() + viewOffset + off;  // sparse data is tightly packed (§3.6.2.3)
      for (std::uint64_t k = 0; k < n * blockComps; ++k) values[k] = readComponent(p + k * size, blockType);
      return values;
    };
    const json& indices = member(sparse, "indices", sp);
    const std::uint64_t itype = index(member(indices, "componentType", sp + "/indices"), sp + "/indices/componentType", UINT64_MAX);
    if (itype != 5121 && itype != 5123 && itype != 5125)
      fail(sp + "/indices/componentType", std::to_string(itype) + ": sparse indices must be unsigned byte, short or int");
    const std::vector<double> ids = readBlock(indices, sp + "/indices", itype, 1);
    const std::vector<double> values = readBlock(member(sparse, "values", sp), sp + "/values", ctype, comps);
    for (std::uint64_t k = 0; k < n; ++k) {
      if (ids[k] >= static_cast<double>(count))
        fail(sp + "/indices", "index " + std::to_string(static_cast<std::uint64_t>(ids[k])) + " out of range (count " +
                                  std::to_string(count) + ")");
      if (k > 0 && ids[k] <= ids[k - 1]) fail(sp + "/indices", "not strictly increasing");
      const auto at = static_cast<std::size_t>(ids[k]);
      for (std::size_t c = 0; c < comps; ++c) out[at * comps + c] = values[k * comps + c];
    }
  }
  for (std::size_t k = 0; k < out.size(); ++k)
    if (!std::isfinite(out[k])) fail(pointer, "non-finite value in element " + std::to_string(k / comps));
  return out;
}

Affine Reader::nodeMatrix(std::size_t i) const {
  const std::string np = "/nodes/" + std::to_string(i);
  const json& node = doc_["nodes"][i];
  Affine m = Affine::Identity();
  auto mat = node.find("matrix");
  if (mat != node.end()) {
    if (!mat->is_array() || mat->size() != 16) fail(np + "/matrix", "expected 16 numbers");
    for (int k = 0; k < 16; ++k) m(k % 4, k / 4) = number((*mat)[k], np + "/matrix/" + std::to_string(k));  // column-major
    return m;
  }
  auto vec = [&](const char* key, std::size_t n, std::array<double, 4> def) {
    auto it = node.find(key);
    if (it == node.end()) return def;
    if (!it->is_array() || it->size() != n) fail(np + "/" + key, "expected " + std::to_string(n) + " numbers");
    for (std::size_t k = 0; k < n; ++k) def[k] = number((*it)[k], np + "/" + key + "/" + std::to_string(k));
    return def;
  };
  const auto t = vec("translation", 3, {0, 0, 0, 0});
  const auto r = vec("rotation", 4, {0, 0, 0, 1});  // quaternion x, y, z, w
  const auto s = vec("scale", 3, {1, 1, 1, 0});
  Eigen::Quaterniond q(r[3], r[0], r[1], r[2]);
  if (q.norm() < 1e-12) fail(np + "/rotation", "a zero quaternion");
  q.normalize();
  // T * R * S (glTF 2.0 §3.5.3)
  m.topLeftCorner<3, 3>() = q.toRotationMatrix() * Eigen::Vector3d(s[0], s[1], s[2]).asDiagonal();
  m.topRightCorner<3, 1>() = Eigen::Vector3d(t[0], t[1], t[2]);
  return m;
}

Affine Reader::worldMatrix(std::size_t node) const {
  const json& nodes = doc_["nodes"];
  std::vector<long> parent(nodes.size(), -1);
  for (std::size_t p = 0; p < nodes.size(); ++p) {
    auto children = nodes[p].find("children");
    if (children == nodes[p].end()) continue;
    if (!children->is_array()) fail("/nodes/" + std::to_string(p) + "/children", "expected an array");
    for (std::size_t k = 0; k < children->size(); ++k) {
      const std::uint64_t c = index((*children)[k], "/nodes/" + std::to_string(p) + "/children/" + std::to_string(k),
                                    nodes.size());
      if (parent[c] >= 0 && parent[c] != static_cast<long>(p))
        fail("/nodes/" + std::to_string(c), "has two parents");
      parent[c] = static_cast<long>(p);
    }
  }
  Affine m = nodeMatrix(node);
  std::size_t steps = 0;
  for (long p = parent[node]; p >= 0; p = parent[p]) {
    if (++steps > nodes.size()) fail("/nodes", "the node hierarchy has a cycle");
    m = nodeMatrix(static_cast<std::size_t>(p)) * m;
  }
  return m;
}

RigFile Reader::read() {
  parseContainer();
  const json& meshes = member(doc_, "meshes", "");
  if (!meshes.is_array()) fail("/meshes", "expected an array");
  // The rig's mesh: the first with morph targets.
  std::size_t meshId = meshes.size();
  for (std::size_t i = 0; i < meshes.size() && meshId == meshes.size(); ++i) {
    const json& prims = member(meshes[i], "primitives", "/meshes/" + std::to_string(i));
    if (!prims.is_array()) fail("/meshes/" + std::to_string(i) + "/primitives", "expected an array");
    for (const json& p : prims)
      if (p.is_object() && p.contains("targets")) meshId = i;
  }
  if (meshId == meshes.size()) fail("/meshes", "no mesh has morph targets (not a blendshape rig)");
  const std::string mp = "/meshes/" + std::to_string(meshId);
  const json& mesh = meshes[meshId];
  const json& prims = mesh["primitives"];
  if (prims.size() != 1)
    fail(mp + "/primitives", std::to_string(prims.size()) + " primitives (a rig here has one)");
  const std::string pp = mp + "/primitives/0";
  const json& prim = prims[0];
  const std::uint64_t mode = optIndex(prim, "mode", pp, 4, UINT64_MAX);
  if (mode != 4) fail(pp + "/mode", std::to_string(mode) + ": only triangles (4) are read");

  const std::vector<double> pos = accessor(index(member(member(prim, "attributes", pp), "POSITION", pp + "/attributes"),
                                                 pp + "/attributes/POSITION", UINT64_MAX), true);
  const std::size_t n = pos.size() / 3;

  std::vector<std::uint64_t> tri;
  if (prim.contains("indices")) {
    const std::vector<double> ids = accessor(index(prim["indices"], pp + "/indices", UINT64_MAX), false);
    tri.reserve(ids.size());
    for (std::size_t k = 0; k < ids.size(); ++k) {
      if (ids[k] >= static_cast<double>(n))
        fail(pp + "/indices", "index " + std::to_string(static_cast<std::uint64_t>(ids[k])) + " at " +
                                  std::to_string(k) + " out of range (" + std::to_string(n) + " vertices)");
      tri.push_back(static_cast<std::uint64_t>(ids[k]));
    }
  } else {
    for (std::size_t k = 0; k < n; ++k) tri.push_back(k);
  }
  if (tri.size() % 3 != 0) fail(pp, std::to_string(tri.size()) + " indices is not a whole number of triangles");
  if (tri.empty()) fail(pp, "no triangles");

  // Names: the mesh's extras.targetNames (the de-facto convention), else the primitive's.
  const json& targets = member(prim, "targets", pp);
  if (!targets.is_array() || targets.empty()) fail(pp + "/targets", "expected a non-empty array");
  const json* names = nullptr;
  std::string namesPointer;
  for (const auto& [holder, where] : {std::pair<const json*, std::string>{&mesh, mp}, {&prim, pp}}) {
    if (names) break;
    auto extras = holder->find("extras");
    if (extras != holder->end() && extras->is_object() && extras->contains("targetNames")) {
      names = &extras->at("targetNames");
      namesPointer = where + "/extras/targetNames";
    }
  }
  if (!names) fail(mp + "/extras/targetNames", "missing (the rig's target names)");
  if (!names->is_array()) fail(namesPointer, "expected an array of strings");
  if (names->size() != targets.size())
    fail(namesPointer, std::to_string(names->size()) + " names for " + std::to_string(targets.size()) + " targets");

  // Place the mesh: the first node that references it, with its parents.
  Affine world = Affine::Identity();
  auto nodes = doc_.find("nodes");
  if (nodes != doc_.end()) {
    if (!nodes->is_array()) fail("/nodes", "expected an array");
    for (std::size_t i = 0; i < nodes->size(); ++i) {
      const json& node = (*nodes)[i];
      if (!node.is_object()) fail("/nodes/" + std::to_string(i), "expected an object");
      auto m = node.find("mesh");
      if (m != node.end() && index(*m, "/nodes/" + std::to_string(i) + "/mesh", meshes.size()) == meshId) {
        world = worldMatrix(i);
        break;
      }
    }
  }
  const Eigen::Matrix3d linear = world.topLeftCorner<3, 3>();
  const Eigen::Vector3d shift = world.topRightCorner<3, 1>();

  // Weld exact duplicate positions in first-seen order (the primitive's order without seam copies).
  RigFile rig;
  rig.path = path_;
  rig.weldedIndex.assign(n, -1);
  std::map<std::array<double, 3>, int> seen;
  std::vector<std::size_t> firsts;
  for (std::size_t k = 0; k < n; ++k) {
    const std::array<double, 3> key{pos[3 * k], pos[3 * k + 1], pos[3 * k + 2]};
    auto [it, fresh] = seen.emplace(key, static_cast<int>(firsts.size()));
    if (fresh) firsts.push_back(k);
    rig.weldedIndex[k] = it->second;
  }
  auto place = [&](const std::vector<double>& p, std::size_t k) {
    return Eigen::Vector3d(kMetresToCm * (linear * Eigen::Vector3d(p[3 * k], p[3 * k + 1], p[3 * k + 2]) + shift));
  };
  rig.base.V.resize(static_cast<Eigen::Index>(firsts.size()), 3);
  for (std::size_t w = 0; w < firsts.size(); ++w) rig.base.V.row(static_cast<Eigen::Index>(w)) = place(pos, firsts[w]).transpose();
  rig.base.F.resize(static_cast<Eigen::Index>(tri.size() / 3), 3);
  for (std::size_t k = 0; k < tri.size(); ++k)
    rig.base.F(static_cast<Eigen::Index>(k / 3), static_cast<Eigen::Index>(k % 3)) = rig.weldedIndex[tri[k]];
  // A mirrored node transform turns the winding inside out; keep the triangles outward.
  if (linear.determinant() < 0) rig.base.F.col(1).swap(rig.base.F.col(2));

  for (std::size_t t = 0; t < targets.size(); ++t) {
    const std::string tp = pp + "/targets/" + std::to_string(t);
    const json& name = (*names)[t];
    if (!name.is_string()) fail(namesPointer + "/" + std::to_string(t), "expected a string");
    const std::string s = name.get<std::string>();
    if (std::find(rig.names.begin(), rig.names.end(), s) != rig.names.end())
      fail(namesPointer + "/" + std::to_string(t), "'" + s + "' appears twice");
    const json& target = targets[t];
    const std::vector<double> d =
        accessor(index(member(target, "POSITION", tp), tp + "/POSITION", UINT64_MAX), true);
    if (d.size() != pos.size())
      fail(tp + "/POSITION", std::to_string(d.size() / 3) + " displacements for " + std::to_string(n) + " vertices");
    std::vector<double> absolute(pos.size());
    for (std::size_t k = 0; k < pos.size(); ++k) absolute[k] = pos[k] + d[k];
    MatX3 shape(static_cast<Eigen::Index>(firsts.size()), 3);
    for (std::size_t w = 0; w < firsts.size(); ++w) shape.row(static_cast<Eigen::Index>(w)) = place(absolute, firsts[w]).transpose();
    if (!shape.allFinite()) fail(tp, "non-finite position after the node transform");
    rig.names.push_back(s);
    rig.targets.push_back(std::move(shape));
  }
  if (!rig.base.V.allFinite()) fail(pp + "/attributes/POSITION", "non-finite position after the node transform");
  return rig;
}

}  // namespace

int RigFile::find(const std::string& name) const {
  for (std::size_t i = 0; i < names.size(); ++i)
    if (names[i] == name) return static_cast<int>(i);
  return -1;
}

const MatX3& RigFile::shape(const std::string& name) const {
  const int i = find(name);
  if (i < 0) throw InputError("no shape '" + name + "' (the rig has: " + joinNames(names) + ")", path);
  return targets[static_cast<std::size_t>(i)];
}

MatX3 RigFile::delta(const std::string& name) const { return shape(name) - base.V; }

RigFile parseRig(std::string_view bytes, const std::string& path) { return Reader(bytes, path).read(); }

RigFile readRig(const std::string& path) {
  const std::string bytes = readWholeFile(path, "cannot open rig file");
  return parseRig(bytes, path);
}

RigShapeRef splitRigShape(const std::string& pathHashShape) {
  const std::size_t hash = pathHashShape.rfind('#');
  if (hash == std::string::npos) return {pathHashShape, ""};
  return {pathHashShape.substr(0, hash), pathHashShape.substr(hash + 1)};
}

bool isRigShapeArgument(const std::string& argument) {
  const RigShapeRef ref = splitRigShape(argument);
  if (ref.shape.empty() && argument.find('#') == std::string::npos) return false;
  std::string ext = std::filesystem::path(ref.path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext == ".glb" || ext == ".gltf";
}

MatX3 rigShape(const std::string& pathHashShape) {
  const RigShapeRef ref = splitRigShape(pathHashShape);
  if (ref.shape.empty())
    throw InputError("name a shape after '#' (RIG.glb#shape)", ref.path);
  return readRig(ref.path).shape(ref.shape);
}

}  // namespace myo
