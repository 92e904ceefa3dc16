// The shell rotation operator W (METHOD.md §3.2) and the rotation formulas of modal warping.
#include <gtest/gtest.h>

#include <Eigen/SVD>
#include <random>

#include "myoshell/mesh/primitives.h"
#include "myoshell/reduce/rotation_operator.h"

namespace myo {
namespace {

Mat3 skew(const Vec3& a) {
  Mat3 m;
  m << 0, -a.z(), a.y(), a.z(), 0, -a.x(), -a.y(), a.x(), 0;
  return m;
}

TriMesh bumpyPatch() {
  TriMesh m = gridMesh(4.0, 3.0, 8, 6);
  for (Eigen::Index i = 0; i < m.V.rows(); ++i)
    m.V(i, 2) = 0.3 * std::sin(m.V(i, 0)) * std::cos(0.7 * m.V(i, 1));
  return m;
}

TEST(RotationOperator, InfinitesimalRigidRotationGivesOmegaEverywhere) {
  const Vec3 omega(0.3, -1.2, 0.7);
  for (const TriMesh& m : {icosphere(2.0, 2), bumpyPatch()}) {
    MatX3 u(m.vertexCount(), 3);
    for (int i = 0; i < m.vertexCount(); ++i) u.row(i) = omega.cross(Vec3(m.V.row(i))).transpose();
    const MatX3 w = nodalRotations(m.V, m.F, u);
    for (int i = 0; i < m.vertexCount(); ++i)
      EXPECT_LT((Vec3(w.row(i)) - omega).norm(), 1e-12) << "vertex " << i;
    // The sparse operator gives the same thing.
    const SparseMat W = rotationOperator(m.V, m.F);
    const VecX wv = W * VecX(flat(u));
    EXPECT_LT((wv - VecX(flat(w))).cwiseAbs().maxCoeff(), 1e-13);
  }
}

TEST(RotationOperator, TranslationGivesNoRotation) {
  const TriMesh m = bumpyPatch();
  MatX3 u = MatX3::Zero(m.vertexCount(), 3);
  u.rowwise() += Eigen::RowVector3d(0.2, -0.5, 1.5);
  EXPECT_LT(nodalRotations(m.V, m.F, u).cwiseAbs().maxCoeff(), 1e-13);
}

// The triangle's rotation from its 3-D deformation gradient F_t (edges and unit normal mapped),
// through the polar decomposition.
Vec3 polarRotationVector(const Vec3 X[3], const Vec3 x[3]) {
  const auto frame = [](const Vec3 p[3]) {
    Mat3 E;
    const Vec3 e1 = p[1] - p[0], e2 = p[2] - p[0];
    E << e1, e2, e1.cross(e2).normalized();
    return E;
  };
  const Mat3 Ft = frame(x) * frame(X).inverse();
  Eigen::JacobiSVD<Mat3> svd(Ft, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Mat3 R = svd.matrixU() * svd.matrixV().transpose();
  return rotationVector(R);
}

TEST(RotationOperator, AgreesWithPolarRotationToFirstOrder) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  const Vec3 X[3] = {Vec3(0.1, 0.2, 0.0), Vec3(1.3, 0.1, 0.4), Vec3(0.4, 1.1, -0.2)};
  const auto B = triangleRotationBlocks(X[0], X[1], X[2]);
  for (int trial = 0; trial < 5; ++trial) {
    Vec3 dU[3];
    for (auto& d : dU) d = Vec3(U(rng), U(rng), U(rng));
    double prevRel = 0.0;
    for (double eps : {1e-2, 1e-3, 1e-4, 1e-5}) {
      Vec3 x[3];
      Vec3 wLin = Vec3::Zero();
      for (int k = 0; k < 3; ++k) {
        x[k] = X[k] + eps * dU[k];
        wLin += B[k] * (eps * dU[k]);
      }
      const Vec3 wTrue = polarRotationVector(X, x);
      const double rel = (wLin - wTrue).norm() / wTrue.norm();
      EXPECT_LT(rel, 50.0 * eps) << "eps " << eps;  // the error is O(ε) relative
      if (prevRel > 0.0) EXPECT_LT(rel, 0.2 * prevRel);  // and shrinks with ε
      prevRel = rel;
    }
  }
}

TEST(RotationOperator, ModalRotationMatrixIsWPhiWithPinnedRowsZero) {
  const TriMesh m = bumpyPatch();
  const int n = m.vertexCount();
  std::vector<int> free;
  for (int i = 0; i < n; ++i)
    if (i % 9 != 0) free.push_back(i);
  const int f = static_cast<int>(free.size());
  std::mt19937 rng(3);
  std::normal_distribution<double> N01;
  MatX Phi(3 * f, 4);
  for (Eigen::Index i = 0; i < Phi.size(); ++i) Phi.data()[i] = N01(rng);
  const MatX Psi = modalRotationMatrix(m.V, m.F, free, Phi);
  // Reference: scatter Φ to the full mesh (zeros on pins), apply W, gather the free rows.
  MatX full = MatX::Zero(3 * n, 4);
  for (int i = 0; i < f; ++i) full.middleRows(3 * free[i], 3) = Phi.middleRows(3 * i, 3);
  const MatX Wfull = rotationOperator(m.V, m.F) * full;
  for (int i = 0; i < f; ++i)
    EXPECT_LT((Psi.middleRows(3 * i, 3) - Wfull.middleRows(3 * free[i], 3)).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(RotationFormulas, RodriguesMatchesAngleAxisAndLogInverts) {
  for (const Vec3& w : {Vec3(0, 0, 0), Vec3(1e-9, 0, 2e-9), Vec3(0.3, 0.1, -0.2), Vec3(0.4, 0.2, 0.1),
                        Vec3(1.0, -2.0, 0.5), Vec3(0, 3.0, 0)}) {
    const Mat3 R = rotationFromVector(w);
    const Mat3 ref = w.norm() > 0 ? Eigen::AngleAxisd(w.norm(), w.normalized()).toRotationMatrix()
                                  : Mat3::Identity();
    EXPECT_LT((R - ref).cwiseAbs().maxCoeff(), 1e-15 * 8);
    EXPECT_LT((R.transpose() * R - Mat3::Identity()).cwiseAbs().maxCoeff(), 1e-14);
    if (w.norm() < 3.1) EXPECT_LT((rotationVector(R) - w).norm(), 1e-12);
  }
}

TEST(RotationFormulas, WarpMatrixIsTheIntegralOfTheRotation) {
  for (const Vec3& w : {Vec3(1e-6, 0, 0), Vec3(0.2, 0.3, 0.1), Vec3(0.35, 0.0, 0.35), Vec3(1.0, -2.0, 0.5)}) {
    // Composite Simpson on ∫₀¹ exp(s[w]×) ds.
    const int N = 2000;
    Mat3 S = Mat3::Zero();
    for (int k = 0; k <= N; ++k) {
      const double c = (k == 0 || k == N) ? 1.0 : (k % 2 ? 4.0 : 2.0);
      S += c * rotationFromVector(double(k) / N * w);
    }
    S /= 3.0 * N;
    EXPECT_LT((warpMatrix(w) - S).cwiseAbs().maxCoeff(), 1e-12);
  }
}

TEST(RotationFormulas, SeriesAndClosedFormAgreeAtTheSwitch) {
  for (double t2 : {1e-12, 1e-4, 0.01, 0.2499999, 0.25, 0.2500001, 1.0}) {
    const auto c = rotationCoefficients(t2);
    const double t = std::sqrt(t2);
    EXPECT_NEAR(c.s, std::sin(t) / t, 1e-15);
    if (t2 < 1e-3) {  // the closed form cancels here: compare with the leading Taylor terms
      EXPECT_NEAR(c.a, 0.5 - t2 / 24 + t2 * t2 / 720, 1e-15);
      EXPECT_NEAR(c.b, 1.0 / 6 - t2 / 120 + t2 * t2 / 5040, 1e-15);
    } else {
      EXPECT_NEAR(c.a, (1 - std::cos(t)) / t2, 1e-14);
      EXPECT_NEAR(c.b, (t - std::sin(t)) / (t2 * t), 1e-13);
    }
  }
  const auto c0 = rotationCoefficients(0.0);
  EXPECT_EQ(c0.s, 1.0);
  EXPECT_EQ(c0.a, 0.5);
  EXPECT_DOUBLE_EQ(c0.b, 1.0 / 6.0);
}

}  // namespace
}  // namespace myo
