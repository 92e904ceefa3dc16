#include "myoshell/verify/reference_solver.h"

#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <sstream>

#include "myoshell/core/check.h"
#include "myoshell/core/errors.h"
#include "myoshell/core/timer.h"

namespace myo {

namespace {

// Free-DOF bookkeeping: DOF 3i+c is free unless vertex i is pinned.
struct DofMap {
  std::vector<int> freeDof;  // ascending full indices of free DOFs
  std::vector<int> toFree;   // full index → free index, −1 for pinned

  DofMap(int n, const std::vector<int>& pinned) : toFree(3 * n, 0) {
    for (int p : pinned) {
      MYO_CHECK(p >= 0 && p < n, "pinned vertex " << p << " out of range [0, " << n << ")");
      for (int c = 0; c < 3; ++c) toFree[3 * p + c] = -1;
    }
    for (int i = 0; i < 3 * n; ++i)
      if (toFree[i] >= 0) {
        toFree[i] = static_cast<int>(freeDof.size());
        freeDof.push_back(i);
      }
  }
  int size() const { return static_cast<int>(freeDof.size()); }

  VecX restrict(const VecX& full) const {
    VecX r(size());
    for (int k = 0; k < size(); ++k) r[k] = full[freeDof[k]];
    return r;
  }
  SparseMat restrict(const SparseMat& full) const {
    std::vector<Triplet> trip;
    trip.reserve(full.nonZeros());
    for (int col = 0; col < full.outerSize(); ++col)
      for (SparseMat::InnerIterator it(full, col); it; ++it) {
        const int r = toFree[it.row()], c = toFree[it.col()];
        if (r >= 0 && c >= 0) trip.emplace_back(r, c, it.value());
      }
    SparseMat out(size(), size());
    out.setFromTriplets(trip.begin(), trip.end());
    return out;
  }
};

// The minimised objective: value, and (when non-null) the full 3n gradient and Hessian (exact or
// per-element PSD-projected).
using Objective = std::function<double(const MatX3& x, VecX* grad, SparseMat* hess, HessianMode mode)>;

// Solves H p = rhs with a sparse LDLᵀ; when the factorization fails or is not positive definite,
// adds a growing multiple of the mean diagonal and retries. Returns false when hopeless.
bool solveSpd(const SparseMat& H, const VecX& rhs, VecX& p, int& retries, bool regularize = true) {
  Eigen::SimplicialLDLT<SparseMat> ldlt;
  const double diagScale = std::max(H.diagonal().cwiseAbs().mean(), 1e-300);
  double reg = 0.0;
  for (int attempt = 0; attempt < (regularize ? 12 : 1); ++attempt) {
    if (reg > 0.0) {
      SparseMat Hr = H;
      for (int i = 0; i < Hr.rows(); ++i) Hr.coeffRef(i, i) += reg;
      ldlt.compute(Hr);
    } else {
      ldlt.compute(H);
    }
    const bool ok = ldlt.info() == Eigen::Success && ldlt.vectorD().minCoeff() > 0.0;
    if (ok) {
      p = ldlt.solve(rhs);
      if (p.allFinite()) return true;
    }
    if (!regularize) return false;
    ++retries;
    reg = reg == 0.0 ? 1e-10 * diagScale : reg * 10.0;
  }
  return false;
}

struct NewtonReport {
  bool converged = false;     // reached tol
  bool atFloor = false;       // stopped at the floor
  int iterations = 0;
  double residual = 0.0;
  std::string failure;        // why it failed (when !converged && !atFloor)
};

// Minimises f over the free DOFs starting from x (modified in place). Converged when
// ‖g_F‖ ≤ tol; accepted at the floor when no progress is possible and ‖g_F‖ ≤ floor.
NewtonReport newtonMinimize(const Objective& f, const DofMap& dofs, MatX3& x, double tol,
                            double floor, const ReferenceOptions& opt, int& retries) {
  NewtonReport rep;
  VecX g;
  SparseMat H;
  double fx = f(x, &g, &H, HessianMode::Exact);
  VecX gF = dofs.restrict(g);
  double best = std::numeric_limits<double>::infinity();
  int stalled = 0;  // iterations without a 10% residual decrease
  for (int it = 0;; ++it) {
    rep.residual = gF.norm();
    rep.iterations = it;
    if (!std::isfinite(rep.residual)) {
      rep.failure = "the residual is not finite";
      return rep;
    }
    if (rep.residual <= tol) {
      rep.converged = true;
      return rep;
    }
    if (it >= opt.maxNewtonIterations) {
      if (rep.residual <= floor) rep.atFloor = true;
      else rep.failure = "no convergence in " + std::to_string(opt.maxNewtonIterations) + " Newton iterations";
      return rep;
    }
    if (rep.residual < 0.9 * best) best = rep.residual, stalled = 0;
    else if (++stalled >= 5 && rep.residual <= floor) {  // round-off floor: no further progress
      rep.atFloor = true;
      return rep;
    }
    // Newton direction: the exact Hessian when it is positive definite (quadratic convergence
    // near a stable equilibrium), otherwise the per-element PSD projection (robust far from it).
    VecX p;
    if (!solveSpd(dofs.restrict(H), -gF, p, retries, false)) {
      f(x, nullptr, &H, HessianMode::Projected);
      if (!solveSpd(dofs.restrict(H), -gF, p, retries)) {
        rep.failure = "the Newton system could not be factorized even with regularization";
        return rep;
      }
    }
    double slope = gF.dot(p);
    if (!(slope < 0.0)) {  // not a descent direction (should not happen with a PSD Hessian)
      p = -gF;
      slope = -gF.squaredNorm();
    }
    auto trial = [&](double alpha) {
      MatX3 xt = x;
      auto xf = flat(xt);
      for (int k = 0; k < dofs.size(); ++k) xf[dofs.freeDof[k]] += alpha * p[k];
      return xt;
    };
    double alpha = 1.0;
    bool accepted = false;
    MatX3 xt;
    for (int ls = 0; ls <= opt.maxLineSearchHalvings; ++ls, alpha *= 0.5) {
      xt = trial(alpha);
      const double ft = f(xt, nullptr, nullptr, HessianMode::Exact);
      if (std::isfinite(ft) && ft <= fx + opt.armijo * alpha * slope) {
        accepted = true;
        break;
      }
      // Round-off regime: the predicted decrease is below what the energy can resolve. Take the
      // full step if it reduces the residual.
      if (ls == 0 && std::abs(slope) < 1e-11 * (std::abs(fx) + 1e-300)) {
        VecX gt;
        f(xt, &gt, nullptr, HessianMode::Exact);
        if (dofs.restrict(gt).norm() < rep.residual) {
          accepted = true;
          break;
        }
      }
    }
    if (!accepted) {
      if (rep.residual <= floor) rep.atFloor = true;
      else rep.failure = "the line search made no progress";
      return rep;
    }
    x = xt;
    fx = f(x, &g, &H, HessianMode::Exact);
    gF = dofs.restrict(g);
  }
}

// A residual norm (dyn) below which the gradient is round-off: positions of magnitude |X| carry
// absolute errors ε|X|, which the stiffest elements turn into forces ~ε·K_ii·|X| per DOF.
// Measured floors were ~100× below this bound.
double roundoffForce(const DiscreteShell& shell, const SparseMat& Krest) {
  const double size = std::max(shell.rest().cwiseAbs().maxCoeff(), 1e-300);
  const double eps = std::numeric_limits<double>::epsilon();
  return 10.0 * eps * Krest.diagonal().cwiseAbs().maxCoeff() * size * std::sqrt(double(Krest.rows()));
}

}  // namespace

StaticReferenceResult solveStaticReference(const DiscreteShell& shell, const std::vector<int>& pinned,
                                           const MatX3& F, const ReferenceOptions& options) {
  Stopwatch clock;
  const int n = shell.vertexCount();
  MYO_CHECK_EQ(F.rows(), n);
  MYO_CHECK(options.loadSteps >= 1, "loadSteps must be ≥ 1");
  const DofMap dofs(n, pinned);
  const MatX3& X = shell.rest();

  StaticReferenceResult res;
  res.x = X;
  const VecX Fflat = flat(F);
  const double Fnorm = dofs.restrict(Fflat).norm();
  if (Fnorm == 0.0) {  // E ≥ 0 = E(X̄): the rest state is the minimiser
    res.u = MatX3::Zero(n, 3);
    res.seconds = clock.seconds();
    return res;
  }

  const double roundoff = roundoffForce(shell, shell.stiffnessAtRest());
  double s = 0.0;                          // load fraction reached
  double ds = 1.0 / options.loadSteps;     // current increment
  int halvings = 0;
  while (s < 1.0 - 1e-12) {
    const double sNext = std::min(1.0, s + ds);
    const bool last = sNext >= 1.0 - 1e-12;
    const VecX load = sNext * Fflat;
    Objective f = [&](const MatX3& x, VecX* g, SparseMat* H, HessianMode mode) {
      const ShellEnergy e = shell.energy(x, g, H, mode);
      if (g) *g -= load;
      return e.total - load.dot(flat(x) - flat(X));
    };
    const double stepNorm = sNext * Fnorm;
    const double tol = (last ? options.relTol : std::max(options.relTol, 1e-6)) * stepNorm;
    MatX3 x = res.x;
    NewtonReport rep = newtonMinimize(f, dofs, x, tol, std::max(options.floorTol * stepNorm, roundoff),
                                      options, res.factorizationRetries);
    res.newtonIterations += rep.iterations;
    if (rep.converged || rep.atFloor) {
      res.x = x;
      s = sNext;
      ++res.loadSteps;
      if (last) {
        res.residual = rep.residual;
        res.reachedTolerance = rep.converged;
      }
      continue;
    }
    if (++halvings > 8) {
      std::ostringstream os;
      os << "static reference solve did not converge at load fraction " << sNext << " (‖g_F‖ = "
         << rep.residual << " dyn, ‖F_F‖ = " << stepNorm << " dyn): " << rep.failure;
      throw NumericalError(os.str());
    }
    ds *= 0.5;  // retry a smaller increment from the last converged state
  }
  res.relativeResidual = res.residual / Fnorm;
  res.u = res.x - X;
  for (int p : pinned) res.u.row(p).setZero(), res.x.row(p) = X.row(p);
  res.seconds = clock.seconds();
  return res;
}

MatX3 solveLinearStatic(const DiscreteShell& shell, const std::vector<int>& pinned, const MatX3& F) {
  const int n = shell.vertexCount();
  MYO_CHECK_EQ(F.rows(), n);
  const DofMap dofs(n, pinned);
  Eigen::SimplicialLDLT<SparseMat> ldlt(dofs.restrict(shell.stiffnessAtRest()));
  if (ldlt.info() != Eigen::Success)
    throw NumericalError("linear static solve: K_FF could not be factorized (under-constrained?)");
  const VecX uF = ldlt.solve(dofs.restrict(VecX(flat(F))));
  if (!uF.allFinite() || ldlt.vectorD().minCoeff() <= 0.0)
    throw NumericalError("linear static solve: K_FF is singular (the pins leave a rigid motion free)");
  MatX3 u = MatX3::Zero(n, 3);
  auto uf = flat(u);
  for (int k = 0; k < dofs.size(); ++k) uf[dofs.freeDof[k]] = uF[k];
  return u;
}

// ---------------------------------------------------------------------------------------------
// Dynamic reference.
//
// Both schemes minimise Φ(x) = (1/(2a²))‖x − x̃‖²_M + E(x) + (1/(2a))(x − x_c)ᵀC(x − x_c) − Fᵀx:
//   backward Euler: a = h, x̃ = x_n + h v_n, x_c = x_n, and v⁺ = (x − x_n)/h;
//   BDF2: a = 2h/3, x̃ = (12x_n − 3x_{n−1} + 2h(4v_n − v_{n−1}))/9, x_c = (4x_n − x_{n−1})/3, and
//         v⁺ = (3x − 4x_n + x_{n−1})/(2h).
// ∇Φ = 0 is M a⁺ = F − ∇E − C v⁺ with the scheme's a⁺ and v⁺ (check: for BDF2,
// a⁺ = (3v⁺ − 4v_n + v_{n−1})/(2h) = (9/(4h²))(x − x̃)).

ImplicitReference::ImplicitReference(const DiscreteShell& shell, std::vector<int> pinned, double xi,
                                     double zeta, ImplicitScheme scheme, ReferenceOptions options,
                                     ReferenceExtras extras)
    : shell_(shell), pinned_(std::move(pinned)), xi_(xi), zeta_(zeta), scheme_(scheme),
      options_(options), Kx_(std::move(extras.stiffness)) {
  MYO_CHECK(xi >= 0.0 && zeta >= 0.0, "Rayleigh damping must be ≥ 0 (ξ = " << xi << ", ζ = " << zeta << ")");
  const int n = shell.vertexCount();
  const DofMap dofs(n, pinned_);
  freeDof_ = dofs.freeDof;
  mass3_.resize(3 * n);
  if (extras.vertexMass.size() > 0) MYO_CHECK_EQ(extras.vertexMass.size(), static_cast<Eigen::Index>(n));
  if (Kx_.size() > 0) {
    MYO_CHECK_EQ(Kx_.rows(), static_cast<Eigen::Index>(3 * n));
    MYO_CHECK_EQ(Kx_.cols(), static_cast<Eigen::Index>(3 * n));
  }
  const VecX& vertexMass = extras.vertexMass.size() > 0 ? extras.vertexMass : shell.lumpedMass();
  for (int i = 0; i < n; ++i) mass3_.segment<3>(3 * i).setConstant(vertexMass[i]);
  SparseMat M(3 * n, 3 * n);
  std::vector<Triplet> trip;
  for (int i = 0; i < 3 * n; ++i) trip.emplace_back(i, i, mass3_[i]);
  M.setFromTriplets(trip.begin(), trip.end());
  const SparseMat K = Kx_.size() > 0 ? SparseMat(shell.stiffnessAtRest() + Kx_) : shell.stiffnessAtRest();
  C_ = xi_ * M + zeta_ * K;
  roundoff_ = roundoffForce(shell, K);
  x_ = shell.rest();
  v_ = MatX3::Zero(n, 3);
}

void ImplicitReference::setState(const MatX3& x, const MatX3& v) {
  MYO_CHECK_EQ(x.rows(), shell_.vertexCount());
  MYO_CHECK_EQ(v.rows(), shell_.vertexCount());
  x_ = x;
  v_ = v;
  for (int p : pinned_) x_.row(p) = shell_.rest().row(p), v_.row(p).setZero();
  haveHistory_ = false;
}

double ImplicitReference::mechanicalEnergy() const {
  const auto vf = flat(v_);
  const double extra = Kx_.size() > 0 ? 0.5 * flat(displacement()).dot(Kx_ * flat(displacement())) : 0.0;
  return 0.5 * vf.dot(mass3_.cwiseProduct(vf)) + shell_.energy(x_).total + extra;
}

void ImplicitReference::step(double h, const MatX3& F) {
  MYO_CHECK(h > 0.0, "time step must be positive, got " << h);
  const int n = shell_.vertexCount();
  MYO_CHECK_EQ(F.rows(), n);
  const DofMap dofs(n, pinned_);
  const bool bdf2 = scheme_ == ImplicitScheme::BDF2 && haveHistory_;
  const VecX xn = flat(x_), vn = flat(v_);
  double a;
  VecX xTilde, xC;
  if (bdf2) {
    const VecX xp = flat(xPrev_), vp = flat(vPrev_);
    a = 2.0 * h / 3.0;
    xTilde = (12.0 * xn - 3.0 * xp + 2.0 * h * (4.0 * vn - vp)) / 9.0;
    xC = (4.0 * xn - xp) / 3.0;
  } else {
    a = h;
    xTilde = xn + h * vn;
    xC = xn;
  }
  const VecX Ff = flat(F);
  const SparseMat Hconst = [&] {
    SparseMat Md(3 * n, 3 * n);
    std::vector<Triplet> trip;
    for (int i = 0; i < 3 * n; ++i) trip.emplace_back(i, i, mass3_[i] / (a * a));
    Md.setFromTriplets(trip.begin(), trip.end());
    return Kx_.size() > 0 ? SparseMat(Md + C_ / a + Kx_) : SparseMat(Md + C_ / a);
  }();
  Objective f = [&](const MatX3& x, VecX* g, SparseMat* H, HessianMode mode) {
    const VecX xf = flat(x);
    const VecX dm = xf - xTilde, dc = xf - xC;
    const VecX Cdc = C_ * dc;
    const ShellEnergy e = shell_.energy(x, g, H, mode);
    double extra = 0.0;
    if (Kx_.size() > 0) {  // ½uᵀK_x u, u = x − X̄
      const VecX u = xf - flat(shell_.rest());
      const VecX Ku = Kx_ * u;
      extra = 0.5 * u.dot(Ku);
      if (g) *g += Ku;
    }
    if (g) *g += mass3_.cwiseProduct(dm) / (a * a) + Cdc / a - Ff;
    if (H) *H += Hconst;
    return dm.dot(mass3_.cwiseProduct(dm)) / (2.0 * a * a) + e.total + extra + dc.dot(Cdc) / (2.0 * a) -
           Ff.dot(xf);
  };

  // Tolerance relative to the forces in the balance at the start of the step.
  VecX gE;
  shell_.energy(x_, &gE);
  const double scale = std::max({dofs.restrict(Ff).norm(), dofs.restrict(gE).norm(),
                                 dofs.restrict(VecX(mass3_.cwiseProduct(xTilde - xn) / (a * a))).norm()});
  const double floorAbs = roundoff_;
  MatX3 x = x_;
  int retries = 0;
  NewtonReport rep = newtonMinimize(f, dofs, x, std::max(options_.relTol * scale, floorAbs),
                                    std::max(options_.floorTol * scale, floorAbs), options_, retries);
  if (!rep.converged && !rep.atFloor) {
    std::ostringstream os;
    os << "implicit reference step (h = " << h << " s) did not converge: " << rep.failure
       << " (‖∇Φ_F‖ = " << rep.residual << " dyn, force scale " << scale << " dyn)";
    throw NumericalError(os.str());
  }
  lastIterations_ = rep.iterations;
  totalIterations_ += rep.iterations;
  const VecX xnew = flat(x);
  VecX vnew = bdf2 ? VecX((3.0 * xnew - 4.0 * xn + flat(xPrev_)) / (2.0 * h)) : VecX((xnew - xn) / h);
  xPrev_ = x_;
  vPrev_ = v_;
  haveHistory_ = true;
  x_ = x;
  v_ = rows3(vnew);
  for (int p : pinned_) x_.row(p) = shell_.rest().row(p), v_.row(p).setZero();
}

}  // namespace myo
