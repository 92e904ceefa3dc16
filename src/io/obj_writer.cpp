#include "myoshell/io/obj_writer.h"

#include <charconv>
#include <cstdio>
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

// Streams the OBJ to `out` (printf into a FILE*: the sequence of a long run writes many MB).
void putObj(std::FILE* out, const TriMesh& mesh, const MatX3& X) {
  const auto num = shortest;
  char a[40], b[40], c[40];
  std::fprintf(out, "# written by myoshell: %d vertices, %zu faces\n", static_cast<int>(X.rows()),
               mesh.polygons.empty() ? static_cast<size_t>(mesh.F.rows()) : mesh.polygons.size());
  for (Eigen::Index i = 0; i < X.rows(); ++i)
    std::fprintf(out, "v %s %s %s\n", num(X(i, 0), a), num(X(i, 1), b), num(X(i, 2), c));
  const bool uv = mesh.UV.rows() == X.rows() && X.rows() > 0;
  if (uv)
    for (Eigen::Index i = 0; i < mesh.UV.rows(); ++i)
      std::fprintf(out, "vt %s %s\n", num(mesh.UV(i, 0), a), num(mesh.UV(i, 1), b));
  auto face = [&](auto begin, auto end) {
    std::fputc('f', out);
    for (auto it = begin; it != end; ++it) {
      if (uv) std::fprintf(out, " %d/%d", *it + 1, *it + 1);
      else std::fprintf(out, " %d", *it + 1);
    }
    std::fputc('\n', out);
  };
  if (!mesh.polygons.empty()) {
    for (const auto& p : mesh.polygons) face(p.begin(), p.end());
  } else {
    for (Eigen::Index t = 0; t < mesh.F.rows(); ++t) {
      const int tri[3] = {mesh.F(t, 0), mesh.F(t, 1), mesh.F(t, 2)};
      face(tri, tri + 3);
    }
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
