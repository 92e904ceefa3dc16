// Closest points on a triangle mesh: brute force over the triangles (closestSurfacePoint), or a
// SurfaceLocator that builds a bounding-box tree once and answers each query with the same result
// bit for bit, visiting only the triangles that could be closest (build time only, both).
#pragma once

#include <vector>

#include <Eigen/Geometry>

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
// Of equally close triangles, the lowest index wins.
SurfacePoint closestSurfacePoint(const MatX3& V, const MatX3i& F, const MatX3& vertexNormals, const Vec3& p);

// Closest points on one mesh, many queries: an axis-aligned bounding-box tree over the triangles
// (leaves of ≤ 8), built once in O(m log m). closest(p) equals closestSurfacePoint(V, F,
// vertexNormals, p) exactly — the same triangle (lowest index among equally close ones), the same
// barycentric coordinates, point, normal and distance — since it evaluates each triangle it visits
// with the same arithmetic and skips a box only when the box is farther than the best so far by
// more than round-off (1e-9 × the mesh's extent). Copies the mesh.
class SurfaceLocator {
 public:
  SurfaceLocator(MatX3 V, MatX3i F, MatX3 vertexNormals);
  SurfacePoint closest(const Vec3& p) const;
  const MatX3& vertices() const { return V_; }          // n×3, cm
  const MatX3i& triangles() const { return F_; }        // m×3
  const MatX3& vertexNormals() const { return N_; }     // n×3, unit

 private:
  struct Node {
    Eigen::AlignedBox3d box;
    int first = 0, count = 0;  // leaf: order_[first, first + count)
    int left = -1, right = -1; // inner node: children (left < 0 for a leaf)
  };
  int build(int first, int count);
  MatX3 V_;
  MatX3i F_;
  MatX3 N_;
  std::vector<int> order_;   // triangle indices, grouped by leaf
  std::vector<Node> nodes_;  // nodes_[0] the root
  double slack_ = 0.0;       // cm: a box is skipped only when farther than best + slack
};

// Index of the vertex of V nearest to p (ties: the lowest index).
int nearestVertex(const MatX3& V, const Vec3& p);

}  // namespace myo
