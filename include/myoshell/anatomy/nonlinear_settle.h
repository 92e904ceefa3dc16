// The reduced nonlinear static settle of the anatomical skin (docs/anatomical_model.md, "Against the
// full-space nonlinear reference"): the Galerkin projection onto a basis Φ (3n × r) of the same
// energy the full-space reference minimises,
//
//   E(u) = E_shell(X + u) + ½ uᵀ K_x u − Fᵀu,   K_x = K_att + Σ K_c − Σ ρ C̃C̃ᵀ   (the released skin)
//   u = Φq:  E_r(q) = E_shell(X + Φq) + ½ qᵀ(ΦᵀK_xΦ)q − (ΦᵀF)ᵀq,
//   ∇E_r = Φᵀ g_shell(X + Φq) + ΦᵀK_xΦ q − ΦᵀF,   ∇²E_r = Φᵀ H_shell(X + Φq) Φ + ΦᵀK_xΦ,
//
// minimised by Newton on q with load continuation and a backtracking line search (as the full-space
// reference; where the Hessian and its projection are indefinite, K_x's release being negative, a
// Levenberg–Marquardt shift; below the energy's round-off, steps judged by the gradient). The basis
// is the skin's Ritz basis (every load pattern's static response) augmented
// with second-order static corrections, the static modal derivatives of Idelsohn & Cardona (1985,
// "A reduction method for nonlinear structural dynamic analysis", Comput Methods Appl Mech Eng 49:253)
// as Barbič & James (2005, "Real-time subspace integration for St. Venant–Kirchhoff deformable
// models", SIGGRAPH: "modal derivatives") write them for modes: with ψ_i the linear response to load pattern i
// (Kψ_i = F_i, K = ∇²E at rest) and N(a, b) = ∇³E_shell(X)[a, b] the second-order internal force,
// u = Σ a_i ψ_i + Σ_{i≤j} a_i a_j χ_ij + O(a³) solves the equilibrium to second order when
//
//   K χ_ij = −N(ψ_i, ψ_j)      (the ½ of the self term is a scale: only the span matters),
//
// N(a, b) by central differences of the Hessian, (H(X + εa) − H(X − εa)) b / 2ε. The corrections
// are solved with the released skin's K (AnatomicalSkin::linearFullResponse) and M-orthonormalised
// against the basis twice, deflated below a tolerance (as RitzBasisBuilder). Beyond second order,
// Newton enrichment (NonlinearSettleSettings::newtonSteps): for each muscle at a = 1, then all of
// them together, from its reduced solution u, full-space Newton steps p = −(H_shell(X + u) + K_x)⁻¹∇E
// (FullSpaceNewton), each p joining the basis; the span then holds each pattern's Newton iterates,
// which converge to its full solution where the rest-stiffness corrections K⁻¹r (residualRounds,
// a modified Newton; off by default) crawl: the zygomaticus stretches the skin beside the mouth
// corner by 36 % and compresses a triangle there to 15 % of its area, far from the rest tangent.
// The patterns: each muscle alone, each side's muscles together, all of them together; a pattern's
// steps stop once a step is 1 % of its displacement (newtonTolerance), at most 10. Measured on ICT
// with the built-in library (the eight and the lips' rings; docs/anatomical_model.md, "The reduced
// nonlinear settle") at a shortening of 20 %: zygomaticus 0.4 %, with the depressor anguli 3.3 %,
// all eight 2.4 %, gravity 0.14 %; the former fixed 6 steps without the sides gave 6.4 % and 6.9 %
// (the eight alone, a shortening of 14.4 %).
#pragma once

#include <Eigen/SparseCholesky>
#include <memory>
#include <vector>

#include "myoshell/anatomy/anatomical_skin.h"
#include "myoshell/core/types.h"
#include "myoshell/shell/discrete_shell.h"

