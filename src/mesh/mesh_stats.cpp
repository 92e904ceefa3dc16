// Table 1 of the thesis for any mesh: counts, topology, bounding box, area.
#include "myoshell/mesh/mesh_stats.h"

#include <limits>
#include <numeric>

#include "myoshell/mesh/edge_table.h"
#include "myoshell/mesh/geometry.h"

namespace myo {

namespace {

// Union-find with path halving; enough for counting components.
struct DisjointSets {
  std::vector<int> parent;
  explicit DisjointSets(int n) : parent(static_cast<size_t>(n)) {
    std::iota(parent.begin(), parent.end(), 0);
  }
  int find(int x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  }
  void unite(int a, int b) { parent[find(a)] = find(b); }
};

// Bounding box over the finite vertices; false when there are none.
bool finiteBox(const MatX3& V, Vec3& lo, Vec3& hi) {
  bool any = false;
  lo.setConstant(std::numeric_limits<double>::infinity());
  hi.setConstant(-std::numeric_limits<double>::infinity());
  for (Eigen::Index i = 0; i < V.rows(); ++i) {
    if (!V.row(i).allFinite()) continue;
    any = true;
    lo = lo.cwiseMin(V.row(i).transpose());
    hi = hi.cwiseMax(V.row(i).transpose());
  }
  if (!any) lo = hi = Vec3::Zero();
  return any;
}

bool finiteTriangle(const MatX3& V, const MatX3i& F, Eigen::Index t) {
  return V.row(F(t, 0)).allFinite() && V.row(F(t, 1)).allFinite() && V.row(F(t, 2)).allFinite();
}

}  // namespace

std::vector<int> degenerateTriangles(const MatX3& V, const MatX3i& F) {
  Vec3 lo, hi;
  finiteBox(V, lo, hi);
  const double limit = kDegenerateAreaTolerance * (hi - lo).squaredNorm();
  std::vector<int> out;
  for (Eigen::Index t = 0; t < F.rows(); ++t) {
    if (!finiteTriangle(V, F, t)) continue;
    // <= so that a mesh collapsed to a point (limit 0) still counts its triangles as degenerate.
    if (triangleArea(V.row(F(t, 0)), V.row(F(t, 1)), V.row(F(t, 2))) <= limit)
      out.push_back(static_cast<int>(t));
  }
  return out;
}

MeshStats meshStats(const TriMesh& mesh) {
  MeshStats s;
  const int n = mesh.vertexCount();
  s.vertices = n;
  s.triangles = mesh.triangleCount();
  finiteBox(mesh.V, s.bboxMin, s.bboxMax);
  for (int t = 0; t < s.triangles; ++t)
    if (finiteTriangle(mesh.V, mesh.F, t))
      s.area += triangleArea(mesh.V.row(mesh.F(t, 0)), mesh.V.row(mesh.F(t, 1)), mesh.V.row(mesh.F(t, 2)));
  s.degenerateTriangles = static_cast<int>(degenerateTriangles(mesh.V, mesh.F).size());

  const EdgeTable table = buildEdgeTable(mesh.F, n);
  s.edges = static_cast<int>(table.edges.size());
  s.interiorEdges = table.interiorCount;
  s.boundaryEdges = table.boundaryCount;
  s.nonManifoldEdges = table.nonManifoldCount;
  s.inconsistentEdges = table.inconsistentOrientationCount;

  // Components: triangles joined through shared vertices.
  DisjointSets faces(n);
  std::vector<char> used(static_cast<size_t>(n), 0);
  for (int t = 0; t < s.triangles; ++t) {
    for (int j = 0; j < 3; ++j) used[mesh.F(t, j)] = 1;
    faces.unite(mesh.F(t, 0), mesh.F(t, 1));
    faces.unite(mesh.F(t, 0), mesh.F(t, 2));
  }
  for (int i = 0; i < n; ++i)
    if (used[i] && faces.find(i) == i) ++s.components;

  // Boundary loops: connected pieces of the boundary-edge graph. Two loops pinched together at
  // one vertex count as one (no unique way to split them).
  DisjointSets boundary(n);
  std::vector<char> onBoundary(static_cast<size_t>(n), 0);
  for (const Edge& e : table.edges) {
    if (!e.isBoundary()) continue;
    onBoundary[e.v[0]] = onBoundary[e.v[1]] = 1;
    boundary.unite(e.v[0], e.v[1]);
  }
  for (int i = 0; i < n; ++i)
    if (onBoundary[i] && boundary.find(i) == i) ++s.boundaryLoops;
  return s;
}

}  // namespace myo
