#include "myoshell/anatomy/nonlinear_settle.h"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "myoshell/core/errors.h"
#include "myoshell/core/timer.h"

namespace myo {

void NonlinearSettleSettings::validate() const {
  if (!(crossOverlap >= 0.0)) throw InputError("nonlinear settle: crossOverlap must be ≥ 0");
  if (!(deflationTolerance > 0.0 && deflationTolerance < 1.0))
    throw InputError("nonlinear settle: deflationTolerance must lie in (0, 1)");
  if (loadSteps < 1) throw InputError("nonlinear settle: loadSteps must be ≥ 1");
  if (residualRounds < 0) throw InputError("nonlinear settle: residualRounds must be ≥ 0");
  if (newtonSteps < 0) throw InputError("nonlinear settle: newtonSteps must be ≥ 0");
  if (!(newtonTolerance >= 0.0 && newtonTolerance < 1.0))
    throw InputError("nonlinear settle: newtonTolerance must lie in [0, 1)");
  if (maxIterations < 1) throw InputError("nonlinear settle: maxIterations must be ≥ 1");
  if (!(tolerance > 0.0)) throw InputError("nonlinear settle: tolerance must be > 0");
}

double reducedShellEnergy(const DiscreteShell& shell, const MatX& Phi, const MatX& Kxr, const VecX& fr, const VecX& q,
                          VecX* grad, MatX* hess, HessianMode mode) {
  MatX3 x = shell.rest();
  flat(x) += Phi * q;
  VecX g;
  SparseMat H;
  const ShellEnergy e = shell.energy(x, grad ? &g : nullptr, hess ? &H : nullptr, mode);
  const VecX Kq = Kxr * q;
  if (grad) *grad = Phi.transpose() * g + Kq - fr;
  if (hess) {
    const MatX HPhi = H * Phi;
    *hess = Phi.transpose() * HPhi + Kxr;
    *hess = 0.5 * (*hess + hess->transpose()).eval();
  }
  return e.total + 0.5 * q.dot(Kq) - fr.dot(q);
}

namespace {

// H(X + εa) and H(X − εa), ε·max|a| = step: N(a, b) = (H₊ − H₋) b / 2ε for any b.
struct HessianPair {
  SparseMat plus, minus;
  double eps = 0.0;
  VecX apply(const VecX& b) const { return (plus * b - minus * b) / (2.0 * eps); }
};
HessianPair hessianPair(const DiscreteShell& shell, const MatX3& a, double step) {
  HessianPair p;
  const double amax = a.cwiseAbs().maxCoeff();
  if (!(amax > 0.0)) throw InputError("second-order force: the direction is zero");
  p.eps = step / amax;
  shell.energy(shell.rest() + p.eps * a, nullptr, &p.plus, HessianMode::Exact);
  shell.energy(shell.rest() - p.eps * a, nullptr, &p.minus, HessianMode::Exact);
  return p;
}

// Appends r to the M-orthonormal columns of Phi (classical Gram–Schmidt twice, as RitzBasisBuilder);
// false when r is already in the span (deflation).
bool appendMOrthonormal(MatX& Phi, const VecX& mass3, VecX r, double tolerance) {
  const double before = std::sqrt(r.dot(mass3.cwiseProduct(r)));
  if (!(before > 0.0)) return false;
  for (int pass = 0; pass < 2; ++pass) r -= Phi * (Phi.transpose() * mass3.cwiseProduct(r));
  const double after = std::sqrt(r.dot(mass3.cwiseProduct(r)));
  if (!(after > tolerance * before)) return false;
  Phi.conservativeResize(Eigen::NoChange, Phi.cols() + 1);
  Phi.col(Phi.cols() - 1) = r / after;
  return true;
}

// Kxr = ΦᵀK_xΦ (symmetrised), grown by the columns of Phi appended since it was formed.
void growReducedStiffness(const SparseMat& Kx, const MatX& Phi, MatX& Kxr) {
  const Eigen::Index r0 = Kxr.cols(), r = Phi.cols();
  if (r0 == r) return;
  const MatX KPhi = Kx * Phi.rightCols(r - r0);
  MatX next(r, r);
  next.topLeftCorner(r0, r0) = Kxr;
  next.rightCols(r - r0) = Phi.transpose() * KPhi;
  next.bottomLeftCorner(r - r0, r0) = next.topRightCorner(r0, r - r0).transpose();
  Kxr = 0.5 * (next + next.transpose());
}

}  // namespace

VecX secondOrderForce(const DiscreteShell& shell, const MatX3& a, const MatX3& b, double step) {
  return hessianPair(shell, a, step).apply(flat(b));
}

ReducedSolve minimizeReducedEnergy(const DiscreteShell& shell, const MatX& Phi, const MatX& Kxr, const VecX& fr,
                                   const NonlinearSettleSettings& s, const VecX* start) {
  s.validate();
  const Eigen::Index r = Phi.cols();
  ReducedSolve out;
  out.q = VecX::Zero(r);
  if (start) {
    if (start->size() > r) throw InputError("nonlinear settle: the start has more coordinates than the basis");
    out.q.head(start->size()) = *start;
  }
  const double fNorm = std::max(fr.norm(), 1e-300);
  // The energy sums terms of ±10⁵ erg on ICT: a predicted decrease −½gᵀp below this fraction of |E|
  // cannot be measured, and the line search only halved round-off (measured: 20 wasted iterations
  // of a load step at |∇E_r| ≈ 3e-7 |ΦᵀF|, each accepting its 30th halving).
  constexpr double kRoundOff = 1e-14;
  Eigen::LLT<MatX> llt;
  VecX g;
  MatX H;
  // From a start, the full load at once (the start is near the solution: no continuation).
  for (int step = start ? s.loadSteps : 1; step <= s.loadSteps; ++step) {
    const VecX f = (static_cast<double>(step) / s.loadSteps) * fr;
    // An intermediate load step is only the next one's start: it stops at the convergence threshold.
    const double tol = step < s.loadSteps ? 1e3 * s.tolerance : s.tolerance;
    for (int it = 0; it < s.maxIterations; ++it) {
      const double e0 = reducedShellEnergy(shell, Phi, Kxr, f, out.q, &g, &H, HessianMode::Exact);
      if (g.norm() <= tol * fNorm) break;
      ++out.iterations;
      llt.compute(H);
      if (llt.info() != Eigen::Success) {  // indefinite: the projected Hessian (PSD blocks) + K_x
        reducedShellEnergy(shell, Phi, Kxr, f, out.q, nullptr, &H, HessianMode::Projected);
        llt.compute(H);
        // K_x lets go of the relaxed muscles (−Σ ρ C̃C̃ᵀ), so even the projected Hessian can be
        // indefinite: shift it until it is positive definite (Levenberg–Marquardt; Nocedal & Wright
        // 2006, "Numerical Optimization", §3.4), which keeps p a descent direction.
        const double scale = std::max(H.diagonal().cwiseAbs().maxCoeff(), 1e-300);
        for (double mu = 1e-10 * scale; llt.info() != Eigen::Success; mu *= 10.0) {
          if (mu > scale) throw NumericalError("nonlinear settle: the reduced Hessian is singular");
          llt.compute(H + mu * MatX::Identity(r, r));
        }
      }
      const VecX p = llt.solve(-g);
      const double slope = g.dot(p);  // < 0
      if (-0.5 * slope <= kRoundOff * std::abs(e0)) {
        // Below round-off the energy cannot judge the step, the gradient can: the full Newton step
        // is taken while it at least halves |∇E_r| (quadratic convergence does far better); where
        // it does not, the gradient is at its noise floor and the load step ends.
        VecX gt;
        reducedShellEnergy(shell, Phi, Kxr, f, out.q + p, &gt, nullptr);
        if (!(gt.norm() <= 0.5 * g.norm())) break;
        out.q += p;
        continue;
      }
      // Backtracking (Armijo). A step that decreases nothing is not taken: the load step stops.
      bool moved = false;
      double alpha = 1.0;
      for (int ls = 0; ls < 30 && !moved; ++ls, alpha *= 0.5) {
        const VecX qt = out.q + alpha * p;
        if (reducedShellEnergy(shell, Phi, Kxr, f, qt, nullptr, nullptr) <= e0 + 1e-4 * alpha * slope) {
          out.q = qt;
          moved = true;
        }
      }
      if (!moved) break;
    }
  }
  reducedShellEnergy(shell, Phi, Kxr, fr, out.q, &g, nullptr);
  out.residual = g.norm() / fNorm;
  out.converged = out.residual <= 1e3 * s.tolerance;
  out.u = MatX3(shell.rest().rows(), 3);
  flat(out.u) = Phi * out.q;
  return out;
}

FullSpaceNewton::FullSpaceNewton(const DiscreteShell& shell, SparseMat Kx) : shell_(shell), Kx_(std::move(Kx)) {
  const Eigen::Index n3 = 3 * shell_.vertexCount();
  if (Kx_.rows() != n3 || Kx_.cols() != n3) throw InputError("full-space Newton: K_x must be 3n×3n");
}

double FullSpaceNewton::energy(const VecX& F, const VecX& u, VecX* grad, SparseMat* hess, HessianMode mode) const {
  const ShellEnergy e = shell_.energy(shell_.rest() + rows3(u), grad, hess, mode);
  const VecX Ku = Kx_ * u;
  if (grad) *grad += Ku - F;
  if (hess) *hess += Kx_;
  return e.total + 0.5 * u.dot(Ku) - F.dot(u);
}

VecX FullSpaceNewton::step(const VecX& F, VecX& u, bool projectedOnly) {
  if (F.size() != Kx_.rows() || u.size() != Kx_.rows()) throw InputError("full-space Newton: F and u must be 3n");
  VecX g;
  SparseMat H;
  const double e0 = energy(F, u, &g, &H, projectedOnly ? HessianMode::Projected : HessianMode::Exact);
  if (g.norm() <= 1e-8 * F.norm()) return VecX::Zero(u.size());
  // The shell Hessian's pattern is the same at every x (discrete_shell.h): ordered once.
  if (!analysed_) {
    ldlt_.analyzePattern(H);
    analysed_ = true;
  }
  ldlt_.factorize(H);
  lastProjected_ = projectedOnly;
  if (!projectedOnly && (ldlt_.info() != Eigen::Success || !(ldlt_.vectorD().minCoeff() > 0.0))) {
    energy(F, u, nullptr, &H, HessianMode::Projected);
    lastProjected_ = true;
    ldlt_.factorize(H);
  }
  if (lastProjected_ && ldlt_.info() != Eigen::Success)
    throw NumericalError("full-space Newton: the projected Hessian is singular");
  const VecX p = ldlt_.solve(-g);
  double alpha = 1.0;
  lastStepLength_ = 0.0;
  for (int ls = 0; ls < 30; ++ls, alpha *= 0.5)
    if (energy(F, u + alpha * p, nullptr, nullptr, HessianMode::Exact) <= e0 + 1e-4 * alpha * g.dot(p)) {
      u += alpha * p;
      lastStepLength_ = alpha;
      break;
    }
  return p;
}

NewtonEnrichment enrichWithNewtonSteps(FullSpaceNewton& newton, const VecX& mass3, const VecX& F,
                                       const NonlinearSettleSettings& s, MatX& Phi, MatX& Kxr) {
  s.validate();
  const DiscreteShell& shell = newton.shell();
  if (F.size() != Phi.rows() || mass3.size() != Phi.rows() || Kxr.rows() != Phi.cols())
    throw InputError("Newton enrichment: F, the masses and the basis must be 3n, Kxr r × r");
  NewtonEnrichment out;
  ReducedSolve r = minimizeReducedEnergy(shell, Phi, Kxr, Phi.transpose() * F, s);
  VecX u = flat(r.u);
  while (out.steps < s.newtonSteps) {
    // Where this pattern's last step needed the projected Hessian and still a line search (α < 1),
    // the iterate is still far from where the exact one is positive definite: the projected one at
    // once, without the exact one's failing factorisation (half of such a step). Once a projected
    // step is taken whole, the exact Hessian is tried again (its steps converge fast, where it holds).
    const bool farOff = out.steps > 0 && newton.lastProjected() && newton.lastStepLength() < 1.0;
    const VecX p = newton.step(F, u, farOff);
    if (!(p.squaredNorm() > 0.0)) break;  // the full solution already
    ++out.steps;
    out.lastStep = p.norm() / std::max(u.norm(), 1e-300);
    const bool added = appendMOrthonormal(Phi, mass3, p, s.deflationTolerance);
    if (added) {
      ++out.appended;
      growReducedStiffness(newton.extraStiffness(), Phi, Kxr);
    }
    // Converged to the tolerance: near the solution p ≈ u* − u, and u + p lies in the span.
    if (out.lastStep <= s.newtonTolerance) break;
    if (s.newtonRestarts && added && out.steps < s.newtonSteps) {
      // The Newton iterate lies in the enriched span: its coordinates start the Galerkin solve.
      const VecX q0 = Phi.transpose() * mass3.cwiseProduct(u);
      r = minimizeReducedEnergy(shell, Phi, Kxr, Phi.transpose() * F, s, &q0);
      u = flat(r.u);
    }
  }
  return out;
}

NonlinearResponse nonlinearFullResponse(const AnatomicalSkin& skin, const MatX3& load, double tolerance,
                                        int maxIterations, int memory) {
  if (!(tolerance > 0.0) || maxIterations < 1 || memory < 1)
    throw InputError("nonlinear response: tolerance must be > 0, maxIterations and memory ≥ 1");
  if (load.rows() != skin.head().mesh.vertexCount()) throw InputError("nonlinear response: the load must be n×3");
  NonlinearResponse out;
  out.u = skin.linearFullResponse(load);
  const VecX F = flat(load);
  if (!(F.squaredNorm() > 0.0)) {
    out.converged = true;
    return out;
  }
  // Only FullSpaceNewton's energy is used: nothing is factorised.
  const FullSpaceNewton energy(skin.shell(), skin.extraStiffness() - skin.releaseStiffness());
  VecX u = flat(out.u), g, gNext;
  double e = energy.energy(F, u, &g, nullptr, HessianMode::Exact);
  std::vector<VecX> S, Y;  // the last steps s_k and gradient changes y_k, oldest first
  std::vector<double> rho, alpha;
  for (int it = 0; it < maxIterations; ++it) {
    // The two-loop recursion (Alg. 7.4) with H₀ = K⁻¹.
    VecX q = -g;
    const size_t m = S.size();
    alpha.assign(m, 0.0);
    for (size_t k = m; k-- > 0;) {
      alpha[k] = rho[k] * S[k].dot(q);
      q -= alpha[k] * Y[k];
    }
    VecX p = flat(skin.linearFullResponse(rows3(q)));
    for (size_t k = 0; k < m; ++k) p += (alpha[k] - rho[k] * Y[k].dot(p)) * S[k];
    const double slope = g.dot(p);
    if (!(slope < 0.0)) break;  // not a descent direction: at the round-off floor
    double a = 1.0, eNext = e;
    bool moved = false;
    for (int ls = 0; ls < 30 && !moved; ++ls) {
      eNext = energy.energy(F, u + a * p, &gNext, nullptr, HessianMode::Exact);
      if (eNext <= e + 1e-4 * a * slope) moved = true;
      else a *= 0.5;
    }
    if (!moved) break;  // no step decreases E: the energy's round-off
    const VecX s = a * p;
    u += s;
    VecX y = gNext - g;
    ++out.iterations;
    out.lastStep = s.norm() / std::max(u.norm(), 1e-300);
    if (y.dot(s) > 1e-12 * y.norm() * s.norm()) {  // curvature condition: the pair keeps H positive definite
      S.push_back(s);
      Y.push_back(std::move(y));
      rho.push_back(1.0 / Y.back().dot(S.back()));
      if (static_cast<int>(S.size()) > memory) {
        S.erase(S.begin());
        Y.erase(Y.begin());
        rho.erase(rho.begin());
      }
    }
    g = gNext;
    e = eNext;
    if (out.lastStep <= tolerance) {
      out.converged = true;
      break;
    }
  }
  out.u = rows3(u);
  return out;
}

NonlinearSkinSettle::NonlinearSkinSettle(std::shared_ptr<const AnatomicalSkin> skin, const NonlinearSettleSettings& settings)
    : skin_(std::move(skin)), settings_(settings) {
  settings_.validate();
  if (!skin_) throw InputError("nonlinear settle: no skin");
  const Stopwatch clock;
  const AnatomicalSkin& sk = *skin_;
  const DiscreteShell& shell = sk.shell();
  Kx_ = sk.extraStiffness() - sk.releaseStiffness();
  Phi_ = sk.basis()->Phi;
  const Eigen::Index n = shell.vertexCount();
  VecX mass3(3 * n);
  for (Eigen::Index i = 0; i < n; ++i) mass3.segment<3>(3 * i).setConstant(sk.vertexMass()(i));

  if (settings_.terms != SecondOrderTerms::None) {
    // The load patterns at their scale: each muscle at a = 1, gravity |g| along x, y, z.
    std::vector<MatX3> psi;
    for (int m = 0; m < static_cast<int>(sk.muscles().size()); ++m) psi.push_back(sk.linearFullResponse(sk.muscleLoad(m)));
    for (int a = 0; a < 3; ++a) {
      MatX3 f = MatX3::Zero(n, 3);
      f.col(a) = sk.settings().gravity * sk.vertexMass();
      psi.push_back(sk.linearFullResponse(f));
    }
    const size_t P = psi.size();
    const VecX norm = [&] {
      VecX v(static_cast<Eigen::Index>(P));
      for (size_t i = 0; i < P; ++i) v(static_cast<Eigen::Index>(i)) = psi[i].norm();
      return v;
    }();
    auto overlaps = [&](size_t i, size_t j) {
      const double o = psi[i].rowwise().norm().dot(psi[j].rowwise().norm());
      return o > settings_.crossOverlap * norm(static_cast<Eigen::Index>(i)) * norm(static_cast<Eigen::Index>(j));
    };
    for (size_t i = 0; i < P; ++i) {
      if (!(norm(static_cast<Eigen::Index>(i)) > 0.0)) continue;
      const HessianPair hp = hessianPair(shell, psi[i], 1e-4);
      for (size_t j = i; j < P; ++j) {
        if (j != i && (settings_.terms != SecondOrderTerms::WithCross || !overlaps(i, j))) continue;
        if (!(norm(static_cast<Eigen::Index>(j)) > 0.0)) continue;
        VecX N = hp.apply(flat(psi[j]));
        const MatX3 chi = sk.linearFullResponse(rows3(N));
        if (appendMOrthonormal(Phi_, mass3, flat(chi), settings_.deflationTolerance)) ++corrections_;
      }
    }
  }
  auto reduceKx = [&] { growReducedStiffness(Kx_, Phi_, Kxr_); };
  reduceKx();
  for (int round = 0; round < settings_.residualRounds; ++round) {
    std::vector<VecX> residuals;
    for (int m = 0; m < static_cast<int>(sk.muscles().size()); ++m) {
      const MatX3& F = sk.muscleLoad(m);
      const ReducedSolve r = minimizeReducedEnergy(shell, Phi_, Kxr_, Phi_.transpose() * flat(F), settings_);
      VecX g;
      shell.energy(shell.rest() + r.u, &g);
      residuals.push_back(flat(F) - g - Kx_ * flat(r.u));
    }
    for (VecX& res : residuals) {
      const MatX3 c = sk.linearFullResponse(rows3(res));
      if (appendMOrthonormal(Phi_, mass3, flat(c), settings_.deflationTolerance)) ++corrections_;
    }
    reduceKx();
  }
  if (settings_.newtonSteps > 0) {
    std::vector<MatX3> patterns;
    const int muscles = static_cast<int>(sk.muscles().size());
    for (int m = 0; m < muscles; ++m) patterns.push_back(sk.muscleLoad(m));
    if (settings_.eachSideTogether)
      for (const char* side : {"left", "right"}) {
        MatX3 together = MatX3::Zero(n, 3);
        int count = 0;
        for (int m = 0; m < muscles; ++m)
          if (sk.muscles()[static_cast<size_t>(m)].muscle.def.side == side) {
            together += sk.muscleLoad(m);
            ++count;
          }
        if (count > 1 && count < muscles) patterns.push_back(together);
      }
    if (settings_.allMusclesTogether && muscles > 1) {
      MatX3 all = MatX3::Zero(n, 3);
      for (int m = 0; m < muscles; ++m) all += sk.muscleLoad(m);
      patterns.push_back(all);
    }
    FullSpaceNewton newton(shell, Kx_);
    // One pattern after another, so each starts from a reduced solution in the basis the ones
    // before it enriched (the muscles together last, from the basis of every muscle alone).
    for (const MatX3& F : patterns) {
      const NewtonEnrichment e = enrichWithNewtonSteps(newton, mass3, flat(F), settings_, Phi_, Kxr_);
      corrections_ += e.appended;
      newtonStepsTaken_.push_back(e.steps);
    }
  }
  buildSeconds_ = clock.seconds();
}

SettledSkin NonlinearSkinSettle::settle(const SkinLoads& loads) const { return settle(skin_->worldLoad(loads)); }

SettledSkin NonlinearSkinSettle::settle(const MatX3& F) const {
  const VecX fr = Phi_.transpose() * flat(F);
  ReducedSolve r = minimizeReducedEnergy(skin_->shell(), Phi_, Kxr_, fr, settings_);
  // A continuation that stalls is run again with finer load steps (4×, then 16×), and the closer
  // solve is kept: on ICT at a shortening of 20 % the zygomaticus L with the depressor anguli R
  // stopped at a relative residual of 10 after 30 Newton iterations of its last third.
  int iterations = r.iterations;
  for (int finer : {4, 16}) {
    if (r.converged) break;
    NonlinearSettleSettings s = settings_;
    s.loadSteps *= finer;
    ReducedSolve again = minimizeReducedEnergy(skin_->shell(), Phi_, Kxr_, fr, s);
    iterations += again.iterations;
    if (again.residual < r.residual) r = std::move(again);
  }
  SettledSkin out;
  out.u = r.u;
  out.q = r.q;
  out.iterations = iterations;
  out.residual = r.residual;
  out.converged = r.converged;
  return out;
}

}  // namespace myo