namespace myo {

// Which second-order corrections join the basis.
enum class SecondOrderTerms {
  None,      // the skin's Ritz basis as it is
  Self,      // χ_ii for every load pattern (muscle loads at a = 1, gravity along x, y, z)
  WithCross  // χ_ii and χ_ij for the pairs whose responses overlap (crossOverlap)
};

struct NonlinearSettleSettings {
  SecondOrderTerms terms = SecondOrderTerms::WithCross;
  // A pair (i, j) is crossed when Σ_v |ψ_i(v)||ψ_j(v)| / (‖ψ_i‖ ‖ψ_j‖) exceeds this.
  double crossOverlap = 0.05;
  // Residual enrichment after the second-order terms: per round, for each muscle alone at a = 1,
  // the full residual r = F − g_shell(X + u) − K_x u of its reduced solve u joins the basis as K⁻¹r
  // (a modified-Newton correction in full space, with the rest stiffness). 0: none. It converges
  // slowly where the skin stretches far (the zygomaticus: 14.2 % after two rounds, 6.2 % after six,
  // 246 s), so the default is Newton enrichment (newtonSteps) instead.
  int residualRounds = 0;
  // Newton enrichment, after the residual rounds: for each enrichment pattern in turn (each muscle
  // alone at a = 1, each side's muscles together when eachSideTogether, then all muscles together
  // when allMusclesTogether), from its reduced solution in the basis so far, at most this many
  // full-space Newton steps (FullSpaceNewton: the tangent stiffness, not the rest one); each step's
  // direction joins the basis. 0: none. Each step is one or two factorisations of the 34k-DOF
  // tangent on ICT (about 2 s each). 10: the zygomaticus's steps take 8–10 (ICT, the anatomical eight).
  int newtonSteps = 10;
  // A pattern's Newton steps stop once a step is this small against the displacement,
  // |p| ≤ newtonTolerance · |u| (Euclidean, all vertices; near the solution p ≈ u* − u, and u + p
  // lies in the enriched span). 0: always newtonSteps steps. 0.01: the corrugators and depressors
  // labii stop after 2 steps, the depressors anguli after 4–5, the zygomatici after 8–10.
  double newtonTolerance = 0.01;
  // Newton–Galerkin restarts: after each Newton direction joins the basis, the pattern's reduced
  // problem is solved again in the enriched basis (from the Newton iterate, which lies in it, without
  // continuation) and the next Newton step starts from that Galerkin minimum, whose energy is at
  // most the iterate's. Off: on ICT the restarted reduced solves stalled far from equilibrium and
  // cost more than the steps they saved (docs/anatomical_model.md).
  bool newtonRestarts = false;
  // Each side's muscles together at a = 1 (MuscleDef::side "left", "right"; a side with two or more
  // muscles, not all of them) as enrichment patterns, after the single muscles and before all of
  // them: the combinations on one side of the mouth (zygomaticus + depressor anguli, ≤ 12 steps:
  // 5.9 % without, 0.8 % with).
  bool eachSideTogether = true;
  bool allMusclesTogether = true;
  double deflationTolerance = 1e-8;  // as RitzSettings: a correction already in the span is dropped
  int loadSteps = 3;                 // continuation (the full-space reference takes 10)
  int maxIterations = 30;            // Newton iterations per load step
  double tolerance = 1e-8;           // |∇E_r| ≤ tolerance · |ΦᵀF|
  void validate() const;             // InputError naming the field
};

// One evaluation of the reduced energy E_r(q) on the basis Phi (3n × r); grad (r) and hess (r × r)
// when non-null. Kxr = ΦᵀK_xΦ, fr = ΦᵀF. mode: the shell Hessian's (Projected: PSD blocks).
double reducedShellEnergy(const DiscreteShell& shell, const MatX& Phi, const MatX& Kxr, const VecX& fr, const VecX& q,
                          VecX* grad, MatX* hess, HessianMode mode = HessianMode::Exact);

// N(a, b) = ∇³E_shell(X)[a, b] (3n, dyn/cm²·cm² = dyn per cm² of displacement): the second-order
// internal force, (H(X + εa) − H(X − εa)) b / 2ε with ε·max|a| = `step` (cm).
VecX secondOrderForce(const DiscreteShell& shell, const MatX3& a, const MatX3& b, double step = 1e-4);

// Minimises E_r on Phi from q = 0 (Newton, continuation, line search), or from start (r, or
// shorter: padded with zeros) at the full load without continuation. u = Φq.
struct ReducedSolve {
  VecX q;
  MatX3 u;
  int iterations = 0;
  double residual = 0.0;  // |∇E_r| / |ΦᵀF| at the end
  bool converged = false;
};
ReducedSolve minimizeReducedEnergy(const DiscreteShell& shell, const MatX& Phi, const MatX& Kxr, const VecX& fr,
                                   const NonlinearSettleSettings& settings, const VecX* start = nullptr);

// Newton's method on the full-space energy E(u) = E_shell(X + u) + ½uᵀK_x u − Fᵀu, one step at a
// time, as the full-space reference iterates (tests/face/anatomical_test.cpp): the exact Hessian
// + K_x, the projected one (PSD blocks) where that is not positive definite, Armijo backtracking.
// The factorisation's ordering is computed once and kept across steps and loads. The shell must
// outlive it.
class FullSpaceNewton {
 public:
  FullSpaceNewton(const DiscreteShell& shell, SparseMat Kx);  // Kx: 3n × 3n
  // E at u (3n) under the load F (3n); grad and hess when non-null.
  double energy(const VecX& F, const VecX& u, VecX* grad, SparseMat* hess, HessianMode mode) const;
  // The Newton direction p at u (zero when |∇E| ≤ 1e-8 |F|); u ← u + αp with the first α = 2⁻ᵏ
  // (k < 30) that decreases E enough, u unchanged when none does. projectedOnly: the projected
  // Hessian without trying the exact one first (one factorisation instead of two where it is
  // indefinite).
  VecX step(const VecX& F, VecX& u, bool projectedOnly = false);
  // Whether the last step used the projected Hessian (the exact one was not positive definite).
  bool lastProjected() const { return lastProjected_; }
  // The last step's α (0: no step decreased E).
  double lastStepLength() const { return lastStepLength_; }
  const DiscreteShell& shell() const { return shell_; }
  const SparseMat& extraStiffness() const { return Kx_; }

