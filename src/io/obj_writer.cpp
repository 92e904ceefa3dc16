#include "myoshell/io/obj_writer.h"

#include <algorithm>
#include <charconv>
#include <cstdio>
#include <map>
#include <utility>
#include <vector>

#include "myoshell/core/atomic_file.h"
#include "myoshell/core/check.h"
#include "myoshell/core/whole_file.h"

namespace myo {

namespace {

// Shortest text that reads back to the same double.
const char* shortest(double x, char* buf) {
  auto r = std::to_chars(buf, buf + 32, x);
  *r.ptr = '\0';
  return buf;
}

bool isBlank(char c) { return c == ' ' || c == '\t'; }

// The [begin, end) byte spans of the first three numbers of every `v` line (a line whose first
// word is "v"), in file order; empty when a `v` line has fewer than three words.
std::vector<std::pair<size_t, size_t>> positionSpans(const std::string& text, bool& ok) {
  std::vector<std::pair<size_t, size_t>> spans;
  ok = true;
  for (size_t line = 0; line < text.size();) {
    size_t end = text.find('\n', line);
    if (end == std::string::npos) end = text.size();
    size_t i = line;
    while (i < end && isBlank(text[i])) ++i;
    if (i + 1 < end && text[i] == 'v' && isBlank(text[i + 1])) {
      size_t first = 0, last = 0;
      ++i;
      for (int word = 0; word < 3; ++word) {
        while (i < end && isBlank(text[i])) ++i;
        const size_t start = i;
        while (i < end && !isBlank(text[i]) && text[i] != '\r') ++i;
        if (i == start) ok = false;
        if (word == 0) first = start;
        last = i;
      }
      spans.emplace_back(first, last);
    }
    line = end + 1;
  }
  return spans;
}

// The faces to write (the mesh's polygons when present, else its triangles) with, when the mesh
// has corner UVs, a texture coordinate index per face corner into `texcoords` (the distinct corner
// UVs in order of first appearance), so that UV seams are written as seams.
struct ObjFaces {
  std::vector<std::vector<int>> vertices;
  std::vector<std::vector<int>> texcoordIndices;  // parallel to vertices; empty without corner UVs
  std::vector<Vec2> texcoords;
};

// Corner UVs onto the faces: each triangle corner's UV goes to the corner of its source polygon at
// the same vertex. False when that cannot be done (sourcePolygon does not match the polygons, or a
// polygon corner is covered by no triangle): the caller then writes UVs per vertex.
bool addCornerTexcoords(const TriMesh& mesh, ObjFaces& faces) {
  std::map<std::pair<double, double>, int> index;
  auto texcoordOf = [&](Eigen::Index row) {
    const std::pair<double, double> uv{mesh.cornerUV(row, 0), mesh.cornerUV(row, 1)};
    auto [it, fresh] = index.try_emplace(uv, static_cast<int>(faces.texcoords.size()));
    if (fresh) faces.texcoords.emplace_back(uv.first, uv.second);
    return it->second;
  };
  const Eigen::Index m = mesh.F.rows();
  if (mesh.polygons.empty()) {
    for (Eigen::Index t = 0; t < m; ++t)
      faces.texcoordIndices.push_back({texcoordOf(3 * t), texcoordOf(3 * t + 1), texcoordOf(3 * t + 2)});
    return true;
  }
  if (mesh.sourcePolygon.size() != static_cast<size_t>(m)) return false;
  for (const auto& p : faces.vertices) faces.texcoordIndices.emplace_back(p.size(), -1);
  for (Eigen::Index t = 0; t < m; ++t) {
    const int p = mesh.sourcePolygon[static_cast<size_t>(t)];
    if (p < 0 || static_cast<size_t>(p) >= faces.vertices.size()) return false;
    const auto& poly = faces.vertices[static_cast<size_t>(p)];
    for (int c = 0; c < 3; ++c) {
      const auto at = std::find(poly.begin(), poly.end(), mesh.F(t, c));
      if (at == poly.end()) return false;
      int& slot = faces.texcoordIndices[static_cast<size_t>(p)][static_cast<size_t>(at - poly.begin())];
      if (slot < 0) slot = texcoordOf(3 * t + c);
    }
  }
  for (const auto& corners : faces.texcoordIndices)
    if (std::find(corners.begin(), corners.end(), -1) != corners.end()) return false;
  return true;
}

ObjFaces objFaces(const TriMesh& mesh) {
  ObjFaces faces;
  faces.vertices = mesh.polygons;
  if (faces.vertices.empty())
    for (Eigen::Index t = 0; t < mesh.F.rows(); ++t) faces.vertices.push_back({mesh.F(t, 0), mesh.F(t, 1), mesh.F(t, 2)});
  if (mesh.hasCornerUV() && !addCornerTexcoords(mesh, faces)) {
    faces.texcoordIndices.clear();
    faces.texcoords.clear();
  }
  return faces;
}

// Streams the OBJ to `out` (printf into a FILE*: the sequence of a long run writes many MB).
void putObj(std::FILE* out, const TriMesh& mesh, const MatX3& X) {
  const auto num = shortest;
  char a[40], b[40], c[40];
  const ObjFaces faces = objFaces(mesh);
  std::fprintf(out, "# written by myoshell: %d vertices, %zu faces\n", static_cast<int>(X.rows()),
               faces.vertices.size());
  for (Eigen::Index i = 0; i < X.rows(); ++i)
    std::fprintf(out, "v %s %s %s\n", num(X(i, 0), a), num(X(i, 1), b), num(X(i, 2), c));
  const bool perCorner = !faces.texcoordIndices.empty();
  const bool perVertex = !perCorner && mesh.UV.rows() == X.rows() && X.rows() > 0;
  if (perCorner)
    for (const Vec2& uv : faces.texcoords) std::fprintf(out, "vt %s %s\n", num(uv[0], a), num(uv[1], b));
  if (perVertex)
    for (Eigen::Index i = 0; i < mesh.UV.rows(); ++i)
      std::fprintf(out, "vt %s %s\n", num(mesh.UV(i, 0), a), num(mesh.UV(i, 1), b));
  for (size_t f = 0; f < faces.vertices.size(); ++f) {
    std::fputc('f', out);
    const auto& p = faces.vertices[f];
    for (size_t k = 0; k < p.size(); ++k) {
      if (perCorner) std::fprintf(out, " %d/%d", p[k] + 1, faces.texcoordIndices[f][k] + 1);
      else if (perVertex) std::fprintf(out, " %d/%d", p[k] + 1, p[k] + 1);
      else std::fprintf(out, " %d", p[k] + 1);
    }
    std::fputc('\n', out);
  }
}

}  // namespace

bool writeObjLikeFile(const std::string& path, const std::string& sourcePath, const MatX3& V) {
  const std::string text = readWholeFile(sourcePath, "cannot open OBJ");
  bool ok = true;
  const std::vector<std::pair<size_t, size_t>> spans = positionSpans(text, ok);
  if (!ok || static_cast<Eigen::Index>(spans.size()) != V.rows()) return false;
  writeFileAtomically(
      path,
      [&](std::FILE* out) {
        char a[40], b[40], c[40];
        size_t at = 0;
        for (size_t i = 0; i < spans.size(); ++i) {
          std::fwrite(text.data() + at, 1, spans[i].first - at, out);
          const auto r = static_cast<Eigen::Index>(i);
          std::fprintf(out, "%s %s %s", shortest(V(r, 0), a), shortest(V(r, 1), b), shortest(V(r, 2), c));
          at = spans[i].second;
        }
        std::fwrite(text.data() + at, 1, text.size() - at, out);
      },
      "cannot write OBJ");
  return true;
}

void writeObj(const std::string& path, const TriMesh& mesh, const MatX3* V) {
  const MatX3& X = V ? *V : mesh.V;
  MYO_CHECK_EQ(X.rows(), mesh.V.rows());
  writeFileAtomically(path, [&](std::FILE* out) { putObj(out, mesh, X); }, "cannot write OBJ");
}

}  // namespace myo
