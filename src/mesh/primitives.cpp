#include "myoshell/mesh/primitives.h"

#include <array>
#include <map>
#include <vector>

#include "myoshell/core/check.h"

namespace myo {

TriMesh gridMesh(double length, double width, int nx, int ny, bool alternate) {
  MYO_CHECK(nx >= 1 && ny >= 1, "a grid needs at least one cell each way");
  TriMesh mesh;
  mesh.V.resize((nx + 1) * (ny + 1), 3);
  mesh.UV.resize((nx + 1) * (ny + 1), 2);
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) {
      const int v = j * (nx + 1) + i;
      mesh.V.row(v) << length * i / nx, width * j / ny, 0.0;
      mesh.UV.row(v) << static_cast<double>(i) / nx, static_cast<double>(j) / ny;
    }
  mesh.F.resize(2 * nx * ny, 3);
  int t = 0;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const int a = j * (nx + 1) + i, b = a + 1, c = a + nx + 1, d = c + 1;
      if (!alternate || (i + j) % 2 == 0) {
        mesh.F.row(t++) << a, b, d;
        mesh.F.row(t++) << a, d, c;
      } else {
        mesh.F.row(t++) << a, b, c;
        mesh.F.row(t++) << b, d, c;
      }
      mesh.polygons.push_back({a, b, d, c});
      mesh.sourcePolygon.push_back(static_cast<int>(mesh.polygons.size()) - 1);
      mesh.sourcePolygon.push_back(static_cast<int>(mesh.polygons.size()) - 1);
    }
  return mesh;
}

TriMesh icosphere(double radius, int subdivisions) {
  const double p = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<Vec3> verts = {{-1, p, 0}, {1, p, 0}, {-1, -p, 0}, {1, -p, 0}, {0, -1, p}, {0, 1, p},
                             {0, -1, -p}, {0, 1, -p}, {p, 0, -1}, {p, 0, 1}, {-p, 0, -1}, {-p, 0, 1}};
  std::vector<std::array<int, 3>> faces = {
      {0, 11, 5}, {0, 5, 1}, {0, 1, 7}, {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
      {11, 10, 2}, {10, 7, 6}, {7, 1, 8}, {3, 9, 4}, {3, 4, 2}, {3, 2, 6}, {3, 6, 8},
      {3, 8, 9}, {4, 9, 5}, {2, 4, 11}, {6, 2, 10}, {8, 6, 7}, {9, 8, 1}};
  for (auto& v : verts) v.normalize();
  for (int level = 0; level < subdivisions; ++level) {
    std::map<std::pair<int, int>, int> midpoint;
    auto mid = [&](int a, int b) {
      auto key = std::minmax(a, b);
      auto [it, inserted] = midpoint.try_emplace({key.first, key.second}, static_cast<int>(verts.size()));
      if (inserted) verts.push_back((verts[a] + verts[b]).normalized());
      return it->second;
    };
    std::vector<std::array<int, 3>> next;
    next.reserve(faces.size() * 4);
    for (const auto& f : faces) {
      const int ab = mid(f[0], f[1]), bc = mid(f[1], f[2]), ca = mid(f[2], f[0]);
      next.push_back({f[0], ab, ca});
      next.push_back({f[1], bc, ab});
      next.push_back({f[2], ca, bc});
      next.push_back({ab, bc, ca});
    }
    faces = std::move(next);
  }
  TriMesh mesh;
  mesh.V.resize(static_cast<Eigen::Index>(verts.size()), 3);
  for (size_t i = 0; i < verts.size(); ++i) mesh.V.row(static_cast<Eigen::Index>(i)) = radius * verts[i];
  mesh.F.resize(static_cast<Eigen::Index>(faces.size()), 3);
  for (size_t t = 0; t < faces.size(); ++t)
    mesh.F.row(static_cast<Eigen::Index>(t)) << faces[t][0], faces[t][1], faces[t][2];
  return mesh;
}

}  // namespace myo