 private:
  const DiscreteShell& shell_;
  SparseMat Kx_;
  Eigen::SimplicialLDLT<SparseMat> ldlt_;
  bool analysed_ = false;
  bool lastProjected_ = false;
  double lastStepLength_ = 0.0;
};

// Newton enrichment for one load pattern F (3n): from its reduced solution on Phi (3n × r,
// M-orthonormal; mass3 (3n) the lumped mass per DOF, g), at most settings.newtonSteps full-space
// Newton steps, each direction appended to Phi (M-orthonormalised, deflated) and Kxr = ΦᵀK_xΦ grown
// to match; with settings.newtonRestarts each step after the first starts from the Galerkin minimum
// in the enriched basis; the steps stop once |p| ≤ settings.newtonTolerance · |u|. Where the last
// step needed the projected Hessian and a line search (α < 1), the next takes the projected one at
// once (FullSpaceNewton::step's projectedOnly): far from the solution the exact one is indefinite.
struct NewtonEnrichment {
  int steps = 0;          // Newton steps taken
  int appended = 0;       // directions that joined the basis (the others were in it already)
  double lastStep = 0.0;  // |p| / |u| of the last step
};
NewtonEnrichment enrichWithNewtonSteps(FullSpaceNewton& newton, const VecX& mass3, const VecX& F,
                                       const NonlinearSettleSettings& settings, MatX& Phi, MatX& Kxr);

// The skin's full-space static response to a load F (n×3, dyn) with the shell's large deflection:
// the minimiser of E(u) = E_shell(X + u) + ½uᵀK_x u − Fᵀu (K_x as FullSpaceNewton's: the attachment
// and the couplings less the relaxed muscles' release), by L-BFGS (Nocedal & Wright 2006, "Numerical
// Optimization", Alg. 7.4 and 7.5, the last `memory` pairs) whose initial inverse Hessian is the
// released skin's rest stiffness K⁻¹ (AnatomicalSkin::linearFullResponse: the kept factorisation,
// no new one), from the linear response K⁻¹F, with Armijo backtracking. It stops once a step moves
// the skin by at most `tolerance` of |u| (Euclidean over all vertices). For a load the reduced basis
// holds no pattern for (the mouth's air, anatomy/mouth_pressure.h): on the built-in head at 2 kPa
// it takes about 25 steps and matches FullSpaceNewton's solution, at a fraction of its cost (no
// factorisation of the tangent).
struct NonlinearResponse {
  MatX3 u;                 // n×3, cm
  int iterations = 0;      // L-BFGS steps taken
  double lastStep = 0.0;   // |Δu| / |u| of the last step
  bool converged = false;  // lastStep ≤ tolerance
};
NonlinearResponse nonlinearFullResponse(const AnatomicalSkin& skin, const MatX3& load, double tolerance = 1e-4,
                                        int maxIterations = 200, int memory = 8);

// The skin's nonlinear settle: its Ritz basis with the second-order corrections, the residual and
// the Newton enrichment (built once, in the constructor: one full-space solve per correction, one
// reduced solve per muscle and round, one reduced solve and at most newtonSteps Newton steps per
// enrichment pattern), then minimizeReducedEnergy for each load. The skin's own basis and
// stepper are untouched: this is a separate, larger basis for static shapes only.
class NonlinearSkinSettle {
 public:
  explicit NonlinearSkinSettle(std::shared_ptr<const AnatomicalSkin> skin, const NonlinearSettleSettings& settings = {});
  // The static equilibrium under the loads (reading (b) of gravity; no contact).
  SettledSkin settle(const SkinLoads& loads) const;
  SettledSkin settle(const MatX3& worldLoad) const;
  const MatX& basis() const { return Phi_; }   // 3n × r, M-orthonormal
  int corrections() const { return corrections_; }  // vectors appended to the skin's basis
  // Newton steps taken per enrichment pattern (each muscle, each side, then all of them together).
  const std::vector<int>& newtonStepsTaken() const { return newtonStepsTaken_; }
  double buildSeconds() const { return buildSeconds_; }
  const NonlinearSettleSettings& settings() const { return settings_; }

 private:
  std::shared_ptr<const AnatomicalSkin> skin_;
  NonlinearSettleSettings settings_;
  SparseMat Kx_;
  MatX Phi_, Kxr_;
  int corrections_ = 0;
  std::vector<int> newtonStepsTaken_;
  double buildSeconds_ = 0.0;
};

}  // namespace myo
