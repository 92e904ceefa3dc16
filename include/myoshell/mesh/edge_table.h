// The edge table of thesis Appendix I (Algorithm 1): each edge with the four vertex indices a
// hinge needs, and the faces it borders.
#pragma once

#include <array>
#include <vector>

#include "myoshell/core/types.h"

namespace myo {

// One edge. v[0]→v[1] is the direction in which the edge runs in its first face face[0], so that
// face[0] = (v[0], v[1], v[2]) counter-clockwise; v[3] is the opposite vertex of the second face
// face[1] = (v[1], v[0], v[3]), or -1 on a boundary (Appendix I; METHOD.md §1.1 — Algorithm 1's
// line 16 writes id[2] twice, the second is id[3]).
struct Edge {
  std::array<int, 4> v{-1, -1, -1, -1};
  std::array<int, 2> face{-1, -1};
  bool isBoundary() const { return face[1] < 0; }
};

struct EdgeTable {
  std::vector<Edge> edges;  // interior and boundary edges, ordered by first appearance in F
  int interiorCount = 0;
  int boundaryCount = 0;
  // Edges used by more than two faces. Strict builds reject them; lenient builds (info) count them
  // and keep only their first two faces.
  int nonManifoldCount = 0;
  // Interior edges whose two faces traverse them in the same direction (inconsistent orientation).
  int inconsistentOrientationCount = 0;
  // First offending edge of each kind, for error messages ({-1,-1} when none).
  std::array<int, 2> firstNonManifold{-1, -1};
  std::array<int, 2> firstInconsistent{-1, -1};
};

// Builds the edge table of triangles F (m×3) over n vertices. Never throws on topology faults; it
// counts them (see validateTopology in obj_reader.h for the strict path).
EdgeTable buildEdgeTable(const MatX3i& F, int vertexCount);

}  // namespace myo
