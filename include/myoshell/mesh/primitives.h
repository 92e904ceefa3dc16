// Meshes generated in code: for tests, benchmarks, validation cases and the demo.
#pragma once

#include "myoshell/mesh/tri_mesh.h"

namespace myo {

// A flat rectangular grid in the xy-plane, [0, length] × [0, width], with (nx+1)×(ny+1) vertices,
// vertex (i, j) at index j·(nx+1) + i; each cell split into two triangles, normals +z.
// Alternating diagonals (alternate = true) avoid the one-directional bias of a uniform split.
TriMesh gridMesh(double length, double width, int nx, int ny, bool alternate = true);

// A closed icosphere of the given radius centred at the origin, outward normals; subdivisions = 0
// gives the 12-vertex icosahedron, each level multiplies the triangles by 4.
TriMesh icosphere(double radius, int subdivisions);

}  // namespace myo
