// Where a line or a ray meets triangles (Möller & Trumbore 1997, "Fast, minimum storage ray–triangle
// intersection"): one triangle, and brute force over a mesh's triangles for the few queries that
// need it (a muscle anchor whose closest skin lies on a hole's rim, muscle.cpp; the viewer's pick;
// the automatic landmarks' frontal view).
#pragma once

#include <optional>

#include "myoshell/core/types.h"
#include "myoshell/mesh/closest_point.h"

namespace myo {

// Where the line origin + t·direction meets triangle (a, b, c): its t (either sign) and the
// barycentric weights (1 − u − v, u, v) of the point; none when it misses the triangle or runs
// parallel to its plane.
struct LineTriangleHit {
  double t = 0.0, u = 0.0, v = 0.0;
};
std::optional<LineTriangleHit> lineMeetsTriangle(const Vec3& origin, const Vec3& direction, const Vec3& a, const Vec3& b,
                                                 const Vec3& c);

// The first point of the mesh (V n×3, F m×3) on the ray origin + t·direction, t > 0, as a surface
// point (its normal interpolated from vertexNormals, distance = t·|direction|); none if the ray
// misses every triangle. Of hits at the same t, the lowest triangle index wins.
std::optional<SurfacePoint> firstRayHit(const MatX3& V, const MatX3i& F, const MatX3& vertexNormals, const Vec3& origin,
                                        const Vec3& direction);

}  // namespace myo
