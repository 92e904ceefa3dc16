#include "myoshell/verify/validation.h"

#include <Eigen/SparseCholesky>
#include <cmath>
#include <memory>
#include <numbers>
#include <sstream>

#include "myoshell/core/check.h"
#include "myoshell/core/errors.h"
#include "myoshell/core/timer.h"
#include "myoshell/mesh/edge_table.h"
#include "myoshell/mesh/primitives.h"
#include "myoshell/reduce/modal_analysis.h"
#include "myoshell/reduce/modal_warping.h"
#include "myoshell/verify/modal_statics.h"
#include "myoshell/verify/reference_solver.h"

namespace myo {

namespace {

// β₁L of the first clamped-free beam mode.
constexpr double kBeta1L = 1.8751040687119611;

DiscreteShell makeShell(const TriMesh& mesh, const ShellMaterial& material) {
  return DiscreteShell(mesh.V, mesh.F, buildEdgeTable(mesh.F, mesh.vertexCount()), material);
}

double relDiff(double a, double ref) { return std::abs(a - ref) / std::abs(ref); }

// P such that the linear full-space tip deflection is loadRatio·L.
double loadForRatio(const Strip& s, double loadRatio) {
  const MatX3 u1 = solveLinearStatic(s.shell, s.pinned, s.tipLoad(1.0));
  return loadRatio * s.def.length / s.tipDisplacement(u1).z();
}

ModalBasis stripBasis(const Strip& s, int d) {
  ModalSettings ms;
  ms.modeCount = d;
  return computeModalBasis(s.shell, s.pinned, ms);
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// Strip

Strip buildStrip(const StripDef& def) {
  MYO_CHECK(def.nx >= 2 && def.ny >= 2 && def.ny % 2 == 0,
            "strip needs nx ≥ 2 and an even ny ≥ 2, got " << def.nx << "×" << def.ny);
  MYO_CHECK(def.length > 0 && def.width > 0, "strip size must be positive");
  def.material.validate();
  const double dx = def.length / def.nx;
  TriMesh mesh = gridMesh(def.length + dx, def.width, def.nx + 1, def.ny, true);
  mesh.V.col(0).array() -= dx;
  DiscreteShell shell = makeShell(mesh, def.material);
  Strip s{def, std::move(mesh), std::move(shell), {}, {}, {}, {}};
  const int row = def.nx + 2;  // vertices per row
  for (int j = 0; j <= def.ny; ++j) {
    s.pinned.push_back(j * row);
    s.pinned.push_back(j * row + 1);
    s.tip.push_back(j * row + def.nx + 1);
    s.tipWeight.push_back((j == 0 || j == def.ny ? 0.5 : 1.0) / def.ny);
  }
  for (int i = 1; i <= def.nx + 1; ++i) s.centreLine.push_back((def.ny / 2) * row + i);
  return s;
}

MatX3 Strip::tipLoad(double P) const {
  MatX3 F = MatX3::Zero(mesh.vertexCount(), 3);
  for (size_t k = 0; k < tip.size(); ++k) F(tip[k], 2) = P * tipWeight[k];
  return F;
}

Vec3 Strip::tipDisplacement(const MatX3& u) const {
  Vec3 r = Vec3::Zero();
  for (size_t k = 0; k < tip.size(); ++k) r += tipWeight[k] * u.row(tip[k]).transpose();
  return r;
}

double Strip::tipRotation(const MatX3& u) const {
  const int a = centreLine[centreLine.size() - 2], b = centreLine.back();
  const Vec3 d = (mesh.V.row(b) + u.row(b) - mesh.V.row(a) - u.row(a)).transpose();
  return std::atan2(d.z(), d.x());
}

double Strip::lengthGrowth(const MatX3& u) const {
  double len = 0.0;
  for (size_t k = 1; k < centreLine.size(); ++k) {
    const int a = centreLine[k - 1], b = centreLine[k];
    len += (mesh.V.row(b) + u.row(b) - mesh.V.row(a) - u.row(a)).norm();
  }
  return len / def.length - 1.0;
}

double Strip::areaGrowth(const MatX3& u) const {
  double a = 0.0, a0 = 0.0;
  for (int t = 0; t < mesh.triangleCount(); ++t) {
    const Vec3 X0 = mesh.V.row(mesh.F(t, 0)), X1 = mesh.V.row(mesh.F(t, 1)), X2 = mesh.V.row(mesh.F(t, 2));
    const Vec3 x0 = X0 + u.row(mesh.F(t, 0)).transpose(), x1 = X1 + u.row(mesh.F(t, 1)).transpose(),
               x2 = X2 + u.row(mesh.F(t, 2)).transpose();
    a += 0.5 * (x1 - x0).cross(x2 - x0).norm();
    a0 += 0.5 * (X1 - X0).cross(X2 - X0).norm();
  }
  return a / a0 - 1.0;
}

double Strip::fieldError(const MatX3& u, const MatX3& ref) const {
  const VecX& m = shell.lumpedMass();
  double num = 0.0, den = 0.0;
  for (int i = 0; i < mesh.vertexCount(); ++i) {
    num += m[i] * (u.row(i) - ref.row(i)).squaredNorm();
    den += m[i] * ref.row(i).squaredNorm();
  }
  return std::sqrt(num / den);
}

// ---------------------------------------------------------------------------------------------
// D_eff

BendingRigidity measureBendingRigidity(const StripDef& def) {
  const double kappa = 1e-4 / def.length;
  // k_B·E_B of a plain nx×ny grid of length len bent to (κx, κy): Q·area for a quadratic form Q.
  auto bend = [&](double len, int nx, double kx, double ky) {
    const TriMesh m = gridMesh(len, def.width, nx, def.ny, true);
    const DiscreteShell shell = makeShell(m, def.material);
    MatX3 x = m.V;
    for (int i = 0; i < x.rows(); ++i) {
      const double px = x(i, 0), py = x(i, 1) - 0.5 * def.width;
      x(i, 2) = 0.5 * (kx * px * px + ky * py * py);
    }
    return def.material.kB * shell.energy(x).EB;
  };
  const double dA = def.length * def.width;  // area difference between 2L and L strips
  auto density = [&](double kx, double ky) {  // energy per area / κ²
    return (bend(2 * def.length, 2 * def.nx, kx, ky) - bend(def.length, def.nx, kx, ky)) / (dA * kappa * kappa);
  };
  const double qxx = density(kappa, 0.0), qyy = density(0.0, kappa);
  const double qxy = 0.5 * (density(kappa, kappa) - qxx - qyy);
  // Relaxed: the same cylinder imposed on the two end columns at each end only, the interior z
  // free to minimise the linearized bending energy ½zᵀK_zz z (at a flat rest K's z-block is the
  // bending part alone, decoupled from the membrane).
  auto relaxed = [&](double len, int nx) {
    const TriMesh m = gridMesh(len, def.width, nx, def.ny, true);
    const DiscreteShell shell = makeShell(m, def.material);
    const SparseMat K = shell.stiffnessAtRest();
    const int n = m.vertexCount();
    std::vector<int> zIndex(n);
    std::vector<int> freeIdx, fixedIdx;
    for (int v = 0; v < n; ++v) {
      const int i = v % (nx + 1);
      const bool fixed = i <= 1 || i >= nx - 1;
      (fixed ? fixedIdx : freeIdx).push_back(v);
    }
    std::vector<int> pos(n);
    for (size_t k = 0; k < freeIdx.size(); ++k) pos[freeIdx[k]] = static_cast<int>(k);
    for (size_t k = 0; k < fixedIdx.size(); ++k) pos[fixedIdx[k]] = static_cast<int>(k);
    std::vector<char> isFree(n, 0);
    for (int v : freeIdx) isFree[v] = 1;
    VecX z0(n);
    for (int v = 0; v < n; ++v) z0[v] = 0.5 * m.V(v, 0) * m.V(v, 0);  // κ = 1 (linear)
    std::vector<Triplet> tff;
    VecX rhs = VecX::Zero(freeIdx.size());
    for (int col = 0; col < K.outerSize(); ++col)
      for (SparseMat::InnerIterator it(K, col); it; ++it) {
        if (it.row() % 3 != 2 || it.col() % 3 != 2) continue;
        const int a = it.row() / 3, b = it.col() / 3;
        if (!isFree[a]) continue;
        if (isFree[b]) tff.emplace_back(pos[a], pos[b], it.value());
        else rhs[pos[a]] -= it.value() * z0[b];
      }
    SparseMat Kff(freeIdx.size(), freeIdx.size());
    Kff.setFromTriplets(tff.begin(), tff.end());
    Eigen::SimplicialLDLT<SparseMat> ldlt(Kff);
    const VecX zf = ldlt.solve(rhs);
    VecX z = z0;
    for (size_t k = 0; k < freeIdx.size(); ++k) z[freeIdx[k]] = zf[k];
    double e = 0.0;
    for (int col = 0; col < K.outerSize(); ++col)
      for (SparseMat::InnerIterator it(K, col); it; ++it)
        if (it.row() % 3 == 2 && it.col() % 3 == 2) e += 0.5 * z[it.row() / 3] * it.value() * z[it.col() / 3];
    return e;
  };
  BendingRigidity r;
  r.relaxed = 2.0 * (relaxed(2 * def.length, 2 * def.nx) - relaxed(def.length, def.nx)) / dA;
  r.cylinder = 2.0 * qxx;
  r.anticlastic = 2.0 * (qxx - qxy * qxy / qyy);
  r.poisson = qxy / qyy;
  return r;
}

// ---------------------------------------------------------------------------------------------
// Cases

double AccuracyCase::get(const std::string& key) const {
  for (const auto& [k, v] : extra)
    if (k == key) return v;
  MYO_CHECK(false, "accuracy case '" << name << "' has no value '" << key << "'");
  return 0.0;
}

bool ValidationReport::allPassed() const {
  for (const auto& c : cases)
    if (!c.passed) return false;
  return true;
}

AccuracyCase cantileverSmallLoad(const StripDef& def, int d, double loadRatio) {
  const Strip s = buildStrip(def);
  const double P = loadForRatio(s, loadRatio);
  const MatX3 F = s.tipLoad(P);
  const StaticReferenceResult ref = solveStaticReference(s.shell, s.pinned, F);
  const MatX3 uFem = solveLinearStatic(s.shell, s.pinned, F);
  const ModalBasis basis = stripBasis(s, d);
  const MatX3 Ff = gatherFree(basis, F);
  const StaticSolveResult lin = solveStaticLinear(basis, Ff);
  StaticSolveSettings ws;
  ws.loadSteps = 2;
  const StaticSolveResult warp = solveStaticWarped(basis, Ff, ws);
  if (!warp.converged) throw NumericalError("cantileverSmallLoad: the warped static solve did not converge");
  const MatX3 uLin = scatterToFull(basis, lin.u), uWarp = scatterToFull(basis, warp.u);

  const Vec3 tRef = s.tipDisplacement(ref.u), tW = s.tipDisplacement(uWarp), tL = s.tipDisplacement(uLin);
  const BendingRigidity D = measureBendingRigidity(def);
  const double L = def.length, w = def.width, rhoT = def.material.density * def.material.thickness;
  auto beamTip = [&](double Deff) { return P * L * L * L / (3.0 * Deff * w); };
  auto beamOmega = [&](double Deff) { return kBeta1L * kBeta1L * std::sqrt(Deff / (rhoT * L * L * L * L)); };
  const double omegaModal = std::sqrt(basis.lambda[0]);

  AccuracyCase c;
  std::ostringstream name;
  name << "cantilever_small_load_" << def.nx << "x" << def.ny;
  c.name = name.str();
  c.description = "clamped strip, transverse end load, linear tip deflection 1% of L: reduced vs full-space "
                  "static deflection, and beam theory with D_eff from E_B";
  c.d = d;
  c.quantity = "tip deflection z (cm)";
  c.reference = tRef.z();
  c.warped = tW.z();
  c.linear = tL.z();
  c.metric = "tip (mean tip-row displacement vector)";
  c.errorWarped = (tW - tRef).norm() / tRef.norm();
  c.errorLinear = (tL - tRef).norm() / tRef.norm();
  const double fieldW = s.fieldError(uWarp, ref.u), fieldL = s.fieldError(uLin, ref.u);
  const double beamErr = relDiff(tRef.z(), beamTip(D.relaxed));
  const double omegaErr = relDiff(omegaModal, beamOmega(D.relaxed));
  c.extra = {{"load_P_dyn", P},
             {"field_error_warped", fieldW},
             {"field_error_linear", fieldL},
             {"linear_fem_tip_z", s.tipDisplacement(uFem).z()},
             {"D_eff_relaxed", D.relaxed},
             {"D_eff_cylinder", D.cylinder},
             {"bending_poisson_ratio", D.poisson},
             {"beam_tip_z", beamTip(D.relaxed)},
             {"beam_tip_error", beamErr},
             {"beam_tip_z_cylinder", beamTip(D.cylinder)},
             {"beam_tip_error_cylinder", relDiff(tRef.z(), beamTip(D.cylinder))},
             {"omega1_modal", omegaModal},
             {"omega1_beam", beamOmega(D.relaxed)},
             {"omega1_error", omegaErr},
             {"omega1_beam_cylinder", beamOmega(D.cylinder)},
             {"omega1_error_cylinder", relDiff(omegaModal, beamOmega(D.cylinder))},
             {"reference_seconds", ref.seconds},
             {"reference_newton_iterations", double(ref.newtonIterations)},
             {"reference_relative_residual", ref.relativeResidual}};
  c.bound = "warped, linear vs reference ≤ 2% (tip and field); beam tip and ω₁ with the relaxed D_eff ≤ 5%";
  c.passed = c.errorWarped <= 0.02 && c.errorLinear <= 0.02 && fieldW <= 0.02 && fieldL <= 0.02 &&
             beamErr <= 0.05 && omegaErr <= 0.05;
  return c;
}

AccuracyCase cantileverLargeLoad(const StripDef& def, int d, double loadRatio) {
  const Strip s = buildStrip(def);
  const double P = loadForRatio(s, loadRatio);
  const MatX3 F = s.tipLoad(P);
  ReferenceOptions ro;
  ro.loadSteps = 20;
  const StaticReferenceResult ref = solveStaticReference(s.shell, s.pinned, F, ro);
  const ModalBasis basis = stripBasis(s, d);
  const MatX3 Ff = gatherFree(basis, F);
  const StaticSolveResult lin = solveStaticLinear(basis, Ff);
  StaticSolveSettings ws;
  ws.loadSteps = 20;
  ws.maxIterations = 400;
  Stopwatch clock;
  const StaticSolveResult warp = solveStaticWarped(basis, Ff, ws);
  const double warpSeconds = clock.seconds();
  if (!warp.converged) throw NumericalError("cantileverLargeLoad: the warped static solve did not converge");
  const MatX3 uLin = scatterToFull(basis, lin.u), uWarp = scatterToFull(basis, warp.u);
  const Vec3 tRef = s.tipDisplacement(ref.u), tW = s.tipDisplacement(uWarp), tL = s.tipDisplacement(uLin);
  constexpr double kDeg = 180.0 / std::numbers::pi;

  AccuracyCase c;
  std::ostringstream name;
  name << "cantilever_large_load_" << def.nx << "x" << def.ny;
  c.name = name.str();
  std::ostringstream desc;
  desc << "clamped strip, transverse end load with linear tip deflection " << loadRatio
       << "·L (large rotation): reduced vs full-space static field";
  c.description = desc.str();
  c.d = d;
  c.quantity = "tip deflection z (cm)";
  c.reference = tRef.z();
  c.warped = tW.z();
  c.linear = tL.z();
  c.metric = "field M-norm";
  c.errorWarped = s.fieldError(uWarp, ref.u);
  c.errorLinear = s.fieldError(uLin, ref.u);
  const double ratio = c.errorLinear / c.errorWarped;
  c.extra = {{"load_P_dyn", P},
             {"error_ratio_linear_over_warped", ratio},
             {"tip_error_warped", (tW - tRef).norm() / tRef.norm()},
             {"tip_error_linear", (tL - tRef).norm() / tRef.norm()},
             {"tip_x_reference", tRef.x()},
             {"tip_x_warped", tW.x()},
             {"tip_x_linear", tL.x()},
             {"tip_rotation_deg_reference", s.tipRotation(ref.u) * kDeg},
             {"tip_rotation_deg_warped", s.tipRotation(uWarp) * kDeg},
             {"tip_rotation_deg_linear", s.tipRotation(uLin) * kDeg},
             {"length_growth_reference", s.lengthGrowth(ref.u)},
             {"length_growth_warped", s.lengthGrowth(uWarp)},
             {"length_growth_linear", s.lengthGrowth(uLin)},
             {"area_growth_reference", s.areaGrowth(ref.u)},
             {"area_growth_warped", s.areaGrowth(uWarp)},
             {"area_growth_linear", s.areaGrowth(uLin)},
             {"reference_seconds", ref.seconds},
             {"reference_newton_iterations", double(ref.newtonIterations)},
             {"reference_load_steps", double(ref.loadSteps)},
             {"reference_relative_residual", ref.relativeResidual},
             {"warped_newton_iterations", double(warp.iterations)},
             {"warped_seconds", warpSeconds}};
  c.bound = "tip rotation ≥ 45° and warped field error ≤ linear/3";
  c.passed = s.tipRotation(ref.u) * kDeg >= 45.0 && ratio >= 3.0;
  return c;
}

AccuracyCase releasedTip(const StripDef& def, int d, double loadRatio, double periods,
                         int stepsPerPeriod, double dampingRatio, ImplicitScheme scheme) {
  MYO_CHECK(periods > 0 && stepsPerPeriod >= 10, "releasedTip: periods > 0, stepsPerPeriod ≥ 10");
  const Strip s = buildStrip(def);
  const double P = loadForRatio(s, loadRatio);
  const MatX3 F = s.tipLoad(P);
  const int n = s.mesh.vertexCount();
  const MatX3 zero = MatX3::Zero(n, 3);

  const StaticReferenceResult st = solveStaticReference(s.shell, s.pinned, F);
  auto basis = std::make_shared<ModalBasis>(stripBasis(s, d));
  const MatX3 Ff = gatherFree(*basis, F);
  StaticSolveSettings ws;
  ws.loadSteps = 5;
  const StaticSolveResult warp0 = solveStaticWarped(*basis, Ff, ws);
  if (!warp0.converged) throw NumericalError("releasedTip: the warped static solve did not converge");
  const StaticSolveResult lin0 = solveStaticLinear(*basis, Ff);

  const double omega1 = std::sqrt(basis->lambda[0]);
  const double period = 2.0 * std::numbers::pi / omega1;
  const double h = period / stepsPerPeriod;
  const int steps = static_cast<int>(std::lround(periods * stepsPerPeriod));
  const double xi = 2.0 * dampingRatio * omega1;

  ImplicitReference ref(s.shell, s.pinned, xi, 0.0, scheme);
  ref.setState(st.x, zero);
  ModalWarpingSettings mws;
  mws.dt = h;
  mws.stepper = ModalStepper::Exact;
  mws.rayleighMass = xi;
  mws.precision = ModalPrecision::Double;
  mws.channel = "validation";
  ModalWarpingIntegrator warped(basis, mws);
  warped.setState(warp0.q, VecX::Zero(basis->modeCount()));
  mws.warping = false;
  ModalWarpingIntegrator linear(basis, mws);
  linear.setState(lin0.q, VecX::Zero(basis->modeCount()));

  auto tipZ = [&](const MatX3& freeU) { return s.tipDisplacement(scatterToFull(*basis, freeU)).z(); };
  double maxRef = std::abs(s.tipDisplacement(st.u).z());
  double maxErrW = std::abs(tipZ(warped.freeDisplacement()) - s.tipDisplacement(st.u).z());
  double maxErrL = std::abs(tipZ(linear.freeDisplacement()) - s.tipDisplacement(st.u).z());
  double sumW = maxErrW * maxErrW, sumL = maxErrL * maxErrL, sumR = maxRef * maxRef;
  double zRef = 0, zW = 0, zL = 0;
  Stopwatch refClock;
  double refSeconds = 0.0;
  for (int k = 0; k < steps; ++k) {
    refClock.restart();
    ref.step(h, zero);
    refSeconds += refClock.seconds();
    warped.step();
    linear.step();
    zRef = s.tipDisplacement(ref.displacement()).z();
    zW = tipZ(warped.freeDisplacement());
    zL = tipZ(linear.freeDisplacement());
    maxRef = std::max(maxRef, std::abs(zRef));
    maxErrW = std::max(maxErrW, std::abs(zW - zRef));
    maxErrL = std::max(maxErrL, std::abs(zL - zRef));
    sumW += (zW - zRef) * (zW - zRef);
    sumL += (zL - zRef) * (zL - zRef);
    sumR += zRef * zRef;
  }

  AccuracyCase c;
  std::ostringstream name;
  name << "released_tip_" << def.nx << "x" << def.ny;
  c.name = name.str();
  std::ostringstream desc;
  desc << "strip released from its static deflection under an end load (linear tip deflection " << loadRatio
       << "·L): tip trajectory over " << periods << " periods, reduced (exact per-mode step) vs full-space "
       << (scheme == ImplicitScheme::BDF2 ? "BDF2" : "backward Euler") << ", h = T1/" << stepsPerPeriod;
  c.description = desc.str();
  c.d = d;
  c.quantity = "tip deflection z at the final time (cm)";
  c.reference = zRef;
  c.warped = zW;
  c.linear = zL;
  c.metric = "tip trajectory: max_t |z − z_ref| / max_t |z_ref|";
  c.errorWarped = maxErrW / maxRef;
  c.errorLinear = maxErrL / maxRef;
  c.extra = {{"load_P_dyn", P},
             {"initial_tip_z_reference", s.tipDisplacement(st.u).z()},
             {"initial_tip_z_warped", tipZ(warp0.u)},
             {"initial_tip_z_linear", tipZ(lin0.u)},
             {"rms_error_warped", std::sqrt(sumW / sumR)},
             {"rms_error_linear", std::sqrt(sumL / sumR)},
             {"omega1", omega1},
             {"h_s", h},
             {"steps", double(steps)},
             {"xi_per_s", xi},
             {"reference_seconds", refSeconds},
             {"reference_newton_iterations", double(ref.totalNewtonIterations())}};
  c.bound = "warped trajectory error ≤ 10% and ≤ the linear one";
  c.passed = c.errorWarped <= 0.10 && c.errorWarped <= c.errorLinear;
  return c;
}

ValidationReport runValidation(const ValidationSettings& settings) {
  Stopwatch clock;
  ValidationReport r;
  r.cases.push_back(cantileverSmallLoad(settings.coarse, settings.modes, settings.smallLoad));
  r.cases.push_back(cantileverSmallLoad(settings.fine, settings.modes, settings.smallLoad));
  r.cases.push_back(cantileverLargeLoad(settings.coarse, settings.modes, settings.largeLoad));
  r.cases.push_back(cantileverLargeLoad(settings.fine, settings.modes, settings.largeLoad));
  if (settings.dynamic)
    r.cases.push_back(releasedTip(settings.coarse, settings.modes, settings.dynamicLoad, settings.dynamicPeriods,
                                  settings.stepsPerPeriod, settings.dampingRatio));
  r.seconds = clock.seconds();
  return r;
}

}  // namespace myo
