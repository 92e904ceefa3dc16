// Distances and shortest paths along a triangle mesh's edges (Dijkstra 1959): the skin's own
// notion of "near", used where a straight line would cut through the face (between the lips,
// along a lid margin).
#pragma once

#include <vector>

#include "myoshell/mesh/tri_mesh.h"

namespace myo {

// Shortest distances along the mesh's edges (mesh units) from vertex `source` to every vertex;
// +∞ where unreachable.
std::vector<double> surfaceDistances(const TriMesh& mesh, int source);

// The vertices of a shortest edge path from `from` to `to`, both included (just {from} when they
// are equal); empty when `to` cannot be reached.
std::vector<int> shortestEdgePath(const TriMesh& mesh, int from, int to);

}  // namespace myo
