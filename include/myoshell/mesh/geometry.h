// Per-element geometry of a triangle mesh: areas, normals, the signed dihedral angle.
#pragma once

#include "myoshell/core/types.h"

namespace myo {

// Area of triangle (a, b, c), cm².
double triangleArea(const Vec3& a, const Vec3& b, const Vec3& c);

// Signed dihedral angle of the hinge (x0, x1, x2, x3) of edge_table.h, radians in (−π, π]:
// θ = atan2((n0 × n1)·ê, n0·n1) with n0 = (x1−x0)×(x2−x0), n1 = (x0−x1)×(x3−x1), ê = (x1−x0)/|x1−x0|.
// 0 when flat; positive on a convex surface with outward normals (METHOD.md §1.1).
double dihedralAngle(const Vec3& x0, const Vec3& x1, const Vec3& x2, const Vec3& x3);

// Per-vertex area-weighted unit normals (n×3) of a mesh.
MatX3 vertexNormals(const MatX3& V, const MatX3i& F);

// Total area of a mesh, cm².
double surfaceArea(const MatX3& V, const MatX3i& F);

}  // namespace myo
