// Constrained modal analysis: Spectra vs dense, orthonormality, rigid modes, pins, participation.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include "myoshell/mesh/edge_table.h"
#include "myoshell/mesh/primitives.h"
#include "myoshell/reduce/modal_analysis.h"
#include "myoshell/shell/discrete_shell.h"

namespace myo {
namespace {

DiscreteShell makeShell(const TriMesh& m, ShellMaterial mat = {}) {
  return DiscreteShell(m.V, m.F, buildEdgeTable(m.F, m.vertexCount()), mat);
}

// A gently curved strip (so membrane and bending couple), (nx+1)×(ny+1) vertices.
TriMesh curvedStrip(int nx, int ny) {
  TriMesh m = gridMesh(10.0, 2.0, nx, ny);
  for (Eigen::Index i = 0; i < m.V.rows(); ++i) m.V(i, 2) = 0.02 * m.V(i, 0) * m.V(i, 0) + 0.1 * m.V(i, 1);
  return m;
}

// Vertices of grid column i (x = i·length/nx).
std::vector<int> gridColumn(int nx, int ny, int i) {
  std::vector<int> v;
  for (int j = 0; j <= ny; ++j) v.push_back(j * (nx + 1) + i);
  return v;
}

std::vector<int> concat(std::vector<int> a, const std::vector<int>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

VecX massDiagOf(const ModalBasis& b) {
  VecX m(3 * b.freeCount());
  for (int i = 0; i < b.freeCount(); ++i) m.segment<3>(3 * i).setConstant(b.freeMass[i]);
  return m;
}

TEST(ModalAnalysis, ShiftInvertMatchesDenseGeneralizedSolve) {
  const int nx = 24, ny = 11;  // 300 vertices, 900 DOFs
  const TriMesh mesh = curvedStrip(nx, ny);
  const DiscreteShell shell = makeShell(mesh);
  const std::vector<int> pins = concat(gridColumn(nx, ny, 0), gridColumn(nx, ny, 1));
  ModalSettings s;
  s.modeCount = 12;
  s.solver = EigenSolverKind::ShiftInvert;
  const ModalBasis b = computeModalBasis(shell, pins, s);
  EXPECT_EQ(b.solver, "shift-invert");

  // Independent reference: Eigen's dense generalized solver on the same K_FF, M_FF.
  const SparseMat Kff = restrictToFree(shell.stiffnessAtRest(), b.freeVertices, shell.vertexCount());
  const VecX m = massDiagOf(b);
  Eigen::GeneralizedSelfAdjointEigenSolver<MatX> ges(MatX(Kff), MatX(m.asDiagonal()));
  ASSERT_EQ(ges.info(), Eigen::Success);
  for (int j = 0; j < s.modeCount; ++j)
    EXPECT_NEAR(b.lambda[j], ges.eigenvalues()[j], 1e-8 * ges.eigenvalues()[j]) << "mode " << j;

  // And the library's own dense path.
  s.solver = EigenSolverKind::Dense;
  s.denseMaxDofs = 100000;
  const ModalBasis bd = computeModalBasis(shell, pins, s);
  EXPECT_EQ(bd.solver, "dense");
  for (int j = 0; j < s.modeCount; ++j) {
    EXPECT_NEAR(b.lambda[j], bd.lambda[j], 1e-8 * bd.lambda[j]);
    // Same mode shapes up to sign (eigenvalues are simple here): |φᵀMφ'| = 1.
    EXPECT_NEAR(std::abs(b.Phi.col(j).dot(m.cwiseProduct(bd.Phi.col(j)))), 1.0, 1e-6);
  }
}

TEST(ModalAnalysis, ModesAreMassOrthonormalAndDiagonalizeK) {
  const int nx = 30, ny = 6;
  const TriMesh mesh = curvedStrip(nx, ny);
  const DiscreteShell shell = makeShell(mesh);
  const std::vector<int> pins = concat(gridColumn(nx, ny, 0), gridColumn(nx, ny, 1));
  for (EigenSolverKind kind : {EigenSolverKind::Dense, EigenSolverKind::ShiftInvert}) {
    ModalSettings s;
    s.modeCount = 15;
    s.solver = kind;
    const ModalBasis b = computeModalBasis(shell, pins, s);
    const SparseMat Kff = restrictToFree(shell.stiffnessAtRest(), b.freeVertices, shell.vertexCount());
    const VecX m = massDiagOf(b);
    const MatX G = b.Phi.transpose() * m.asDiagonal() * b.Phi;
    EXPECT_LT((G - MatX::Identity(15, 15)).cwiseAbs().maxCoeff(), 1e-10);
    const MatX L = b.Phi.transpose() * (Kff * b.Phi);
    EXPECT_LT((L - MatX(b.lambda.asDiagonal())).cwiseAbs().maxCoeff(), 1e-9 * b.lambda.maxCoeff());
    for (int j = 1; j < 15; ++j) EXPECT_LE(b.lambda[j - 1], b.lambda[j]);  // ascending
    EXPECT_GT(b.lambda[0], 0.0);
    // ‖KΦ − MΦΛ‖ small: true eigenvectors, not just a Ritz basis.
    const MatX res = Kff * b.Phi - m.asDiagonal() * b.Phi * b.lambda.asDiagonal();
    for (int j = 0; j < 15; ++j)
      EXPECT_LT(res.col(j).norm(), 1e-7 * b.lambda.maxCoeff() * m.cwiseProduct(b.Phi.col(j)).norm());
  }
}

TEST(ModalAnalysis, FreeIcosphereHasSixRigidModes) {
  const TriMesh mesh = icosphere(3.0, 2);  // 162 vertices
  const DiscreteShell shell = makeShell(mesh);
  for (EigenSolverKind kind : {EigenSolverKind::Dense, EigenSolverKind::ShiftInvert}) {
    ModalSettings s;
    s.modeCount = 10;
    s.solver = kind;
    const ModalBasis b = computeModalBasis(shell, {}, s);
    ASSERT_EQ(b.modeCount(), 10);
    EXPECT_EQ(b.freeCount(), mesh.vertexCount());
    const double scale = b.lambda[9];
    for (int j = 0; j < 6; ++j) EXPECT_LT(std::abs(b.lambda[j]), 1e-8 * scale) << "mode " << j;
    EXPECT_GT(b.lambda[6], 1e-3 * scale);
  }
}

TEST(ModalAnalysis, PinnedVerticesAreRemovedFromTheBasis) {
  const int nx = 10, ny = 3;
  const TriMesh mesh = curvedStrip(nx, ny);
  const DiscreteShell shell = makeShell(mesh);
  const std::vector<int> pins = {0, 11, 22, 33, 5, 5, 1};  // unsorted, with a duplicate
  ModalSettings s;
  s.modeCount = 6;
  const ModalBasis b = computeModalBasis(shell, pins, s);
  EXPECT_EQ(b.fullVertexCount, mesh.vertexCount());
  EXPECT_EQ(b.freeCount(), mesh.vertexCount() - 6);
  EXPECT_EQ(b.Phi.rows(), 3 * b.freeCount());
  EXPECT_EQ(b.Psi.rows(), 3 * b.freeCount());
  EXPECT_TRUE(std::is_sorted(b.freeVertices.begin(), b.freeVertices.end()));
  for (int p : pins) EXPECT_FALSE(std::binary_search(b.freeVertices.begin(), b.freeVertices.end(), p));
  const std::vector<int> map = b.fullToFree();
  for (int p : pins) EXPECT_EQ(map[p], -1);
  // A free field scattered to the full mesh is exactly zero on the pins.
  const VecX col = b.Phi.col(0);
  const MatX3 full = scatterToFull(b, MatX3(rows3(col)));
  for (int p : pins) EXPECT_EQ(full.row(p).squaredNorm(), 0.0);
  EXPECT_EQ(gatherFree(b, full), MatX3(rows3(col)));
  // Out-of-range pins are an input error.
  EXPECT_THROW(computeModalBasis(shell, {mesh.vertexCount()}, s), InputError);
  s.modeCount = 0;
  EXPECT_THROW(computeModalBasis(shell, pins, s), InputError);
}

TEST(ModalAnalysis, CollinearPinsLeaveAHingeModeTwoRowsDoNot) {
  const int nx = 16, ny = 3;
  const TriMesh mesh = curvedStrip(nx, ny);  // column 0 is the straight line x = 0 … but curved in z
  // Column 0 lies on x = 0 with z = 0.1·y: collinear. Columns 0 and 1 together are not.
  const DiscreteShell shell = makeShell(mesh);
  for (EigenSolverKind kind : {EigenSolverKind::Dense, EigenSolverKind::ShiftInvert}) {
    ModalSettings s;
    s.modeCount = 4;
    s.solver = kind;
    const ModalBasis one = computeModalBasis(shell, gridColumn(nx, ny, 0), s);
    EXPECT_LT(std::abs(one.lambda[0]), 1e-8 * one.lambda[1]);  // the rigid hinge about the pinned line
    EXPECT_GT(one.lambda[1], 0.0);
    const ModalBasis two =
        computeModalBasis(shell, concat(gridColumn(nx, ny, 0), gridColumn(nx, ny, 1)), s);
    EXPECT_GT(two.lambda[0], 1e-3 * two.lambda[1]);
  }
}

TEST(ModalAnalysis, LoadParticipationGrowsToOneWithAllModes) {
  const int nx = 8, ny = 2;
  const TriMesh mesh = curvedStrip(nx, ny);
  const DiscreteShell shell = makeShell(mesh);
  const std::vector<int> pins = concat(gridColumn(nx, ny, 0), gridColumn(nx, ny, 1));
  ModalSettings s;
  s.solver = EigenSolverKind::Dense;
  s.modeCount = 3;
  const ModalBasis few = computeModalBasis(shell, pins, s);
  MatX3 F = MatX3::Zero(few.freeCount(), 3);
  for (int i = 0; i < few.freeCount(); ++i)
    if (mesh.V(few.freeVertices[i], 0) > 9.9) F.row(i) << 1.0, 0.0, 5.0;  // tip load
  const LoadParticipation lpFew = loadParticipation(few, shell, F);
  EXPECT_GT(lpFew.ratio, 0.0);
  EXPECT_LT(lpFew.ratio, 1.0);
  EXPECT_NEAR(lpFew.modal, lpFew.perMode.sum(), 1e-12 * lpFew.modal);
  s.modeCount = 3 * few.freeCount();  // every mode
  const ModalBasis all = computeModalBasis(shell, pins, s);
  const LoadParticipation lpAll = loadParticipation(all, shell, F);
  EXPECT_NEAR(lpAll.ratio, 1.0, 1e-8);
  EXPECT_NEAR(lpAll.total, lpFew.total, 1e-10 * lpAll.total);
  EXPECT_GT(lpAll.ratio, lpFew.ratio);
  // A free system has no finite compliance.
  s.modeCount = 8;
  const ModalBasis free = computeModalBasis(shell, {}, s);
  EXPECT_THROW(loadParticipation(free, shell, MatX3::Ones(free.freeCount(), 3)), NumericalError);
}

TEST(ModalAnalysis, CacheKeyCoversItsInputs) {
  const TriMesh mesh = curvedStrip(6, 2);
  const DiscreteShell shell = makeShell(mesh);
  ModalSettings s;
  s.modeCount = 5;
  const BasisKey k = modalBasisKey(shell, {0, 7}, s);
  EXPECT_EQ(k, modalBasisKey(shell, {7, 0, 0}, s));  // pin order and duplicates do not matter
  EXPECT_EQ(k.hex().size(), 32u);
  EXPECT_NE(k, modalBasisKey(shell, {0, 8}, s));
  ModalSettings s2 = s;
  s2.modeCount = 6;
  EXPECT_NE(k, modalBasisKey(shell, {0, 7}, s2));
  ShellMaterial mat;
  mat.kB *= 1.0000001;
  EXPECT_NE(k, modalBasisKey(makeShell(mesh, mat), {0, 7}, s));
  TriMesh moved = mesh;
  moved.V(3, 1) += 1e-12;
  EXPECT_NE(k, modalBasisKey(makeShell(moved), {0, 7}, s));
}

}  // namespace
}  // namespace myo
