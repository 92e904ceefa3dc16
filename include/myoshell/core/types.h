// Scalar, vector and matrix types used across Myoshell. Units are cm–g–s everywhere (DESIGN.md).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <Eigen/SparseCore>

namespace myo {

using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using VecX = Eigen::VectorXd;
using MatX = Eigen::MatrixXd;
using VecXi = Eigen::VectorXi;

// Per-vertex positions or displacements: n×3, one row per vertex, row-major so that the 3n
// vector (x0, y0, z0, x1, …) of the physics is a plain Map over the same memory.
using MatX3 = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;
// Triangles: m×3 vertex indices, one row per triangle, counter-clockwise seen from outside.
using MatX3i = Eigen::Matrix<int, Eigen::Dynamic, 3, Eigen::RowMajor>;
// Per-vertex texture coordinates: n×2 (empty when the mesh has none).
using MatX2 = Eigen::Matrix<double, Eigen::Dynamic, 2, Eigen::RowMajor>;

using SparseMat = Eigen::SparseMatrix<double>;
using Triplet = Eigen::Triplet<double>;

// The 3n-vector view of an n×3 row-major matrix (no copy).
inline Eigen::Map<VecX> flat(MatX3& m) { return Eigen::Map<VecX>(m.data(), m.size()); }
inline Eigen::Map<const VecX> flat(const MatX3& m) {
  return Eigen::Map<const VecX>(m.data(), m.size());
}
// The n×3 view of a 3n-vector (no copy).
inline Eigen::Map<MatX3> rows3(VecX& v) { return Eigen::Map<MatX3>(v.data(), v.size() / 3, 3); }
inline Eigen::Map<const MatX3> rows3(const VecX& v) {
  return Eigen::Map<const MatX3>(v.data(), v.size() / 3, 3);
}

}  // namespace myo
