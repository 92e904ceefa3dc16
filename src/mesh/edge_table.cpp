// Edge extraction of thesis Appendix I (Algorithm 1), done with one hash map instead of a sort.
#include "myoshell/mesh/edge_table.h"

#include <unordered_map>

#include "myoshell/core/check.h"

namespace myo {

EdgeTable buildEdgeTable(const MatX3i& F, int vertexCount) {
  EdgeTable table;
  table.edges.reserve(static_cast<size_t>(F.rows()) * 3 / 2 + 8);
  // Undirected edge key → index into table.edges.
  std::unordered_map<uint64_t, int> index;
  index.reserve(static_cast<size_t>(F.rows()) * 2);
  std::vector<int> faceCount;  // faces seen per edge (> 2 means non-manifold)
  auto key = [](int a, int b) {
    const auto lo = static_cast<uint64_t>(std::min(a, b)), hi = static_cast<uint64_t>(std::max(a, b));
    return (lo << 32) | hi;
  };
  for (int t = 0; t < F.rows(); ++t) {
    for (int j = 0; j < 3; ++j) {
      const int a = F(t, j), b = F(t, (j + 1) % 3), opposite = F(t, (j + 2) % 3);
      MYO_CHECK(a >= 0 && a < vertexCount && b >= 0 && b < vertexCount,
                "triangle " << t << " has a vertex index outside [0, " << vertexCount << ")");
      auto [it, inserted] = index.try_emplace(key(a, b), static_cast<int>(table.edges.size()));
      if (inserted) {
        Edge e;
        e.v = {a, b, opposite, -1};  // the first face fixes the direction v0→v1
        e.face = {t, -1};
        table.edges.push_back(e);
        faceCount.push_back(1);
        continue;
      }
      Edge& e = table.edges[it->second];
      const int seen = ++faceCount[it->second];
      if (seen == 2) {
        e.v[3] = opposite;
        e.face[1] = t;
        // A consistently oriented neighbour runs the shared edge the other way (b→a).
        if (a == e.v[0]) {
          ++table.inconsistentOrientationCount;
          if (table.firstInconsistent[0] < 0) table.firstInconsistent = {e.v[0], e.v[1]};
        }
      } else if (seen == 3) {
        ++table.nonManifoldCount;
        if (table.firstNonManifold[0] < 0) table.firstNonManifold = {e.v[0], e.v[1]};
      }
    }
  }
  for (const Edge& e : table.edges) (e.isBoundary() ? table.boundaryCount : table.interiorCount)++;
  return table;
}

}  // namespace myo
