// Where a ray first meets a triangle mesh (Möller & Trumbore 1997, "Fast, minimum storage
// ray–triangle intersection"): brute force over the triangles, for the few queries that need it
// (a muscle anchor whose closest skin lies on a hole's rim, muscle.cpp).
#pragma once

#include <optional>

#include "myoshell/core/types.h"
#include "myoshell/mesh/closest_point.h"

namespace myo {

// The first point of the mesh (V n×3, F m×3) on the ray origin + t·direction, t > 0, as a surface
// point (its normal interpolated from vertexNormals, distance = t·|direction|); none if the ray
// misses every triangle. Of hits at the same t, the lowest triangle index wins.
std::optional<SurfacePoint> firstRayHit(const MatX3& V, const MatX3i& F, const MatX3& vertexNormals, const Vec3& origin,
                                        const Vec3& direction);

}  // namespace myo
