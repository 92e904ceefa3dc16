// The thesis's Table 1 for any mesh, and more: counts, topology, bounding box, area.
#pragma once

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

}  // namespace myo
