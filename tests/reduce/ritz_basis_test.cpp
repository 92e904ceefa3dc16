// Load-dependent Ritz vectors (reduce/ritz_basis.h) on a curved strip held by a soft foundation:
// mass orthonormality, a diagonal reduced stiffness, exact static responses, deflation, grabs.
#include <gtest/gtest.h>

#include "myoshell/core/errors.h"
#include "myoshell/core/parallel.h"
#include "myoshell/mesh/edge_table.h"
#include "myoshell/mesh/primitives.h"
#include "myoshell/reduce/ritz_basis.h"
#include "myoshell/shell/discrete_shell.h"

namespace myo {
namespace {

struct Fixture {
  TriMesh mesh = gridMesh(4.0, 1.0, 16, 4);
  SparseMat K;
  VecX mass;
  Fixture() {
    for (Eigen::Index v = 0; v < mesh.V.rows(); ++v) mesh.V(v, 2) = 0.1 * mesh.V(v, 0) * mesh.V(v, 0);  // curved
    ShellMaterial mat;
    mat.kA = 2e3, mat.kL = 2e2, mat.kB = 50.0;
    const DiscreteShell shell(mesh.V, mesh.F, buildEdgeTable(mesh.F, mesh.vertexCount()), mat);
    const int n = mesh.vertexCount();
    std::vector<Triplet> t;
    for (int i = 0; i < 3 * n; ++i) t.emplace_back(i, i, 50.0 + 5.0 * (i % 7));  // a foundation: K positive definite
    SparseMat Katt(3 * n, 3 * n);
    Katt.setFromTriplets(t.begin(), t.end());
    K = shell.stiffnessAtRest() + Katt;
    mass = shell.lumpedMass();
  }
  MatX3 load(int vertex, const Vec3& f) const {
    MatX3 F = MatX3::Zero(mesh.vertexCount(), 3);
    F.row(vertex) = f.transpose();
    return F;
  }
  VecX mass3() const {
    VecX m(3 * mass.size());
    for (Eigen::Index i = 0; i < mass.size(); ++i) m.segment<3>(3 * i).setConstant(mass(i));
    return m;
  }
};

void expectOrthonormalAndDiagonal(const ModalBasis& B, const SparseMat& K, const VecX& m3) {
  const MatX PtMP = B.Phi.transpose() * m3.asDiagonal() * B.Phi;
  EXPECT_LE((PtMP - MatX::Identity(B.modeCount(), B.modeCount())).cwiseAbs().maxCoeff(), 1e-10);
  MatX PtKP = B.Phi.transpose() * (K * B.Phi);
  const double scale = B.lambda.cwiseAbs().maxCoeff();
  for (int j = 0; j < B.modeCount(); ++j) EXPECT_NEAR(PtKP(j, j), B.lambda(j), 1e-10 * scale);
  PtKP.diagonal().setZero();
  EXPECT_LE(PtKP.cwiseAbs().maxCoeff(), 1e-10 * scale);
  for (int j = 1; j < B.modeCount(); ++j) EXPECT_LE(B.lambda(j - 1), B.lambda(j));
}

double reducedStaticError(const ModalBasis& B, const RitzBasisBuilder& b, const MatX3& f) {
  const VecX q = (B.Phi.transpose() * flat(f)).cwiseQuotient(B.lambda);
  const VecX uRed = B.Phi * q;
  const MatX3 uFull = b.staticResponse(f);
  return (uRed - flat(uFull)).norm() / flat(uFull).norm();
}

TEST(RitzBasis, StaticResponsesOfTheLoadsAreExactAndTheReducedSystemDiagonal) {
  Fixture fx;
  RitzSettings s;
  s.modes.modeCount = 6;
  RitzBasisBuilder b(fx.K, fx.mass, fx.mesh.V, fx.mesh.F, s);
  const std::vector<MatX3> loads = {fx.load(40, Vec3(1, 0, 0)), fx.load(60, Vec3(0, 0, 3)), fx.load(7, Vec3(0, 2, 1))};
  // Before the loads are added, the 6 modes miss most of a tangential point load's response.
  EXPECT_GT(reducedStaticError(b.basis(), b, loads[0]), 0.1);
  for (const MatX3& f : loads) EXPECT_TRUE(b.addLoad(f));
  b.diagonalize();
  const ModalBasis& B = b.basis();
  EXPECT_EQ(B.modeCount(), 9);
  expectOrthonormalAndDiagonal(B, fx.K, fx.mass3());
  for (const MatX3& f : loads) EXPECT_LE(reducedStaticError(B, b, f), 1e-9);
  // Ψ = WΦ still holds after the re-diagonalisation.
  EXPECT_EQ(B.Psi.cols(), 9);
}

TEST(RitzBasis, ARepeatedOrCombinedLoadIsDeflated) {
  Fixture fx;
  RitzSettings s;
  s.modes.modeCount = 4;
  RitzBasisBuilder b(fx.K, fx.mass, fx.mesh.V, fx.mesh.F, s);
  const MatX3 f1 = fx.load(30, Vec3(1, 1, 0)), f2 = fx.load(50, Vec3(0, 0, 1));
  EXPECT_TRUE(b.addLoad(f1));
  EXPECT_TRUE(b.addLoad(f2));
  EXPECT_FALSE(b.addLoad(f1));               // the same load again
  EXPECT_FALSE(b.addLoad(2.0 * f1 - 3.0 * f2));  // in the span already
  EXPECT_FALSE(b.addLoad(MatX3::Zero(fx.mesh.vertexCount(), 3)));
  EXPECT_EQ(b.loadVectors(), 2);
  EXPECT_EQ(b.deflated(), 3);
  b.diagonalize();
  EXPECT_EQ(b.basis().modeCount(), 6);
}

TEST(RitzBasis, AGrabAddedLaterIsExactAndKeepsTheOthersExact) {
  Fixture fx;
  RitzSettings s;
  s.modes.modeCount = 5;
  RitzBasisBuilder b(fx.K, fx.mass, fx.mesh.V, fx.mesh.F, s);
  const MatX3 f1 = fx.load(22, Vec3(0, 1, 0));
  b.addLoadAndDiagonalize(f1);
  const MatX3 grab = fx.load(70, Vec3(1, 0, 0.5));
  EXPECT_TRUE(b.addLoadAndDiagonalize(grab));
  expectOrthonormalAndDiagonal(b.basis(), fx.K, fx.mass3());
  EXPECT_LE(reducedStaticError(b.basis(), b, f1), 1e-9);
  EXPECT_LE(reducedStaticError(b.basis(), b, grab), 1e-9);
}

// The build spread over threads (core/parallel.h): step 1 beside K's factorisation, the loads'
// solves side by side. The basis must be the serial one, bit for bit, for any thread count.
TEST(RitzBasis, ThreadsGiveTheSerialBasisBitForBit) {
  Fixture fx;
  RitzSettings s;
  s.modes.modeCount = 6;
  std::vector<MatX3> loads;
  for (int k = 0; k < 11; ++k) loads.push_back(fx.load(5 * k + 3, Vec3(1.0 + k, 0.5 * k, 2.0 - k)));
  loads.push_back(loads[2]);  // deflated, in the middle of a chunk
  loads.push_back(fx.load(44, Vec3(0, 0, 1)));
  const int saved = parallelThreads();
  auto build = [&](int threads, bool serialCalls) {
    setParallelThreads(threads);
    RitzBasisBuilder b(fx.K, fx.mass, fx.mesh.V, fx.mesh.F, s);
    int appended = 0;
    if (serialCalls)
      for (const MatX3& f : loads) appended += b.addLoad(f) ? 1 : 0;
    else
      appended = b.addLoads(loads);
    EXPECT_EQ(appended, 12);
    EXPECT_EQ(b.deflated(), 1);
    b.diagonalize();
    return b.basis();
  };
  const ModalBasis serial = build(1, true);
  for (int threads : {1, 2, 3}) {
    const ModalBasis threaded = build(threads, false);
    EXPECT_TRUE(threaded.Phi == serial.Phi) << threads << " threads";
    EXPECT_TRUE(threaded.Psi == serial.Psi) << threads << " threads";
    EXPECT_TRUE(threaded.lambda == serial.lambda) << threads << " threads";
  }
  setParallelThreads(2);
  const Fixture bad;
  const SparseMat Kbad = bad.K - SparseMat(bad.K.diagonal().asDiagonal().toDenseMatrix().sparseView()) * 2.0;
  EXPECT_THROW(RitzBasisBuilder(Kbad, bad.mass, bad.mesh.V, bad.mesh.F, s), NumericalError);  // refused on two threads too
  setParallelThreads(saved);
}

TEST(RitzBasis, ANonPositiveDefiniteStiffnessIsRefused) {
  Fixture fx;
  const SparseMat Kbad = fx.K - SparseMat(fx.K.diagonal().asDiagonal().toDenseMatrix().sparseView()) * 2.0;
  EXPECT_THROW(RitzBasisBuilder(Kbad, fx.mass, fx.mesh.V, fx.mesh.F), NumericalError);
}

}  // namespace
}  // namespace myo
