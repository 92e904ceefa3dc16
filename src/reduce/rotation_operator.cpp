#include "myoshell/reduce/rotation_operator.h"

#include <Eigen/Geometry>

#include "myoshell/core/check.h"

namespace myo {

namespace {
Mat3 cross(const Vec3& a) {
  Mat3 m;
  m << 0, -a.z(), a.y(), a.z(), 0, -a.x(), -a.y(), a.x(), 0;
  return m;
}

std::vector<int> incidentCounts(const MatX3i& F, int n) {
  std::vector<int> count(n, 0);
  for (Eigen::Index t = 0; t < F.rows(); ++t)
    for (int k = 0; k < 3; ++k) ++count[F(t, k)];
  return count;
}
}  // namespace

std::array<Mat3, 3> triangleRotationBlocks(const Vec3& X0, const Vec3& X1, const Vec3& X2) {
  const Vec3 X[3] = {X0, X1, X2};
  Vec3 nn = (X1 - X0).cross(X2 - X0);
  const double twoA = nn.norm();
  MYO_CHECK(twoA > 0.0, "degenerate triangle in the rotation operator");
  const Vec3 n = nn / twoA;
  std::array<Mat3, 3> B;
  for (int k = 0; k < 3; ++k) {
    const Vec3 gradN = n.cross(X[(k + 2) % 3] - X[(k + 1) % 3]) / twoA;
    B[k] = 0.5 * n * (n.transpose() * cross(gradN)) - n.cross(gradN) * n.transpose();
  }
  return B;
}

SparseMat rotationOperator(const MatX3& rest, const MatX3i& F) {
  const int n = static_cast<int>(rest.rows());
  const std::vector<int> count = incidentCounts(F, n);
  std::vector<Triplet> trip;
  trip.reserve(F.rows() * 81);
  for (Eigen::Index t = 0; t < F.rows(); ++t) {
    const auto B = triangleRotationBlocks(rest.row(F(t, 0)).transpose(), rest.row(F(t, 1)).transpose(),
                                          rest.row(F(t, 2)).transpose());
    for (int a = 0; a < 3; ++a) {
      const int i = F(t, a);
      const double wgt = 1.0 / count[i];
      for (int k = 0; k < 3; ++k)
        for (int r = 0; r < 3; ++r)
          for (int c = 0; c < 3; ++c)
            trip.emplace_back(3 * i + r, 3 * F(t, k) + c, wgt * B[k](r, c));
    }
  }
  SparseMat W(3 * n, 3 * n);
  W.setFromTriplets(trip.begin(), trip.end());
  return W;
}

MatX3 nodalRotations(const MatX3& rest, const MatX3i& F, const MatX3& u) {
  MYO_CHECK_EQ(u.rows(), rest.rows());
  const int n = static_cast<int>(rest.rows());
  const std::vector<int> count = incidentCounts(F, n);
  MatX3 w = MatX3::Zero(n, 3);
  for (Eigen::Index t = 0; t < F.rows(); ++t) {
    const auto B = triangleRotationBlocks(rest.row(F(t, 0)).transpose(), rest.row(F(t, 1)).transpose(),
                                          rest.row(F(t, 2)).transpose());
    Vec3 wt = Vec3::Zero();
    for (int k = 0; k < 3; ++k) wt += B[k] * u.row(F(t, k)).transpose();
    for (int a = 0; a < 3; ++a) w.row(F(t, a)) += wt.transpose() / count[F(t, a)];
  }
  return w;
}

MatX modalRotationMatrix(const MatX3& rest, const MatX3i& F, const std::vector<int>& freeVertices,
                         const MatX& Phi) {
  const int n = static_cast<int>(rest.rows());
  const int f = static_cast<int>(freeVertices.size());
  MYO_CHECK_EQ(Phi.rows(), static_cast<Eigen::Index>(3 * f));
  const Eigen::Index d = Phi.cols();
  std::vector<int> toFree(n, -1);
  for (int i = 0; i < f; ++i) toFree[freeVertices[i]] = i;
  const std::vector<int> count = incidentCounts(F, n);
  MatX Psi = MatX::Zero(3 * f, d);
  MatX wt(3, d);
  for (Eigen::Index t = 0; t < F.rows(); ++t) {
    const int fi[3] = {toFree[F(t, 0)], toFree[F(t, 1)], toFree[F(t, 2)]};
    if (fi[0] < 0 && fi[1] < 0 && fi[2] < 0) continue;
    const auto B = triangleRotationBlocks(rest.row(F(t, 0)).transpose(), rest.row(F(t, 1)).transpose(),
                                          rest.row(F(t, 2)).transpose());
    wt.setZero();
    for (int k = 0; k < 3; ++k)
      if (fi[k] >= 0) wt.noalias() += B[k] * Phi.middleRows(3 * fi[k], 3);  // pinned: u = 0
    for (int a = 0; a < 3; ++a)
      if (fi[a] >= 0) Psi.middleRows(3 * fi[a], 3) += wt / count[F(t, a)];
  }
  return Psi;
}

Mat3 rotationFromVector(const Vec3& w) {
  const auto c = rotationCoefficients(w.squaredNorm());
  const Mat3 W = cross(w);
  return Mat3::Identity() + c.s * W + c.a * W * W;
}

Vec3 rotationVector(const Mat3& R) {
  const Eigen::AngleAxisd aa(R);
  return aa.angle() * aa.axis();
}

Mat3 warpMatrix(const Vec3& w) {
  const auto c = rotationCoefficients(w.squaredNorm());
  const Mat3 W = cross(w);
  return Mat3::Identity() + c.a * W + c.b * W * W;
}

}  // namespace myo
