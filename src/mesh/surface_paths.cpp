#include "myoshell/mesh/surface_paths.h"

#include <algorithm>
#include <functional>
#include <limits>
#include <queue>
#include <utility>

namespace myo {

namespace {

struct Dijkstra {
  std::vector<double> distance;
  std::vector<int> previous;  // the vertex before each on its shortest path; −1 at the source
};

Dijkstra runDijkstra(const TriMesh& mesh, int source) {
  const size_t n = static_cast<size_t>(mesh.vertexCount());
  std::vector<std::vector<std::pair<int, double>>> adjacent(n);
  for (Eigen::Index t = 0; t < mesh.F.rows(); ++t)
    for (int k = 0; k < 3; ++k) {
      const int a = mesh.F(t, k), b = mesh.F(t, (k + 1) % 3);
      const double length = (mesh.V.row(a) - mesh.V.row(b)).norm();
      adjacent[static_cast<size_t>(a)].emplace_back(b, length);
      adjacent[static_cast<size_t>(b)].emplace_back(a, length);
    }
  Dijkstra r{std::vector<double>(n, std::numeric_limits<double>::infinity()), std::vector<int>(n, -1)};
  using Item = std::pair<double, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
  r.distance[static_cast<size_t>(source)] = 0.0;
  queue.emplace(0.0, source);
  while (!queue.empty()) {
    const auto [dist, v] = queue.top();
    queue.pop();
    if (dist > r.distance[static_cast<size_t>(v)]) continue;
    for (const auto& [w, length] : adjacent[static_cast<size_t>(v)])
      if (dist + length < r.distance[static_cast<size_t>(w)]) {
        r.distance[static_cast<size_t>(w)] = dist + length;
        r.previous[static_cast<size_t>(w)] = v;
        queue.emplace(dist + length, w);
      }
  }
  return r;
}

}  // namespace

std::vector<double> surfaceDistances(const TriMesh& mesh, int source) { return runDijkstra(mesh, source).distance; }

std::vector<int> shortestEdgePath(const TriMesh& mesh, int from, int to) {
  const Dijkstra r = runDijkstra(mesh, from);
  if (r.distance[static_cast<size_t>(to)] == std::numeric_limits<double>::infinity()) return {};
  std::vector<int> path;
  for (int v = to; v != -1; v = r.previous[static_cast<size_t>(v)]) path.push_back(v);
  std::reverse(path.begin(), path.end());
  return path;
}

}  // namespace myo
