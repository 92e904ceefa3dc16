#include "myoshell/io/obj_writer.h"

#include <charconv>
#include <cstdio>

#include "myoshell/core/atomic_file.h"
#include "myoshell/core/check.h"

namespace myo {

namespace {

// Streams the OBJ to `out` (printf into a FILE*: the sequence of a long run writes many MB).
void putObj(std::FILE* out, const TriMesh& mesh, const MatX3& X) {
  auto num = [](double x, char* buf) {  // shortest text that reads back to the same double
    auto r = std::to_chars(buf, buf + 32, x);
    *r.ptr = '\0';
    return buf;
  };
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

void writeObj(const std::string& path, const TriMesh& mesh, const MatX3* V) {
  const MatX3& X = V ? *V : mesh.V;
  MYO_CHECK_EQ(X.rows(), mesh.V.rows());
  writeFileAtomically(path, [&](std::FILE* out) { putObj(out, mesh, X); }, "cannot write OBJ");
}

}  // namespace myo
