// Exact and projected Hessians of the discrete-shell energy, and the element θ Hessian's closed-form
// diagonal blocks of METHOD.md §1.4.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <numbers>
#include <random>

#include "myoshell/mesh/geometry.h"
#include "myoshell/shell/discrete_shell.h"
#include "myoshell/shell/element_derivatives.h"
#include "shell/shell_fixtures.h"

namespace myo {
namespace {

using test::RestMesh;

Vec3 randomPoint(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  return {u(rng), u(rng), u(rng)};
}

// A random, well-shaped hinge: the edge along roughly x, x2 on one side, x3 on the other.
std::array<Vec3, 4> randomHinge(std::mt19937& rng) {
  const Vec3 x0 = 0.2 * randomPoint(rng), x1 = Vec3(1, 0, 0) + 0.2 * randomPoint(rng);
  const Vec3 x2 = Vec3(0.5, 1, 0) + 0.3 * randomPoint(rng);
  const Vec3 x3 = Vec3(0.5, -1, 0) + 0.3 * randomPoint(rng) + Vec3(0, 0, 0.8 * randomPoint(rng).z());
  return {x0, x1, x2, x3};
}

TEST(ElementDerivatives, DihedralValueIsGeometryDihedralAngle) {
  std::mt19937 rng(3);
  for (int trial = 0; trial < 20; ++trial) {
    const auto x = randomHinge(rng);
    double theta = 0.0;
    ASSERT_TRUE(dihedralAngleDerivatives(x[0], x[1], x[2], x[3], theta));
    EXPECT_EQ(theta, dihedralAngle(x[0], x[1], x[2], x[3]));
  }
}

TEST(ElementDerivatives, DihedralHessianDiagonalBlocksMatchClosedForms) {
  // METHOD.md §1.4: ∂²θ/∂x2² = (m̂0 n̂0ᵀ + n̂0 m̂0ᵀ)/h0², m̂0 = n̂0 × ê;
  //                 ∂²θ/∂x3² = (m̂1 n̂1ᵀ + n̂1 m̂1ᵀ)/h1², m̂1 = n̂1 × (−ê).
  std::mt19937 rng(7);
  for (int trial = 0; trial < 20; ++trial) {
    const auto x = randomHinge(rng);
    double theta = 0.0;
    Vec12 g;
    Mat12 H;
    ASSERT_TRUE(dihedralAngleDerivatives(x[0], x[1], x[2], x[3], theta, &g, &H));
    const Vec3 e = x[1] - x[0], eh = e.normalized();
    const Vec3 n0 = e.cross(x[2] - x[0]), n1 = (x[0] - x[1]).cross(x[3] - x[1]);
    const double h0 = n0.norm() / e.norm(), h1 = n1.norm() / e.norm();
    const Vec3 n0h = n0.normalized(), n1h = n1.normalized();
    const Vec3 m0 = n0h.cross(eh), m1 = n1h.cross(-eh);
    const Mat3 H22 = (m0 * n0h.transpose() + n0h * m0.transpose()) / (h0 * h0);
    const Mat3 H33 = (m1 * n1h.transpose() + n1h * m1.transpose()) / (h1 * h1);
    EXPECT_LE((H.block<3, 3>(6, 6) - H22).norm(), 1e-12 * H22.norm()) << "trial " << trial;
    EXPECT_LE((H.block<3, 3>(9, 9) - H33).norm(), 1e-12 * H33.norm()) << "trial " << trial;
    // And the gradient blocks of §1.3.
    EXPECT_LE((g.segment<3>(6) + n0h / h0).norm(), 1e-12 / h0);
    EXPECT_LE((g.segment<3>(9) + n1h / h1).norm(), 1e-12 / h1);
  }
}

// Best relative FD error of an element function's Hessian against its own gradient.
template <class F>
double elementHessianError(F f, const Vec12& x) {
  Vec12 g;
  Mat12 H;
  f(x, &g, &H);
  double best = 1e300;
  for (double h : test::fdSteps()) {
    Mat12 fd;
    for (int j = 0; j < 12; ++j) {
      Vec12 xp = x, xm = x, gp, gm;
      xp[j] += h;
      xm[j] -= h;
      Mat12 dummy;
      f(xp, &gp, &dummy);
      f(xm, &gm, &dummy);
      fd.col(j) = (gp - gm) / (2 * h);
    }
    best = std::min(best, (fd - H).norm() / H.norm());
  }
  return best;
}

TEST(ElementDerivatives, DihedralHessianMatchesFiniteDifferences) {
  std::mt19937 rng(11);
  for (int trial = 0; trial < 20; ++trial) {
    const auto p = randomHinge(rng);
    Vec12 x;
    x << p[0], p[1], p[2], p[3];
    const double err = elementHessianError(
        [](const Vec12& y, Vec12* g, Mat12* H) {
          double t;
          dihedralAngleDerivatives(y.segment<3>(0), y.segment<3>(3), y.segment<3>(6), y.segment<3>(9), t, g, H);
        },
        x);
    EXPECT_LE(err, 1e-7) << "trial " << trial;
  }
}

TEST(ElementDerivatives, AreaHessianMatchesFiniteDifferences) {
  std::mt19937 rng(12);
  for (int trial = 0; trial < 20; ++trial) {
    Vec12 x;
    x << randomPoint(rng), randomPoint(rng), randomPoint(rng), Vec3::Zero();
    const double err = elementHessianError(
        [](const Vec12& y, Vec12* g, Mat12* H) {
          double a;
          Vec9 g9;
          Mat9 H9;
          triangleAreaDerivatives(y.segment<3>(0), y.segment<3>(3), y.segment<3>(6), a, &g9, &H9);
          g->setZero();
          H->setZero();
          g->head<9>() = g9;
          H->topLeftCorner<9, 9>() = H9;
        },
        x);
    EXPECT_LE(err, 1e-7) << "trial " << trial;
  }
}

TEST(ElementDerivatives, WrapAngleMapsIntoHalfOpenInterval) {
  const double pi = std::numbers::pi;
  EXPECT_DOUBLE_EQ(wrapAngle(0.3), 0.3);
  EXPECT_NEAR(wrapAngle(2 * pi - 0.1), -0.1, 1e-14);
  EXPECT_NEAR(wrapAngle(-2 * pi + 0.1), 0.1, 1e-14);
  EXPECT_DOUBLE_EQ(wrapAngle(-pi), pi);
  EXPECT_DOUBLE_EQ(wrapAngle(pi), pi);
}

// ---------------------------------------------------------------------------------------------
// Assembled Hessian

TEST(DiscreteShellHessian, EachTermMatchesFiniteDifferences) {
  unsigned seed = 200;
  for (const RestMesh& m : test::testMeshes())
    for (char term : {'A', 'L', 'B'}) {
      const DiscreteShell shell = test::makeShell(m, test::onlyTerm(term));
      const MatX3 x = m.V + test::randomMatrix(static_cast<int>(m.V.rows()), 0.1, ++seed);
      EXPECT_LE(test::bestHessianError(shell, x), 1e-5) << m.name << ", E_" << term;
    }
}

TEST(DiscreteShellHessian, IsSymmetricAwayFromRest) {
  const RestMesh m = test::icospherePatch();
  const DiscreteShell shell = test::makeShell(m);
  SparseMat H;
  shell.energy(m.V + test::randomMatrix(static_cast<int>(m.V.rows()), 0.2, 3), nullptr, &H);
  const MatX Hd = MatX(H);
  EXPECT_LE((Hd - Hd.transpose()).norm(), 1e-14 * Hd.norm());
}

TEST(DiscreteShellHessian, ProjectedIsPsdAndExactIsNot) {
  for (const RestMesh& m : test::testMeshes()) {
    const DiscreteShell shell = test::makeShell(m);
    const MatX3 x = m.V + test::randomMatrix(static_cast<int>(m.V.rows()), 0.2, 17);
    VecX gExact, gProj;
    SparseMat Hexact, Hproj;
    const double e1 = shell.energy(x, &gExact, &Hexact).total;
    const double e2 = shell.energy(x, &gProj, &Hproj, HessianMode::Projected).total;
    EXPECT_EQ(e1, e2);
    EXPECT_EQ((gExact - gProj).norm(), 0.0);  // the mode changes the Hessian only
    const MatX P = MatX(Hproj);
    EXPECT_LE((P - P.transpose()).norm(), 1e-13 * P.norm()) << m.name;
    const VecX lp = Eigen::SelfAdjointEigenSolver<MatX>(P).eigenvalues();
    EXPECT_GE(lp.minCoeff(), -1e-12 * lp.maxCoeff()) << m.name;
    const VecX le = Eigen::SelfAdjointEigenSolver<MatX>(MatX(Hexact)).eigenvalues();
    EXPECT_LT(le.minCoeff(), -1e-6 * le.maxCoeff()) << m.name << ": the test deformation should be indefinite";
  }
}

TEST(DiscreteShellHessian, PatternIsFixedAcrossStatesModesAndMaterials) {
  const RestMesh m = test::icospherePatch();
  const DiscreteShell shell = test::makeShell(m);
  SparseMat H1, H2, H3;
  shell.energy(m.V, nullptr, &H1);
  shell.energy(m.V + test::randomMatrix(static_cast<int>(m.V.rows()), 0.2, 8), nullptr, &H2,
               HessianMode::Projected);
  shell.withMaterial(test::onlyTerm('L')).energy(m.V, nullptr, &H3);
  const SparseMat K = shell.stiffnessAtRest();
  for (const SparseMat* H : {&H1, &H2, &H3}) {
    ASSERT_EQ(H->nonZeros(), K.nonZeros());
    EXPECT_TRUE(std::equal(K.outerIndexPtr(), K.outerIndexPtr() + K.outerSize() + 1, H->outerIndexPtr()));
    EXPECT_TRUE(std::equal(K.innerIndexPtr(), K.innerIndexPtr() + K.nonZeros(), H->innerIndexPtr()));
  }
}

TEST(DiscreteShellHessian, ProjectedEqualsExactAtRest) {
  const RestMesh m = test::saddlePatch();
  const DiscreteShell shell = test::makeShell(m);
  SparseMat H, P;
  shell.energy(m.V, nullptr, &H);
  shell.energy(m.V, nullptr, &P, HessianMode::Projected);
  const MatX Hd = MatX(H);
  EXPECT_LE((MatX(P) - Hd).norm(), 1e-12 * Hd.norm());
}

}  // namespace
}  // namespace myo
