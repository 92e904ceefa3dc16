// The full-space reference solvers (METHOD.md §5.1): static Newton with load stepping, and the
// implicit dynamic integrator.
#include "myoshell/verify/reference_solver.h"

#include <gtest/gtest.h>

#include <cmath>

#include "myoshell/core/errors.h"
#include "myoshell/mesh/edge_table.h"
#include "myoshell/mesh/primitives.h"

namespace myo {
namespace {

// A 1 × 0.1 cm strip, 20×2 cells, alternating diagonals, two rows of vertices clamped at x = 0.
struct Strip {
  static constexpr int kNx = 20, kNy = 2;
  TriMesh mesh = gridMesh(1.0, 0.1, kNx, kNy, true);
  DiscreteShell shell = makeShell(mesh);
  std::vector<int> pinned;
  std::vector<int> tip;

  Strip() {
    for (int j = 0; j <= kNy; ++j) {
      pinned.push_back(j * (kNx + 1));
      pinned.push_back(j * (kNx + 1) + 1);
      tip.push_back(j * (kNx + 1) + kNx);
    }
  }
  static DiscreteShell makeShell(const TriMesh& m) {
    ShellMaterial mat;
    mat.kA = 1e3;
    mat.kL = 1e2;
    mat.kB = 1e-2;
    mat.density = 1.0;
    mat.thickness = 1.0;
    return DiscreteShell(m.V, m.F, buildEdgeTable(m.F, m.vertexCount()), mat);
  }
  // Total transverse (z) load P shared equally by the tip vertices.
  MatX3 tipLoad(double P) const {
    MatX3 F = MatX3::Zero(mesh.vertexCount(), 3);
    for (int v : tip) F(v, 2) = P / tip.size();
    return F;
  }
  int n() const { return mesh.vertexCount(); }
};

double freeResidual(const DiscreteShell& shell, const std::vector<int>& pinned, const MatX3& x,
                    const MatX3& F) {
  VecX g;
  shell.energy(x, &g);
  g -= flat(F);
  for (int p : pinned) g.segment<3>(3 * p).setZero();
  return g.norm();
}

TEST(ReferenceSolver, ZeroLoadGivesZeroDisplacement) {
  Strip s;
  const auto res = solveStaticReference(s.shell, s.pinned, MatX3::Zero(s.n(), 3));
  EXPECT_EQ(res.u.cwiseAbs().maxCoeff(), 0.0);
  EXPECT_EQ((res.x - s.shell.rest()).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_TRUE(res.reachedTolerance);
}

TEST(ReferenceSolver, SmallLoadMatchesLinearSolveToSecondOrder) {
  Strip s;
  // Load giving a linear tip deflection of 1e-2·L, then half of it.
  const MatX3 uUnit = solveLinearStatic(s.shell, s.pinned, s.tipLoad(1.0));
  const double P = 1e-2 / uUnit(s.tip[1], 2);
  double diff[2], rel[2];
  for (int k = 0; k < 2; ++k) {
    const MatX3 F = s.tipLoad(P / (1 << k));
    const auto ref = solveStaticReference(s.shell, s.pinned, F);
    const MatX3 lin = solveLinearStatic(s.shell, s.pinned, F);
    diff[k] = (ref.u - lin).norm();
    rel[k] = diff[k] / lin.norm();
  }
  EXPECT_LT(rel[0], 1e-2);
  // The difference is second order in the load: halving the load divides it by ≈ 4.
  EXPECT_NEAR(diff[0] / diff[1], 4.0, 0.4) << diff[0] << " " << diff[1];
}

TEST(ReferenceSolver, ResidualBelowToleranceAndPinsExactlyFixed) {
  Strip s;
  const MatX3 uUnit = solveLinearStatic(s.shell, s.pinned, s.tipLoad(1.0));
  const MatX3 F = s.tipLoad(0.5 / uUnit(s.tip[1], 2));  // δ_lin = L/2: large rotation
  ReferenceOptions opt;
  const auto res = solveStaticReference(s.shell, s.pinned, F, opt);
  const double Fnorm = F.norm();
  EXPECT_TRUE(res.reachedTolerance);
  EXPECT_LE(res.relativeResidual, opt.relTol);
  EXPECT_LE(freeResidual(s.shell, s.pinned, res.x, F), 1.01 * opt.relTol * Fnorm);
  for (int p : s.pinned) {
    EXPECT_EQ(res.u.row(p).cwiseAbs().maxCoeff(), 0.0);
    EXPECT_EQ((res.x.row(p) - s.shell.rest().row(p)).cwiseAbs().maxCoeff(), 0.0);
  }
  EXPECT_GE(res.loadSteps, opt.loadSteps);
  EXPECT_GT(res.newtonIterations, 0);
  // Large deflection: the tip moved up but less than linear theory says, and stayed on an arc.
  EXPECT_GT(res.u(s.tip[1], 2), 0.2);
  EXPECT_LT(res.u(s.tip[1], 2), 0.5);
  EXPECT_LT(res.u(s.tip[1], 0), -0.02);
}

TEST(ReferenceSolver, ThrowsWhenNotConverging) {
  Strip s;
  const MatX3 uUnit = solveLinearStatic(s.shell, s.pinned, s.tipLoad(1.0));
  ReferenceOptions opt;
  opt.loadSteps = 1;
  opt.maxNewtonIterations = 1;
  try {
    solveStaticReference(s.shell, s.pinned, s.tipLoad(1.0 / uUnit(s.tip[1], 2)), opt);
    FAIL() << "expected NumericalError";
  } catch (const NumericalError& e) {
    EXPECT_NE(std::string(e.what()).find("did not converge"), std::string::npos) << e.what();
  }
}

TEST(ReferenceSolver, LinearSolveNeedsConstraints) {
  Strip s;
  EXPECT_THROW(solveLinearStatic(s.shell, {}, s.tipLoad(1.0)), NumericalError);
}

TEST(ImplicitReference, RestWithoutForceStaysPut) {
  Strip s;
  for (auto scheme : {ImplicitScheme::Euler, ImplicitScheme::BDF2}) {
    ImplicitReference sim(s.shell, s.pinned, 0.1, 1e-3, scheme);
    for (int k = 0; k < 5; ++k) sim.step(1e-3, MatX3::Zero(s.n(), 3));
    // Exactly for backward Euler; BDF2's extrapolated centre (12x_n − 3x_{n−1})/9 carries round-off.
    EXPECT_LE((sim.positions() - s.shell.rest()).cwiseAbs().maxCoeff(), 1e-15);
    EXPECT_LE(sim.velocities().cwiseAbs().maxCoeff(), 1e-12);
    if (scheme == ImplicitScheme::Euler)
      EXPECT_EQ((sim.positions() - s.shell.rest()).cwiseAbs().maxCoeff(), 0.0);
  }
}

// With extras (the anatomical model's attachment and couplings: ½uᵀK_x u, its own masses), long
// damped steps settle where the shell's and the extra forces balance the load.
TEST(ImplicitReference, ExtraStiffnessJoinsTheBalance) {
  Strip s;
  const int n = s.n();
  std::vector<Triplet> trip;
  for (int i = 0; i < 3 * n; ++i) trip.emplace_back(i, i, 50.0);  // dyn/cm on every DOF
  SparseMat Kx(3 * n, 3 * n);
  Kx.setFromTriplets(trip.begin(), trip.end());
  const MatX3 F = s.tipLoad(0.02);
  ImplicitReference sim(s.shell, s.pinned, 1.0, 0.0, ImplicitScheme::Euler, {},
                        ReferenceExtras{Kx, VecX::Constant(n, 2.0)});
  for (int k = 0; k < 20; ++k) sim.step(1e3, F);
  VecX g;
  s.shell.energy(sim.positions(), &g);
  g += Kx * flat(sim.displacement()) - flat(F);
  for (int p : s.pinned) g.segment<3>(3 * p).setZero();
  EXPECT_LE(g.norm(), 1e-6 * flat(F).norm());
  // The extra springs hold the tip: less deflection than the shell alone.
  ImplicitReference alone(s.shell, s.pinned, 1.0, 0.0);
  for (int k = 0; k < 20; ++k) alone.step(1e3, F);
  EXPECT_LT(sim.displacement().cwiseAbs().maxCoeff(), alone.displacement().cwiseAbs().maxCoeff());
}

// Released from a static deflection: the mechanical energy decays monotonically with damping.
TEST(ImplicitReference, EnergyDecaysWithDamping) {
  Strip s;
  const MatX3 uUnit = solveLinearStatic(s.shell, s.pinned, s.tipLoad(1.0));
  const auto st = solveStaticReference(s.shell, s.pinned, s.tipLoad(0.1 / uUnit(s.tip[1], 2)));
  for (auto scheme : {ImplicitScheme::Euler, ImplicitScheme::BDF2}) {
    ImplicitReference sim(s.shell, s.pinned, 0.5, 1e-4, scheme);
    sim.setState(st.x, MatX3::Zero(s.n(), 3));
    const double E0 = sim.mechanicalEnergy();
    ASSERT_GT(E0, 0.0);
    double prev = E0;
    const MatX3 zero = MatX3::Zero(s.n(), 3);
    for (int k = 0; k < 60; ++k) {  // ω₁ ≈ 0.8 rad/s: 3 s ≈ 0.4 periods
      sim.step(0.05, zero);
      const double E = sim.mechanicalEnergy();
      if (scheme == ImplicitScheme::Euler) EXPECT_LE(E, prev * (1 + 1e-12)) << "step " << k;
      prev = E;
    }
    EXPECT_LT(prev, 0.9 * E0);
    for (int p : s.pinned) EXPECT_EQ(sim.displacement().row(p).cwiseAbs().maxCoeff(), 0.0);
  }
}

// Without damping, the tip oscillates about rest: it swings through zero within one period.
TEST(ImplicitReference, UndampedBdf2Oscillates) {
  Strip s;
  const MatX3 uUnit = solveLinearStatic(s.shell, s.pinned, s.tipLoad(1.0));
  const auto st = solveStaticReference(s.shell, s.pinned, s.tipLoad(0.01 / uUnit(s.tip[1], 2)));
  ImplicitReference sim(s.shell, s.pinned, 0.0, 0.0, ImplicitScheme::BDF2);
  sim.setState(st.x, MatX3::Zero(s.n(), 3));
  const double z0 = st.u(s.tip[1], 2);
  double zmin = z0;
  const MatX3 zero = MatX3::Zero(s.n(), 3);
  for (int k = 0; k < 200; ++k) {  // ω₁ ≈ 0.8 rad/s: 10 s ≈ 1.3 periods
    sim.step(0.05, zero);
    zmin = std::min(zmin, sim.displacement()(s.tip[1], 2));
  }
  EXPECT_LT(zmin, -0.9 * z0);  // BDF2's numerical damping is small at this h
}

}  // namespace
}  // namespace myo
