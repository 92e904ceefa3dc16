#include "myoshell/shell/discrete_shell.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <numbers>

#include "myoshell/core/errors.h"
#include "myoshell/mesh/geometry.h"
#include "shell/shell_fixtures.h"

namespace myo {
namespace {

using test::RestMesh;

// ---------------------------------------------------------------------------------------------
// Material

TEST(ShellMaterial, DefaultsAreValid) { EXPECT_NO_THROW(ShellMaterial{}.validate()); }

TEST(ShellMaterial, RejectsNegativeStiffnessNamingTheField) {
  ShellMaterial m;
  m.kA = -1.0;
  try {
    m.validate();
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "k_A must be ≥ 0 (got -1)");
  }
  m = {};
  m.kB = -2.5;
  EXPECT_THROW(m.validate(), InputError);
}

TEST(ShellMaterial, RejectsNonPositiveDensityAndThicknessAndNaN) {
  ShellMaterial m;
  m.density = 0.0;
  try {
    m.validate();
    FAIL();
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "density must be > 0 (got 0)");
  }
  m = {};
  m.thickness = -0.1;
  try {
    m.validate();
    FAIL();
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "thickness must be > 0 (got -0.1)");
  }
  m = {};
  m.kL = std::nan("");
  try {
    m.validate();
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("k_L must be ≥ 0"), std::string::npos) << e.what();
  }
  m = {};
  m.kA = std::numeric_limits<double>::infinity();
  EXPECT_THROW(m.validate(), InputError);
}

TEST(DiscreteShell, ConstructorValidatesMaterial) {
  const RestMesh m = test::perturbedGrid();
  ShellMaterial bad;
  bad.thickness = 0.0;
  EXPECT_THROW(test::makeShell(m, bad), InputError);
  EXPECT_THROW(test::makeShell(m).withMaterial(bad), InputError);
}

// ---------------------------------------------------------------------------------------------
// Energy values

TEST(DiscreteShell, EnergyTermsMatchHandComputedValues) {
  // Stretch one triangle pair: a unit square (two triangles) scaled by 1.1 in x.
  const TriMesh g = gridMesh(1.0, 1.0, 1, 1);
  const DiscreteShell shell(g.V, g.F, buildEdgeTable(g.F, g.vertexCount()), ShellMaterial{});
  MatX3 x = g.V;
  x.col(0) *= 1.1;
  const ShellEnergy E = shell.energy(x);
  // Each triangle: Ā = 0.5, A = 0.55 → 0.05²/0.5 each.
  EXPECT_NEAR(E.EA, 2 * 0.05 * 0.05 / 0.5, 1e-14);
  // Edges: two along x (0.1²/1 each), two along y (0), the diagonal (√(1.21+1) − √2)²/√2.
  const double d = std::sqrt(2.21) - std::sqrt(2.0);
  EXPECT_NEAR(E.EL, 2 * 0.01 + d * d / std::sqrt(2.0), 1e-14);
  EXPECT_NEAR(E.EB, 0.0, 1e-14);  // still flat
  const ShellMaterial& k = shell.material();
  EXPECT_NEAR(E.total, k.kA * E.EA + k.kL * E.EL + k.kB * E.EB, 1e-12);
}

TEST(DiscreteShell, BendingEnergyOfAFoldedPairUsesThreeEdgeSquaredOverAreaSum) {
  // Two right triangles sharing the diagonal; fold by rotating vertex 3 about the diagonal.
  MatX3 V(4, 3);
  V << 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0;
  MatX3i F(2, 3);
  F << 0, 1, 2, 0, 2, 3;
  const DiscreteShell shell(V, F, buildEdgeTable(F, 4), ShellMaterial{});
  const double fold = 0.3;
  const Vec3 axis = Vec3(1, 1, 0).normalized();
  MatX3 x = V;
  x.row(3) = (Eigen::AngleAxisd(fold, axis) * Vec3(V.row(3).transpose())).transpose();
  const ShellEnergy E = shell.energy(x);
  // c_e = 3|ē|²/(Ā1+Ā2) = 3·2/1 = 6 (METHOD.md §1.2: not 9× that).
  EXPECT_NEAR(E.EB, 6.0 * fold * fold, 1e-12);
}

TEST(DiscreteShell, ConvexIcosphereHasPositiveRestDihedralAngles) {
  const TriMesh s = icosphere(2.0, 2);
  const DiscreteShell shell(s.V, s.F, buildEdgeTable(s.F, s.vertexCount()), ShellMaterial{});
  for (size_t i = 0; i < shell.edgeTable().edges.size(); ++i) {
    ASSERT_FALSE(shell.edgeTable().edges[i].isBoundary());
    EXPECT_GT(shell.restDihedralAngles()[i], 0.0) << "edge " << i;
  }
}

