#include "myoshell/mesh/subdivision.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <unordered_map>

#include "myoshell/core/check.h"

namespace myo {

namespace {

std::uint64_t edgeKey(int a, int b) {
  if (a > b) std::swap(a, b);
  return (static_cast<std::uint64_t>(a) << 32) | static_cast<std::uint32_t>(b);
}

struct EdgeInfo {
  int a = -1, b = -1;        // end points (as first met)
  int opp[2] = {-1, -1};     // opposite vertices of the (up to) two faces
  int faces = 0;             // number of faces using the edge
};

}  // namespace

std::vector<std::vector<int>> boundaryLoops(const MatX3i& F, int vertexCount) {
  std::unordered_map<std::uint64_t, int> count;
  count.reserve(static_cast<size_t>(F.rows()) * 3);
  for (int t = 0; t < F.rows(); ++t)
    for (int k = 0; k < 3; ++k) ++count[edgeKey(F(t, k), F(t, (k + 1) % 3))];
  // Directed boundary half-edges a→b as the triangles traverse them.
  std::vector<std::vector<int>> out(static_cast<size_t>(vertexCount));
  int remaining = 0;
  for (int t = 0; t < F.rows(); ++t)
    for (int k = 0; k < 3; ++k) {
      const int a = F(t, k), b = F(t, (k + 1) % 3);
      if (count[edgeKey(a, b)] == 1) {
        out[a].push_back(b);
        ++remaining;
      }
    }
  std::vector<std::vector<int>> loops;
  for (int s = 0; s < vertexCount && remaining > 0; ++s) {
    while (!out[s].empty()) {
      std::vector<int> loop{s};
      int v = s;
      for (;;) {
        MYO_CHECK(!out[v].empty(), "boundary not closed at vertex " << v
                                       << " (non-manifold or inconsistently oriented mesh)");
        const int next = out[v].back();
        out[v].pop_back();
        --remaining;
        if (next == s) break;
        loop.push_back(next);
        v = next;
      }
      loops.push_back(std::move(loop));
    }
  }
  std::stable_sort(loops.begin(), loops.end(),
                   [](const auto& x, const auto& y) { return x.size() > y.size(); });
  return loops;
}

TriMesh loopSubdivide(const TriMesh& mesh, const LoopOptions& options) {
  const int n = mesh.vertexCount();
  const int m = mesh.triangleCount();
  const MatX3& V = mesh.V;
  const MatX3i& F = mesh.F;

  // Edges in order of first appearance, and each triangle's three edge ids.
  std::unordered_map<std::uint64_t, int> edgeId;
  edgeId.reserve(static_cast<size_t>(m) * 2);
  std::vector<EdgeInfo> edges;
  edges.reserve(static_cast<size_t>(m) * 3 / 2 + 16);
  MatX3i triEdges(m, 3);
  for (int t = 0; t < m; ++t)
    for (int k = 0; k < 3; ++k) {
      const int a = F(t, k), b = F(t, (k + 1) % 3), c = F(t, (k + 2) % 3);
      auto [it, inserted] = edgeId.try_emplace(edgeKey(a, b), static_cast<int>(edges.size()));
      if (inserted) {
        EdgeInfo e;
        e.a = a;
        e.b = b;
        edges.push_back(e);
      }
      EdgeInfo& e = edges[static_cast<size_t>(it->second)];
      MYO_CHECK(e.faces < 2, "loopSubdivide: edge (" << a << ", " << b
                                 << ") has more than two faces (non-manifold mesh)");
      e.opp[e.faces++] = c;
      triEdges(t, k) = it->second;
    }
  const int ne = static_cast<int>(edges.size());

  // Neighbours of each vertex, and its boundary neighbours.
  std::vector<std::vector<int>> nbr(static_cast<size_t>(n)), bnbr(static_cast<size_t>(n));
  for (const EdgeInfo& e : edges) {
    nbr[e.a].push_back(e.b);
    nbr[e.b].push_back(e.a);
    if (e.faces == 1) {
      bnbr[e.a].push_back(e.b);
      bnbr[e.b].push_back(e.a);
    }
  }

  TriMesh out;
  out.V.resize(n + ne, 3);
  const double cosCorner = std::cos(options.cornerAngleDegrees * std::numbers::pi / 180.0);
  for (int i = 0; i < n; ++i) {
    const Vec3 v = V.row(i);
    const auto& bn = bnbr[static_cast<size_t>(i)];
    const auto& nb = nbr[static_cast<size_t>(i)];
    if (nb.empty()) {  // isolated vertex
      out.V.row(i) = v;
    } else if (!bn.empty()) {  // boundary vertex: crease rule
      bool corner = !options.smoothBoundary || bn.size() != 2;
      if (!corner) {
        const Vec3 din = v - Vec3(V.row(bn[0]));
        const Vec3 dout = Vec3(V.row(bn[1])) - v;
        const double l = din.norm() * dout.norm();
        // Turning angle > cornerAngle ⇔ cos(turn) < cos(cornerAngle).
        corner = l <= 0.0 || din.dot(dout) / l < cosCorner;
      }
      if (corner)
        out.V.row(i) = v;
      else
        out.V.row(i) = 0.75 * v + 0.125 * (Vec3(V.row(bn[0])) + Vec3(V.row(bn[1])));
    } else {  // interior vertex: Loop's rule
      const double k = static_cast<double>(nb.size());
      const double c = 0.375 + 0.25 * std::cos(2.0 * std::numbers::pi / k);
      const double beta = (0.625 - c * c) / k;
      Vec3 sum = Vec3::Zero();
      for (int j : nb) sum += V.row(j);
      out.V.row(i) = (1.0 - k * beta) * v + beta * sum;
    }
  }
  for (int e = 0; e < ne; ++e) {
    const EdgeInfo& ed = edges[static_cast<size_t>(e)];
    const Vec3 a = V.row(ed.a), b = V.row(ed.b);
    if (ed.faces == 2)
      out.V.row(n + e) = 0.375 * (a + b) + 0.125 * (Vec3(V.row(ed.opp[0])) + Vec3(V.row(ed.opp[1])));
    else
      out.V.row(n + e) = 0.5 * (a + b);
  }

  out.F.resize(4 * m, 3);
  for (int t = 0; t < m; ++t) {
    const int v0 = F(t, 0), v1 = F(t, 1), v2 = F(t, 2);
    const int e01 = n + triEdges(t, 0), e12 = n + triEdges(t, 1), e20 = n + triEdges(t, 2);
    out.F.row(4 * t + 0) << v0, e01, e20;
    out.F.row(4 * t + 1) << v1, e12, e01;
    out.F.row(4 * t + 2) << v2, e20, e12;
    out.F.row(4 * t + 3) << e01, e12, e20;
  }

  if (mesh.UV.rows() == n) {
    out.UV.resize(n + ne, 2);
    out.UV.topRows(n) = mesh.UV;
    for (int e = 0; e < ne; ++e)
      out.UV.row(n + e) = 0.5 * (mesh.UV.row(edges[static_cast<size_t>(e)].a) +
                                 mesh.UV.row(edges[static_cast<size_t>(e)].b));
  }
  // Corner UVs follow each triangle's own corners, so a seam stays a seam: an edge point's UV is
  // the midpoint of its triangle's two corner UVs (the same on both sides of an edge that is not a
  // seam, since 0.5·(a + b) = 0.5·(b + a) exactly in floating point).
  if (mesh.hasCornerUV()) {
    out.cornerUV.resize(12 * m, 2);
    for (int t = 0; t < m; ++t) {
      const Vec2 u0 = mesh.cornerUV.row(3 * t), u1 = mesh.cornerUV.row(3 * t + 1), u2 = mesh.cornerUV.row(3 * t + 2);
      const Vec2 m01 = 0.5 * (u0 + u1), m12 = 0.5 * (u1 + u2), m20 = 0.5 * (u2 + u0);
      const Vec2 corners[12] = {u0, m01, m20, u1, m12, m01, u2, m20, m12, m01, m12, m20};
      for (int k = 0; k < 12; ++k) out.cornerUV.row(12 * t + k) = corners[k].transpose();
    }
  }
  out.groups = mesh.groups;
  out.sourcePath = mesh.sourcePath;
  return out;
}

TriMesh loopSubdivide(const TriMesh& mesh, int levels, const LoopOptions& options) {
  MYO_CHECK_GE(levels, 0);
  TriMesh out = mesh;
  for (int l = 0; l < levels; ++l) out = loopSubdivide(out, options);
  return out;
}

}  // namespace myo
