// Loop subdivision (Loop 1987) with the boundary kept as a crease (Hoppe et al. 1994), and the
// boundary loops it relies on.
#pragma once

#include <vector>

#include "myoshell/core/types.h"
#include "myoshell/mesh/tri_mesh.h"

namespace myo {

struct LoopOptions {
  // true: a boundary is a smooth crease, subdivided as a cubic B-spline curve of its own vertices
  // (vertex 3/4·v + 1/8·(a + b) with a, b its boundary neighbours; edge point (a + b)/2), so the
  // boundary never depends on the interior. false: boundary vertices stay where they are and edge
  // points are midpoints, so the boundary stays exactly on its original polyline.
  bool smoothBoundary = true;
  // A boundary vertex whose boundary turns by more than this angle (degrees, between the incoming
  // and the outgoing boundary edge) is a corner and stays fixed. So do boundary vertices with more
  // than two boundary edges (non-manifold vertices). 60° keeps a grid's corners and a mouth's
  // corners sharp while smoothing a gently curved rim.
  double cornerAngleDegrees = 60.0;
};

// One Loop subdivision step. Vertex i of the result is the updated vertex i of the input (original
// ids kept, first); vertex n + e is the point of edge e, edges numbered in order of first appearance
// in F (triangle by triangle, edges (0,1), (1,2), (2,0)). Triangle t becomes triangles 4t … 4t+3:
// (v0, e01, e20), (v1, e12, e01), (v2, e20, e12), (e01, e12, e20) — orientation kept.
// Interior vertices: (1 − nβ)·v + β·Σ neighbours, β = (5/8 − (3/8 + cos(2π/n)/4)²)/n (Loop);
// interior edge points 3/8·(a + b) + 1/8·(c + d). UVs, when present, are interpolated linearly
// (per vertex, and per corner within each triangle so that UV seams stay seams).
// Groups keep the original vertex ids; sourcePolygon and polygons are dropped. Vertex count of
// the result: V + E.
TriMesh loopSubdivide(const TriMesh& mesh, const LoopOptions& options = {});

// `levels` steps of loopSubdivide.
TriMesh loopSubdivide(const TriMesh& mesh, int levels, const LoopOptions& options = {});

// The boundary loops of triangles F (m×3) over vertexCount vertices: each loop a list of vertex ids
// in the order in which its triangles traverse the boundary edges (so the surface lies to the left
// walking along a loop with the normal up), starting at its smallest vertex id; loops sorted by
// decreasing length in edges (ties: smallest start first). Requires an edge-manifold mesh with
// consistently oriented triangles; a vertex on two boundary loops (pinched) is followed in order.
std::vector<std::vector<int>> boundaryLoops(const MatX3i& F, int vertexCount);

}  // namespace myo