TEST(DiscreteShell, EnergyIsZeroAtRest) {
  for (const RestMesh& m : test::testMeshes()) {
    const DiscreteShell shell = test::makeShell(m);
    VecX g;
    const ShellEnergy E = shell.energy(m.V, &g);
    EXPECT_EQ(E.total, 0.0) << m.name;
    EXPECT_EQ(g.norm(), 0.0) << m.name;
  }
}

// ---------------------------------------------------------------------------------------------
// Gradient against finite differences, each term alone

TEST(DiscreteShell, GradientOfEachTermMatchesFiniteDifferences) {
  unsigned seed = 10;
  for (const RestMesh& m : test::testMeshes())
    for (char term : {'A', 'L', 'B'}) {
      const DiscreteShell shell = test::makeShell(m, test::onlyTerm(term));
      for (int trial = 0; trial < 2; ++trial) {
        const MatX3 x = m.V + test::randomMatrix(static_cast<int>(m.V.rows()), 0.1, ++seed);
        const double err = test::bestGradientError(shell, x);
        EXPECT_LE(err, 1e-6) << m.name << ", E_" << term << ", trial " << trial;
      }
    }
}

TEST(DiscreteShell, GradientOfTheTotalMatchesFiniteDifferences) {
  const RestMesh m = test::saddlePatch();
  const DiscreteShell shell = test::makeShell(m);
  const MatX3 x = m.V + test::randomMatrix(static_cast<int>(m.V.rows()), 0.15, 99);
  EXPECT_LE(test::bestGradientError(shell, x), 1e-6);
}

TEST(DiscreteShell, WrapsBendingAcrossTheBranchCut) {
  // A hinge folded to almost −π at rest, deformed past the cut: Δθ stays small.
  MatX3 V(4, 3);
  // x3 = (0.5, cos φ, sin φ): φ = π is flat, φ → 0 folds x3 onto x2's side (|θ| = π − φ).
  const double a = 0.05;
  V << 0, 0, 0, 1, 0, 0, 0.5, 1, 0, 0.5, std::cos(a), std::sin(a);
  MatX3i F(2, 3);
  F << 0, 1, 2, 1, 0, 3;
  const DiscreteShell shell(V, F, buildEdgeTable(F, 4), test::onlyTerm('B'));
  const double rest = shell.restDihedralAngles()[0];
  ASSERT_GT(std::abs(rest), 3.0);
  MatX3 x = V;
  const double b = -0.05;  // crosses ±π: θ jumps from −(π − 0.05) to π − 0.05
  x.row(3) << 0.5, std::cos(b), std::sin(b);
  const ShellEnergy E = shell.energy(x);
  EXPECT_NEAR(E.EB, shell.bendingWeights()[0] * 0.1 * 0.1, 1e-10);
}

TEST(DiscreteShell, CollapsedHingeGivesNoNaN) {
  MatX3 V(4, 3);
  V << 0, 0, 0, 1, 0, 0, 0.5, 1, 0, 0.5, -1, 0;
  MatX3i F(2, 3);
  F << 0, 1, 2, 1, 0, 3;
  const DiscreteShell shell(V, F, buildEdgeTable(F, 4), ShellMaterial{});
  MatX3 x = V;
  x.row(2) << 0.3, 0.0, 0.0;  // f0 collapses onto the edge
  VecX g;
  SparseMat H;
  const ShellEnergy E = shell.energy(x, &g, &H);
  EXPECT_TRUE(std::isfinite(E.total));
  EXPECT_TRUE(g.allFinite());
  EXPECT_TRUE(MatX(H).allFinite());
  shell.energy(x, &g, &H, HessianMode::Projected);
  EXPECT_TRUE(MatX(H).allFinite());
}

// ---------------------------------------------------------------------------------------------
// Invariances

TEST(DiscreteShell, RigidMotionsGiveZeroEnergyAndForce) {
  unsigned seed = 40;
  for (const RestMesh& m : test::testMeshes()) {
    const DiscreteShell shell = test::makeShell(m);
    VecX gRef;
    const double eRef =
        shell.energy(m.V + test::randomMatrix(static_cast<int>(m.V.rows()), 0.1, ++seed), &gRef).total;
    const Mat3 R = Eigen::AngleAxisd(1.1, Vec3(0.3, -0.5, 0.8).normalized()).toRotationMatrix();
    MatX3 x = (m.V * R.transpose()).rowwise() + Eigen::RowVector3d(0.7, -2.0, 1.3);
    VecX g;
    const double e = shell.energy(x, &g).total;
    EXPECT_LE(std::abs(e), 1e-10 * eRef) << m.name;
    EXPECT_LE(g.norm(), 1e-10 * gRef.norm()) << m.name;
  }
}

