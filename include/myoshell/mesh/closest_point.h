// Closest points on a triangle mesh (brute force over the triangles: used at build time only).
#pragma once

#include "myoshell/core/types.h"

namespace myo {

struct SurfacePoint {
  Vec3 point = Vec3::Zero();   // closest point on the surface, cm
  Vec3 normal = Vec3::UnitZ(); // unit normal there, interpolated from vertex normals
  int triangle = -1;           // triangle it lies on
  Vec3 barycentric = Vec3::Zero();
  double distance = 0.0;       // |p − point|, cm
};

// Closest point of triangle (a, b, c) to p, as barycentric coordinates (u, v, w), u+v+w = 1.
Vec3 closestPointBarycentric(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c);

// Closest point of the mesh (V n×3, F m×3) to p; vertexNormals: n×3 unit normals of the mesh.
SurfacePoint closestSurfacePoint(const MatX3& V, const MatX3i& F, const MatX3& vertexNormals, const Vec3& p);

// Index of the vertex of V nearest to p (ties: the lowest index).
int nearestVertex(const MatX3& V, const Vec3& p);

}  // namespace myo
