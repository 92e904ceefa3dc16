// The modal warping integrator and the static modal solves.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <sstream>

#include "myoshell/mesh/edge_table.h"
#include "myoshell/mesh/primitives.h"
#include "myoshell/reduce/modal_analysis.h"
#include "myoshell/reduce/modal_warping.h"
#include "myoshell/verify/modal_statics.h"
#include "myoshell/shell/discrete_shell.h"

namespace myo {
namespace {

constexpr int kNx = 20, kNy = 4;

DiscreteShell makeWarpingShell(const MatX3& V, const MatX3i& F) {
  return DiscreteShell(V, F, buildEdgeTable(F, static_cast<int>(V.rows())), ShellMaterial{});
}

// A slightly curved cantilever strip 10 cm × 2 cm, clamped on its first two columns.
TriMesh strip() {
  TriMesh m = gridMesh(10.0, 2.0, kNx, kNy);
  for (Eigen::Index i = 0; i < m.V.rows(); ++i) m.V(i, 2) = 0.01 * m.V(i, 0) * m.V(i, 0) + 0.05 * m.V(i, 1);
  return m;
}

std::vector<int> clampedColumns() {
  std::vector<int> v;
  for (int j = 0; j <= kNy; ++j)
    for (int i = 0; i < 2; ++i) v.push_back(j * (kNx + 1) + i);
  return v;
}

std::shared_ptr<const ModalBasis> stripBasis(int d, const MatX3& V, const MatX3i& F) {
  ModalSettings s;
  s.modeCount = d;
  s.solver = EigenSolverKind::Dense;
  s.denseMaxDofs = 100000;
  return std::make_shared<const ModalBasis>(computeModalBasis(makeWarpingShell(V, F), clampedColumns(), s));
}

// A tip load (dyn) in direction dir on the last column, as a free f×3 field.
MatX3 tipLoad(const ModalBasis& b, const MatX3& V, const Vec3& dir) {
  MatX3 F = MatX3::Zero(b.freeCount(), 3);
  for (int i = 0; i < b.freeCount(); ++i)
    if (b.freeVertices[i] % (kNx + 1) == kNx) F.row(i) = dir.transpose();
  static_cast<void>(V);
  return F;
}

// The tip load along dir scaled so that the linear static tip deflection is `fraction` of the
// strip length (10 cm): 0.3 gives tip rotations of a few tenths of a radian.
MatX3 scaledTipLoad(const ModalBasis& b, const MatX3& V, const Vec3& dir, double fraction) {
  const MatX3 F = tipLoad(b, V, dir);
  const double umax = solveStaticLinear(b, F).u.rowwise().norm().maxCoeff();
  return F * (fraction * 10.0 / umax);
}

// Rayleigh damping that makes mode 0 and mode d−1 critically damped (all modes decay at a rate
// of at least √λ_0).
void criticalDamping(const ModalBasis& b, ModalWarpingSettings& s) {
  s.rayleighMass = std::sqrt(b.lambda[0]);
  s.rayleighStiffness = 1.0 / std::sqrt(b.lambda[b.modeCount() - 1]);
}

double relErr(const MatX3& a, const MatX3& b) { return (a - b).norm() / std::max(b.norm(), 1e-300); }

// A synthetic basis with chosen λ: f = d free vertices of a 2d-vertex "mesh", Φ_i = e_x-rows.
std::shared_ptr<const ModalBasis> syntheticBasis(const VecX& lambda) {
  auto b = std::make_shared<ModalBasis>();
  const int d = static_cast<int>(lambda.size());
  b->fullVertexCount = 2 * d;
  for (int i = 0; i < d; ++i) b->freeVertices.push_back(2 * i);
  b->Phi = MatX::Zero(3 * d, d);
  for (int j = 0; j < d; ++j) b->Phi(3 * j, j) = 1.0;  // mode j moves vertex j along x
  b->Psi = MatX::Zero(3 * d, d);
  b->lambda = lambda;
  b->freeMass = VecX::Ones(d);
  return b;
}

// RK4 of q̈ + c q̇ + λ q = f over time T with n substeps.
std::pair<double, double> rk4(double q, double v, double lambda, double c, double f, double T, int n) {
  const double h = T / n;
  auto acc = [&](double qq, double vv) { return f - c * vv - lambda * qq; };
  for (int i = 0; i < n; ++i) {
    const double k1q = v, k1v = acc(q, v);
    const double k2q = v + 0.5 * h * k1v, k2v = acc(q + 0.5 * h * k1q, v + 0.5 * h * k1v);
    const double k3q = v + 0.5 * h * k2v, k3v = acc(q + 0.5 * h * k2q, v + 0.5 * h * k2v);
    const double k4q = v + h * k3v, k4v = acc(q + h * k3q, v + h * k3v);
    q += h / 6 * (k1q + 2 * k2q + 2 * k3q + k4q);
    v += h / 6 * (k1v + 2 * k2v + 2 * k3v + k4v);
  }
  return {q, v};
}

TEST(ModalWarping, ExactStepperMatchesFineRk4) {
  // Undamped, under-, critically and over-damped modes, a zero (rigid) and a round-off negative λ.
  VecX lambda(8);
  lambda << 0.0, -1e-12, 1.0, 100.0, 2.5e3, 1e4, 4e5, 1e-7;
  for (auto [xi, zeta] : {std::pair{0.0, 0.0}, {20.0, 0.0}, {20.0, 1e-3}, {300.0, 0.0}, {0.5, 0.05}}) {
    ModalWarpingSettings s;
    s.dt = 1.0 / 60.0;
    s.warping = false;
    s.precision = ModalPrecision::Double;
    s.rayleighMass = xi;
    s.rayleighStiffness = zeta;
    ModalWarpingIntegrator integ(syntheticBasis(lambda), s);
    const int d = static_cast<int>(lambda.size());
    VecX q0(d), v0(d);
    for (int j = 0; j < d; ++j) {
      q0[j] = 0.3 - 0.1 * j;
      v0[j] = 0.05 * j - 0.2;
    }
    integ.setState(q0, v0);
    MatX3 F = MatX3::Zero(d, 3);
    for (int j = 0; j < d; ++j) F(j, 0) = 1.0 + 0.5 * j;  // f̃_j = F(j, 0)
    const int steps = 5;
    for (int k = 0; k < steps; ++k) integ.step(F);
    for (int j = 0; j < d; ++j) {
      const double c = xi + zeta * lambda[j];
      const auto [q, v] = rk4(q0[j], v0[j], lambda[j], c, F(j, 0), steps * s.dt, 200000);
      const double scale = std::max({1.0, std::abs(q), std::abs(v)});
      EXPECT_NEAR(integ.q()[j], q, 1e-10 * scale) << "mode " << j << " xi " << xi << " zeta " << zeta;
      EXPECT_NEAR(integ.qdot()[j], v, 1e-10 * scale) << "mode " << j << " xi " << xi << " zeta " << zeta;
    }
  }
}

TEST(ModalWarping, SemiImplicitMatchesItsRecurrenceAndRefusesUnstableSteps) {
  VecX lambda(3);
  lambda << 1.0, 100.0, 3600.0;
  ModalWarpingSettings s;
  s.stepper = ModalStepper::SemiImplicit;
  s.warping = false;
  s.precision = ModalPrecision::Double;
  s.dt = 0.01;
  s.rayleighMass = 0.3;
  ModalWarpingIntegrator integ(syntheticBasis(lambda), s);
  MatX3 F = MatX3::Zero(3, 3);
  F.col(0) << 1.0, 2.0, 3.0;
  double q = 0, v = 0;
  for (int k = 0; k < 10; ++k) {
    integ.step(F);
    v += s.dt * (3.0 - 0.3 * v - 3600.0 * q);
    q += s.dt * v;
  }
  EXPECT_NEAR(integ.q()[2], q, 1e-14);
  EXPECT_NEAR(integ.qdot()[2], v, 1e-12);

  // h·√λ_max = 1/60·60 = 1 is fine; 1/30·60 = 2 is not.
  s.channel = "zygomatic";
  s.dt = 1.0 / 30.0;
  std::ostringstream expected;
  expected << "channel 'zygomatic': semi-implicit Euler is unstable at dt = " << s.dt
           << " s: the highest mode has lambda_max = " << 3600.0
           << " 1/s^2, so dt must be below 2/sqrt(lambda_max) = " << 2.0 / 60.0
           << " s (use the exact stepper, a smaller dt or fewer modes)";
  try {
    ModalWarpingIntegrator bad(syntheticBasis(lambda), s);
    FAIL() << "an unstable semi-implicit step was accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), expected.str());
  }
  // Scaling the stiffness past the limit is refused too, and the old scale is kept.
  s.dt = 1.0 / 60.0;
  ModalWarpingIntegrator ok(syntheticBasis(lambda), s);
  EXPECT_THROW(ok.setStiffnessScale(4.0), InputError);
  EXPECT_EQ(ok.stiffnessScale(), 1.0);
  EXPECT_NEAR(ok.maxSemiImplicitDt(), 2.0 / 60.0, 1e-15);
  // The exact stepper takes any step.
  s.stepper = ModalStepper::Exact;
  s.dt = 1.0;
  EXPECT_NO_THROW(ModalWarpingIntegrator(syntheticBasis(lambda), s));
}

TEST(ModalWarping, FreeShellStaysPutWithoutForces) {
  const TriMesh m = icosphere(2.0, 2);
  ModalSettings ms;
  ms.modeCount = 12;
  auto b = std::make_shared<const ModalBasis>(computeModalBasis(makeWarpingShell(m.V, m.F), {}, ms));
  for (ModalPrecision p : {ModalPrecision::Float, ModalPrecision::Double}) {
    ModalWarpingSettings s;
    s.precision = p;
    ModalWarpingIntegrator integ(b, s);
    const MatX3 zero = MatX3::Zero(b->freeCount(), 3);
    for (int k = 0; k < 100; ++k) integ.step(zero);
    EXPECT_TRUE(integ.isAtRest(1e-300));
    EXPECT_EQ(integ.freeDisplacement().cwiseAbs().maxCoeff(), 0.0);
    integ.step();
    EXPECT_EQ(integ.freeDisplacement().cwiseAbs().maxCoeff(), 0.0);
  }
}

TEST(ModalWarping, DampedReleaseLosesEnergyMonotonically) {
  const TriMesh m = strip();
  auto b = stripBasis(10, m.V, m.F);
  ModalWarpingSettings s;
  s.rayleighMass = 1.0;
  s.rayleighStiffness = 1e-4;
  ModalWarpingIntegrator integ(b, s);
  // Release from the static deflection under a tip load.
  const StaticSolveResult st = solveStaticLinear(*b, scaledTipLoad(*b, m.V, Vec3(0, 0, 1.0), 0.3));
  integ.setState(st.q, VecX::Zero(b->modeCount()));
  double e = integ.energy();
  const double e0 = e;
  ASSERT_GT(e0, 0.0);
  for (int k = 0; k < 600; ++k) {
    integ.step();
    const double en = integ.energy();
    EXPECT_LE(en, e * (1.0 + 1e-12)) << "step " << k;
    e = en;
  }
  EXPECT_LT(e, 1e-3 * e0);
  EXPECT_FALSE(integ.isAtRest(1e-12));
  integ.reset();
  EXPECT_TRUE(integ.isAtRest(1e-300));
  EXPECT_EQ(integ.freeDisplacement().cwiseAbs().maxCoeff(), 0.0);
}

TEST(ModalWarping, RotatingMeshPinsAndLoadRotatesTheAnswer) {
  const TriMesh m = strip();
  const Mat3 Q = Eigen::AngleAxisd(0.7, Vec3(1, 2, -0.5).normalized()).toRotationMatrix();
  const MatX3 VQ = m.V * Q.transpose();
  auto b = stripBasis(12, m.V, m.F);
  auto bq = stripBasis(12, VQ, m.F);
  ModalWarpingSettings s;
  s.precision = ModalPrecision::Double;
  s.dt = 0.1;
  criticalDamping(*b, s);
  s.rayleighMass *= 0.3;  // underdamped: overshoot exercises larger rotations
  ModalWarpingIntegrator a(b, s), aq(bq, s);
  const MatX3 F = scaledTipLoad(*b, m.V, Vec3(0.1, 0.2, 1.0), 0.3);
  const MatX3 FQ = F * Q.transpose();
  for (int k = 0; k < 100; ++k) {
    a.step(F);
    aq.step(FQ);
  }
  const MatX3 u = a.freeDisplacement();
  // Large enough to exercise the warp: tip rotation of a few tenths of a radian.
  EXPECT_GT(a.freeRotations().rowwise().norm().maxCoeff(), 0.1);
  EXPECT_LT(relErr(aq.freeDisplacement(), u * Q.transpose()), 1e-8);
  // The static warped solve is equivariant too.
  const StaticSolveResult r = solveStaticWarped(*b, F), rq = solveStaticWarped(*bq, FQ);
  ASSERT_TRUE(r.converged && rq.converged);
  EXPECT_LT(relErr(rq.u, r.u * Q.transpose()), 1e-8);
}

TEST(ModalWarping, WarpingOffIsPlainLinearModalDisplacement) {
  const TriMesh m = strip();
  auto b = stripBasis(10, m.V, m.F);
  ModalWarpingSettings s;
  s.precision = ModalPrecision::Double;
  s.warping = false;
  ModalWarpingIntegrator integ(b, s);
  const MatX3 F = scaledTipLoad(*b, m.V, Vec3(0.03, 0.0, 1.0), 0.3);
  for (int k = 0; k < 20; ++k) integ.step(F);
  const VecX uRef = b->Phi * integ.q();
  EXPECT_LT((VecX(flat(integ.freeDisplacement())) - uRef).cwiseAbs().maxCoeff(), 1e-14 * uRef.cwiseAbs().maxCoeff());
  EXPECT_EQ(integ.freeRotations().cwiseAbs().maxCoeff(), 0.0);
  // Forces are not rotated: the modal force is ΦᵀF.
  EXPECT_LT((modalForce(*b, integ.q(), F, false) - b->Phi.transpose() * flat(F)).norm(), 1e-12);
}

TEST(ModalWarping, FloatPathAgreesWithDoubleTo1e5) {
  const TriMesh m = strip();
  auto b = stripBasis(16, m.V, m.F);
  ModalWarpingSettings s;
  s.rayleighMass = 1.0;
  s.precision = ModalPrecision::Double;
  ModalWarpingIntegrator dbl(b, s);
  s.precision = ModalPrecision::Float;
  ModalWarpingIntegrator flt(b, s);
  const MatX3 F = scaledTipLoad(*b, m.V, Vec3(0.0, 0.2, 1.0), 0.3);
  for (int k = 0; k < 60; ++k) {
    dbl.step(F);
    flt.step(F);
    EXPECT_LT(relErr(flt.freeDisplacement(), dbl.freeDisplacement()), 1e-5) << "step " << k;
  }
  EXPECT_LT((flt.q() - dbl.q()).norm(), 1e-5 * dbl.q().norm());
}

// The float read runs whole chunks of 8 modes over q padded with zeros and reads the last vertices
// from a padded copy: mode counts below 8 and not a multiple of 8, warped and linear, agree with
// the double path.
TEST(ModalWarping, FloatPathAgreesWithDoubleForModeCountsOffTheChunk) {
  const TriMesh m = strip();
  for (int d : {1, 3, 7, 13}) {
    auto b = stripBasis(d, m.V, m.F);
    const MatX3 F = scaledTipLoad(*b, m.V, Vec3(0.0, 0.2, 1.0), 0.3);
    for (bool warping : {true, false}) {
      ModalWarpingSettings s;
      s.rayleighMass = 1.0;
      s.warping = warping;
      s.precision = ModalPrecision::Double;
      ModalWarpingIntegrator dbl(b, s);
      s.precision = ModalPrecision::Float;
      ModalWarpingIntegrator flt(b, s);
      for (int k = 0; k < 30; ++k) {
        dbl.step(F);
        flt.step(F);
      }
      EXPECT_LT(relErr(flt.freeDisplacement(), dbl.freeDisplacement()), 1e-5) << "d " << d << " warping " << warping;
      EXPECT_GT(dbl.freeDisplacement().norm(), 0.0);
    }
  }
}

TEST(ModalWarping, PinnedRowsOfTheFullMeshAreUntouched) {
  const TriMesh m = strip();
  auto b = stripBasis(8, m.V, m.F);
  ModalWarpingIntegrator integ(b, ModalWarpingSettings{});
  for (int k = 0; k < 10; ++k) integ.step(scaledTipLoad(*b, m.V, Vec3(0, 0, 1.0), 0.3));
  MatX3 full = MatX3::Constant(m.vertexCount(), 3, 7.25);
  integ.addDisplacementTo(full);
  for (int p : clampedColumns()) EXPECT_EQ(full.row(p), Eigen::RowVector3d(7.25, 7.25, 7.25));
  for (int i = 0; i < b->freeCount(); ++i)
    EXPECT_EQ(full.row(b->freeVertices[i]), integ.freeDisplacement().row(i) + Eigen::RowVector3d::Constant(7.25));
}

// Gravity-like load on every free vertex (m_i·g along dir), scaled like scaledTipLoad: exercises
// the dense-load projection path of step().
MatX3 scaledBodyLoad(const ModalBasis& b, const Vec3& dir, double fraction) {
  MatX3 F(b.freeCount(), 3);
  for (int i = 0; i < b.freeCount(); ++i) F.row(i) = b.freeMass[i] * dir.transpose();
  const double umax = solveStaticLinear(b, F).u.rowwise().norm().maxCoeff();
  return F * (fraction * 10.0 / umax);
}

class ModalWarpingLoads : public ::testing::TestWithParam<bool> {};

TEST_P(ModalWarpingLoads, FloatPathAgreesWithDoubleTo1e5) {
  const TriMesh m = strip();
  auto b = stripBasis(16, m.V, m.F);
  ModalWarpingSettings s;
  s.dt = 0.05;
  criticalDamping(*b, s);
  s.precision = ModalPrecision::Double;
  ModalWarpingIntegrator dbl(b, s);
  s.precision = ModalPrecision::Float;
  ModalWarpingIntegrator flt(b, s);
  const MatX3 F = GetParam() ? scaledBodyLoad(*b, Vec3(0.0, 0.3, -1.0), 0.4)
                             : scaledTipLoad(*b, m.V, Vec3(0.0, 0.3, -1.0), 0.4);
  for (int k = 0; k < 100; ++k) {
    dbl.step(F);
    flt.step(F);
    EXPECT_LT(relErr(flt.freeDisplacement(), dbl.freeDisplacement()), 1e-5) << "step " << k;
  }
}

TEST_P(ModalWarpingLoads, DampedDynamicsSettleOnTheStaticWarpedSolution) {
  const TriMesh m = strip();
  auto b = stripBasis(10, m.V, m.F);
  const MatX3 F = GetParam() ? scaledBodyLoad(*b, Vec3(0.0, 0.0, -1.0), 0.3)
                             : scaledTipLoad(*b, m.V, Vec3(0.0, 0.0, 1.0), 0.3);
  const StaticSolveResult lin = solveStaticLinear(*b, F);
  const StaticSolveResult st = solveStaticWarped(*b, F);
  ASSERT_TRUE(st.converged);
  EXPECT_LT(st.residual, 1e-12);
  EXPECT_LT(st.iterations, 15);  // Newton with the exact Jacobian converges fast
  // The warped tip is shorter along x than the linear one (the arc, not a shear).
  EXPECT_GT(relErr(st.u, lin.u), 1e-3);
  ModalWarpingSettings s;
  s.precision = ModalPrecision::Double;
  s.dt = 0.1;  // the exact stepper takes any step; 200 s of simulated time
  criticalDamping(*b, s);
  ModalWarpingIntegrator integ(b, s);
  for (int k = 0; k < 2000; ++k) integ.step(F);
  EXPECT_LT(relErr(integ.freeDisplacement(), st.u), 1e-8);
  // A tiny load: warped and linear agree to first order.
  const MatX3 f = F * 1e-6;
  EXPECT_LT(relErr(solveStaticWarped(*b, f).u, solveStaticLinear(*b, f).u), 1e-5);
  // Load continuation reaches the same answer.
  StaticSolveSettings cont;
  cont.loadSteps = 5;
  EXPECT_LT(relErr(solveStaticWarped(*b, F, cont).u, st.u), 1e-10);
}

INSTANTIATE_TEST_SUITE_P(TipAndBody, ModalWarpingLoads, ::testing::Bool());

TEST(ModalWarping, StiffnessScaleScalesTheStaticResponse) {
  const TriMesh m = strip();
  auto b = stripBasis(6, m.V, m.F);
  ModalWarpingSettings s;
  s.precision = ModalPrecision::Double;
  s.warping = false;
  s.dt = 0.1;
  criticalDamping(*b, s);
  ModalWarpingIntegrator integ(b, s);
  integ.setStiffnessScale(2.0);
  const MatX3 F = tipLoad(*b, m.V, Vec3(0.0, 0.0, 50.0));
  for (int k = 0; k < 2000; ++k) integ.step(F);
  EXPECT_LT(relErr(integ.freeDisplacement(), 0.5 * solveStaticLinear(*b, F).u), 1e-8);
  EXPECT_THROW(integ.setStiffnessScale(0.0), InputError);
}

TEST(ModalWarping, StaticSolvesNeedAConstrainedBasis) {
  const TriMesh m = icosphere(1.0, 1);
  ModalSettings ms;
  ms.modeCount = 8;
  const ModalBasis b = computeModalBasis(makeWarpingShell(m.V, m.F), {}, ms);
  const MatX3 F = MatX3::Ones(b.freeCount(), 3);
  EXPECT_THROW(solveStaticLinear(b, F), NumericalError);
  EXPECT_THROW(solveStaticWarped(b, F), NumericalError);
}

}  // namespace
}  // namespace myo