TEST(DiscreteShell, UniformScalingScalesEachTermByItsDimension) {
  const RestMesh m = test::cylinderPatch();
  const DiscreteShell shell = test::makeShell(m);
  const MatX3 x = m.V + test::randomMatrix(static_cast<int>(m.V.rows()), 0.1, 5);
  const ShellEnergy E = shell.energy(x);
  const double s = 2.5;
  const MatX3 restScaled = s * m.V;
  const DiscreteShell scaled(restScaled, m.F, shell.edgeTable(), shell.material());
  const ShellEnergy Es = scaled.energy(s * x);
  EXPECT_NEAR(Es.EL / E.EL, s, 1e-12 * s);
  EXPECT_NEAR(Es.EA / E.EA, s * s, 1e-12 * s * s);
  EXPECT_NEAR(Es.EB / E.EB, 1.0, 1e-12);
}

// ---------------------------------------------------------------------------------------------
// Rest stiffness and mass

TEST(DiscreteShell, HessianAtRestEqualsStiffnessAtRestAndIsSymmetricPsd) {
  for (const RestMesh& m : test::testMeshes()) {
    const DiscreteShell shell = test::makeShell(m);
    VecX g;
    SparseMat H;
    shell.energy(m.V, &g, &H);
    const SparseMat K = shell.stiffnessAtRest();
    const MatX Kd = MatX(K), Hd = MatX(H);
    EXPECT_LE((Hd - Kd).norm(), 1e-10 * Kd.norm()) << m.name;
    EXPECT_LE((Kd - Kd.transpose()).norm(), 1e-14 * Kd.norm()) << m.name;
    const VecX lambda = Eigen::SelfAdjointEigenSolver<MatX>(Kd).eigenvalues();
    EXPECT_GE(lambda.minCoeff(), -1e-12 * lambda.maxCoeff()) << m.name;
  }
}

TEST(DiscreteShell, StiffnessAtRestMatchesFiniteDifferencesOfTheGradient) {
  for (const RestMesh& m : {test::cylinderPatch(), test::icospherePatch()}) {
    const DiscreteShell shell = test::makeShell(m);
    const MatX K = MatX(shell.stiffnessAtRest());
    MatX fd(K.rows(), K.cols());
    const double h = 1e-6;
    VecX gp, gm;
    MatX3 x = m.V;
    for (Eigen::Index j = 0; j < K.cols(); ++j) {
      flat(x)[j] += h;
      shell.energy(x, &gp);
      flat(x)[j] -= 2 * h;
      shell.energy(x, &gm);
      flat(x)[j] += h;
      fd.col(j) = (gp - gm) / (2 * h);
    }
    EXPECT_LE((fd - K).norm(), 1e-6 * K.norm()) << m.name;
  }
}

TEST(DiscreteShell, FreeClosedShellHasExactlySixRigidModes) {
  const TriMesh s = icosphere(1.0, 1);
  const DiscreteShell shell(s.V, s.F, buildEdgeTable(s.F, s.vertexCount()), ShellMaterial{});
  const VecX lambda = Eigen::SelfAdjointEigenSolver<MatX>(MatX(shell.stiffnessAtRest())).eigenvalues();
  const double lmax = lambda.maxCoeff();
  for (int i = 0; i < 6; ++i) EXPECT_LE(std::abs(lambda[i]), 1e-12 * lmax) << "eigenvalue " << i;
  EXPECT_GE(lambda[6], 1e6 * std::max(std::abs(lambda[5]), 1e-300));
  EXPECT_GT(lambda[6], 1e-6 * lmax);
}

TEST(DiscreteShell, LumpedMassIsPositiveAndSumsToArealDensityTimesArea) {
  for (const RestMesh& m : test::testMeshes()) {
    ShellMaterial mat;
    mat.density = 1.1;
    mat.thickness = 0.3;
    const DiscreteShell shell = test::makeShell(m, mat);
    const VecX& mass = shell.lumpedMass();
    ASSERT_EQ(mass.size(), m.V.rows());
    EXPECT_GT(mass.minCoeff(), 0.0) << m.name;
    EXPECT_NEAR(mass.sum(), 1.1 * 0.3 * surfaceArea(m.V, m.F), 1e-12) << m.name;
    ShellMaterial heavier = mat;
    heavier.density = 2.2;
    EXPECT_NEAR(shell.withMaterial(heavier).lumpedMass().sum(), 2 * mass.sum(), 1e-12);
    EXPECT_EQ(shell.withMaterial(heavier).material().density, 2.2);
  }
}

TEST(DiscreteShell, WithMaterialRescalesStiffness) {
  const RestMesh m = test::perturbedGrid();
  const DiscreteShell shell = test::makeShell(m);
  ShellMaterial twice = shell.material();
  twice.kA *= 2;
  twice.kL *= 2;
  twice.kB *= 2;
  const MatX K1 = MatX(shell.stiffnessAtRest());
  const MatX K2 = MatX(shell.withMaterial(twice).stiffnessAtRest());
  EXPECT_LE((K2 - 2 * K1).norm(), 1e-12 * K1.norm());
}

}  // namespace
}  // namespace myo
