// Splitting a mesh along its UV seams, for formats that hold one texture coordinate per vertex
// (glTF): a vertex whose corners carry several distinct UVs (TriMesh::cornerUV) becomes the vertex
// itself plus one appended duplicate per further UV, and the triangles are re-indexed to them.
#pragma once

#include <vector>

#include "myoshell/core/types.h"
#include "myoshell/mesh/tri_mesh.h"

namespace myo {

struct SeamSplit {
  // For each output vertex, the mesh vertex it copies: the first n are 0 … n−1 (the mesh's own
  // vertices, in order), duplicates follow.
  std::vector<int> sourceVertex;
  MatX3i triangles;  // m×3, the mesh's triangles (same order, same winding) over the output vertices
  MatX2 uv;          // one row per output vertex (OBJ convention), or 0×2 when the mesh has no UVs

  int vertexCount() const { return static_cast<int>(sourceVertex.size()); }
  int duplicateCount(int meshVertexCount) const { return vertexCount() - meshVertexCount; }
};

// The split of `mesh`. With cornerUV: vertex v keeps the UV of the first corner (triangle by
// triangle, corners in order) that names it, and each further distinct UV at v (exact equality)
// gets one duplicate, appended in order of first appearance; a vertex no triangle names keeps
// mesh.UV's row (zero without UVs). Without cornerUV: no duplicates, uv = mesh.UV.
// CheckError when cornerUV has neither 0 nor 3m rows.
SeamSplit splitUvSeams(const TriMesh& mesh);

// The same over the arrays: vertexUV (n×2 or 0×2) and cornerUV (3m×2 or 0×2) as in TriMesh.
SeamSplit splitUvSeams(int vertexCount, const MatX3i& triangles, const MatX2& vertexUV, const MatX2& cornerUV);

// Rows of `perVertex` (n×k, per mesh vertex) copied to the split's output vertices.
template <typename Matrix>
Matrix expandToSplit(const SeamSplit& split, const Matrix& perVertex) {
  Matrix out(static_cast<Eigen::Index>(split.sourceVertex.size()), perVertex.cols());
  for (size_t i = 0; i < split.sourceVertex.size(); ++i)
    out.row(static_cast<Eigen::Index>(i)) = perVertex.row(split.sourceVertex[i]);
  return out;
}

}  // namespace myo
