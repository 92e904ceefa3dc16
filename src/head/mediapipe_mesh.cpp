#include "myoshell/head/mediapipe_mesh.h"

#include <algorithm>
#include <cstring>
#include <set>
#include <vector>

#include "myoshell/core/errors.h"

namespace myo {

namespace {

// A minimal protobuf wire-format reader (wire types 0, 1, 2, 5).
class WireReader {
 public:
  WireReader(const std::uint8_t* data, std::size_t size, std::size_t base, const std::string& name)
      : p_(data), end_(data + size), base_(base), begin_(data), name_(name) {}

  bool done() const { return p_ >= end_; }
  std::size_t offset() const { return base_ + static_cast<std::size_t>(p_ - begin_); }

  std::uint64_t varint() {
    std::uint64_t r = 0;
    for (int shift = 0; shift < 64; shift += 7) {
      if (p_ >= end_) fail("truncated varint");
      const std::uint8_t c = *p_++;
      r |= static_cast<std::uint64_t>(c & 0x7f) << shift;
      if (c < 0x80) return r;
    }
    fail("varint longer than 10 bytes");
  }
  float fixed32Float() {
    if (end_ - p_ < 4) fail("truncated 32-bit value");
    std::uint32_t u = static_cast<std::uint32_t>(p_[0]) | static_cast<std::uint32_t>(p_[1]) << 8 |
                      static_cast<std::uint32_t>(p_[2]) << 16 | static_cast<std::uint32_t>(p_[3]) << 24;
    p_ += 4;
    float f;
    std::memcpy(&f, &u, 4);
    return f;
  }
  // A length-delimited payload: returns its start and advances past it.
  const std::uint8_t* bytes(std::size_t& len) {
    const std::uint64_t n = varint();
    if (n > static_cast<std::uint64_t>(end_ - p_)) fail("length-delimited field runs past the end");
    len = static_cast<std::size_t>(n);
    const std::uint8_t* s = p_;
    p_ += len;
    return s;
  }
  void skip(int wireType) {
    std::size_t len = 0;
    switch (wireType) {
      case 0: varint(); break;
      case 1:
        if (end_ - p_ < 8) fail("truncated 64-bit value");
        p_ += 8;
        break;
      case 2: bytes(len); break;
      case 5:
        if (end_ - p_ < 4) fail("truncated 32-bit value");
        p_ += 4;
        break;
      default: fail("unsupported wire type " + std::to_string(wireType));
    }
  }
  [[noreturn]] void fail(const std::string& what) const {
    throw InputError("malformed protobuf at byte " + std::to_string(offset()) + ": " + what, name_);
  }

