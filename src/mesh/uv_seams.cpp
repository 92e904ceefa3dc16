// The UV seam split: one pass over the triangle corners, remembering per mesh vertex which UVs it
// has been given and which output vertex holds each.
#include "myoshell/mesh/uv_seams.h"

#include <utility>

#include "myoshell/core/check.h"

namespace myo {

SeamSplit splitUvSeams(const TriMesh& mesh) {
  return splitUvSeams(mesh.vertexCount(), mesh.F, mesh.UV, mesh.cornerUV);
}

SeamSplit splitUvSeams(int vertexCount, const MatX3i& triangles, const MatX2& vertexUV, const MatX2& cornerUV) {
  const auto n = static_cast<size_t>(vertexCount);
  const Eigen::Index m = triangles.rows();
  MYO_CHECK(vertexUV.rows() == 0 || static_cast<size_t>(vertexUV.rows()) == n,
            "vertexUV must have 0 or " << n << " rows, got " << vertexUV.rows());
  MYO_CHECK(cornerUV.rows() == 0 || cornerUV.rows() == 3 * m,
            "cornerUV must have 0 or " << 3 * m << " rows (3 per triangle), got " << cornerUV.rows());
  MYO_CHECK(m == 0 || (triangles.minCoeff() >= 0 && static_cast<size_t>(triangles.maxCoeff()) < n),
            "triangle indices must lie in [0, " << n << ")");

  SeamSplit split;
  split.sourceVertex.resize(n);
  for (size_t v = 0; v < n; ++v) split.sourceVertex[v] = static_cast<int>(v);
  split.triangles = triangles;
  if (cornerUV.rows() == 0) {
    split.uv = vertexUV;
    return split;
  }

  // uvs[v]: the (UV, output vertex) pairs vertex v has so far; the first is v itself. A linear
  // search is enough: a seam vertex has two or three UVs, rarely more.
  std::vector<std::vector<std::pair<Vec2, int>>> uvs(n);
  std::vector<Vec2> outputUV;
  outputUV.reserve(n);
  for (size_t v = 0; v < n; ++v)
    outputUV.push_back(vertexUV.rows() ? Vec2(vertexUV.row(static_cast<Eigen::Index>(v))) : Vec2::Zero());
  for (Eigen::Index t = 0; t < m; ++t)
    for (int c = 0; c < 3; ++c) {
      const int v = triangles(t, c);
      const Vec2 uv = cornerUV.row(3 * t + c);
      auto& known = uvs[static_cast<size_t>(v)];
      int output = -1;
      for (const auto& [seen, index] : known)
        if (seen == uv) output = index;  // exact: a seam is where the file gives another number
      if (output < 0) {
        output = known.empty() ? v : static_cast<int>(split.sourceVertex.size());
        if (known.empty()) {
          outputUV[static_cast<size_t>(v)] = uv;
        } else {
          split.sourceVertex.push_back(v);
          outputUV.push_back(uv);
        }
        known.emplace_back(uv, output);
      }
      split.triangles(t, c) = output;
    }
  split.uv.resize(static_cast<Eigen::Index>(outputUV.size()), 2);
  for (size_t i = 0; i < outputUV.size(); ++i) split.uv.row(static_cast<Eigen::Index>(i)) = outputUV[i].transpose();
  return split;
}

}  // namespace myo
