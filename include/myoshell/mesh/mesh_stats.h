// The thesis's Table 1 for any mesh, and more: counts, topology, bounding box, area.
#pragma once

#include <vector>

#include "myoshell/core/types.h"
#include "myoshell/mesh/tri_mesh.h"

namespace myo {

struct MeshStats {
  int vertices = 0;
  int triangles = 0;
  int edges = 0;
  int interiorEdges = 0;
  int boundaryEdges = 0;
  int boundaryLoops = 0;
  int components = 0;  // connected components over the triangles (isolated vertices not counted)
  int nonManifoldEdges = 0;
  int degenerateTriangles = 0;
  int inconsistentEdges = 0;
  Vec3 bboxMin = Vec3::Zero();  // cm
  Vec3 bboxMax = Vec3::Zero();  // cm
  double area = 0.0;            // cm²
};

MeshStats meshStats(const TriMesh& mesh);

// A triangle is degenerate when its area is at most this fraction of the squared bounding-box
// diagonal (scale-free, so it means the same for a mesh in cm or in m).
constexpr double kDegenerateAreaTolerance = 1e-12;

// Indices of the degenerate triangles of (V, F), ascending. Triangles with a non-finite corner are
// not counted (they are reported as non-finite coordinates); the bbox is over finite vertices.
std::vector<int> degenerateTriangles(const MatX3& V, const MatX3i& F);

}  // namespace myo