 private:
  const std::uint8_t* p_;
  const std::uint8_t* end_;
  std::size_t base_;
  const std::uint8_t* begin_;
  const std::string& name_;
};

// Decodes a Mesh3d whose bytes start at byte `base` of the file (for error offsets).
TriMesh parseMesh3dAt(const std::uint8_t* data, std::size_t size, std::size_t base,
                      const std::string& name) {
  WireReader r(data, size, base, name);
  std::vector<float> floats;
  std::vector<std::uint64_t> indices;
  while (!r.done()) {
    const std::size_t at = r.offset();
    const std::uint64_t key = r.varint();
    const int field = static_cast<int>(key >> 3), wire = static_cast<int>(key & 7);
    if ((field == 1 || field == 2) && wire == 0) {
      const std::uint64_t v = r.varint();
      if (v != 0)
        throw InputError("Mesh3d at byte " + std::to_string(at) + ": " +
                             (field == 1 ? "vertex_type " : "primitive_type ") + std::to_string(v) +
                             " is not supported (only 0: VERTEX_PT, TRIANGLE)",
                         name);
    } else if (field == 3 && wire == 5) {  // unpacked float
      floats.push_back(r.fixed32Float());
    } else if (field == 3 && wire == 2) {  // packed floats
      std::size_t len = 0;
      const std::uint8_t* s = r.bytes(len);
      if (len % 4 != 0) r.fail("packed vertex_buffer of " + std::to_string(len) + " bytes");
      WireReader sub(s, len, base + static_cast<std::size_t>(s - data), name);
      while (!sub.done()) floats.push_back(sub.fixed32Float());
    } else if (field == 4 && wire == 0) {  // unpacked uint32
      indices.push_back(r.varint());
    } else if (field == 4 && wire == 2) {  // packed varints
      std::size_t len = 0;
      const std::uint8_t* s = r.bytes(len);
      WireReader sub(s, len, base + static_cast<std::size_t>(s - data), name);
      while (!sub.done()) indices.push_back(sub.varint());
    } else {
      r.skip(wire);
    }
  }
  if (floats.size() % 5 != 0)
    throw InputError("Mesh3d vertex_buffer holds " + std::to_string(floats.size()) +
                         " floats, not a multiple of 5 (X Y Z U V per vertex)",
                     name);
  if (indices.size() % 3 != 0)
    throw InputError("Mesh3d index_buffer holds " + std::to_string(indices.size()) +
                         " indices, not a multiple of 3",
                     name);
  const int n = static_cast<int>(floats.size() / 5), m = static_cast<int>(indices.size() / 3);
  TriMesh mesh;
  mesh.sourcePath = name;
  mesh.V.resize(n, 3);
  mesh.UV.resize(n, 2);
  for (int i = 0; i < n; ++i) {
    for (int k = 0; k < 3; ++k) mesh.V(i, k) = floats[static_cast<size_t>(5 * i + k)];
    for (int k = 0; k < 2; ++k) mesh.UV(i, k) = floats[static_cast<size_t>(5 * i + 3 + k)];
  }
  mesh.F.resize(m, 3);
  for (int t = 0; t < m; ++t)
    for (int k = 0; k < 3; ++k) {
      const std::uint64_t v = indices[static_cast<size_t>(3 * t + k)];
      if (v >= static_cast<std::uint64_t>(n))
        throw InputError("Mesh3d triangle " + std::to_string(t) + " uses vertex " +
                             std::to_string(v) + ", out of range [0, " + std::to_string(n) + ")",
                         name);
      mesh.F(t, k) = static_cast<int>(v);
    }
  return mesh;
}

}  // namespace

TriMesh parseMesh3d(const std::uint8_t* data, std::size_t size, const std::string& name) {
  return parseMesh3dAt(data, size, 0, name);
}

TriMesh parseGeometryPipelineMetadata(const std::uint8_t* data, std::size_t size,
                                      const std::string& name) {
  WireReader r(data, size, 0, name);
  while (!r.done()) {
    const std::uint64_t key = r.varint();
    const int field = static_cast<int>(key >> 3), wire = static_cast<int>(key & 7);
    if (field == 1 && wire == 2) {
      std::size_t len = 0;
      const std::uint8_t* s = r.bytes(len);
      return parseMesh3dAt(s, len, static_cast<std::size_t>(s - data), name);
    }
    r.skip(wire);
  }
  throw InputError("GeometryPipelineMetadata has no canonical_mesh (field 1)", name);
}

namespace {

// Removes every triangle whose three vertices lie on the two lines and which has a vertex on each
// line besides their shared end points (the strip between two lines that meet at their ends).
// Corner UVs follow the kept triangles. Returns the number removed.
template <size_t N>
int removeBetweenLines(TriMesh& mesh, const std::array<int, N>& lineA, const std::array<int, N>& lineB) {
  std::set<int> a(lineA.begin(), lineA.end());
  std::set<int> b(lineB.begin(), lineB.end());
  const int corners[2] = {lineA.front(), lineA.back()};
  auto isCorner = [&](int v) { return v == corners[0] || v == corners[1]; };
  std::vector<int> keep;
  keep.reserve(static_cast<size_t>(mesh.triangleCount()));
  for (int t = 0; t < mesh.triangleCount(); ++t) {
    bool allOnLines = true, hasA = false, hasB = false;
    for (int k = 0; k < 3; ++k) {
      const int v = mesh.F(t, k);
      const bool onA = a.count(v) > 0, onB = b.count(v) > 0;
      allOnLines = allOnLines && (onA || onB);
      if (!isCorner(v)) {
        hasA = hasA || onA;
        hasB = hasB || onB;
      }
    }
    if (!(allOnLines && hasA && hasB)) keep.push_back(t);
  }
  const int removed = mesh.triangleCount() - static_cast<int>(keep.size());
  MatX3i F(static_cast<int>(keep.size()), 3);
  for (size_t i = 0; i < keep.size(); ++i) F.row(static_cast<int>(i)) = mesh.F.row(keep[i]);
  if (mesh.hasCornerUV()) {  // the kept triangles keep their corners' UVs
    MatX2 cornerUV(3 * F.rows(), 2);
    for (size_t i = 0; i < keep.size(); ++i)
      cornerUV.middleRows(3 * static_cast<Eigen::Index>(i), 3) = mesh.cornerUV.middleRows(3 * keep[i], 3);
    mesh.cornerUV = std::move(cornerUV);
  } else {
    mesh.cornerUV.resize(0, 2);
  }
  mesh.F = std::move(F);
  mesh.sourcePolygon.clear();
  mesh.polygons.clear();
  return removed;
}

}  // namespace

int openMediapipeMouth(TriMesh& mesh) {
  return removeBetweenLines(mesh, kMediapipeInnerLipUpper, kMediapipeInnerLipLower);
}

int openMediapipeEyes(TriMesh& mesh) {
  return removeBetweenLines(mesh, kMediapipeRightEyeUpper, kMediapipeRightEyeLower) +
         removeBetweenLines(mesh, kMediapipeLeftEyeUpper, kMediapipeLeftEyeLower);
}

}  // namespace myo
