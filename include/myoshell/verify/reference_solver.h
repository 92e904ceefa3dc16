// Full-space nonlinear reference solvers on the discrete-shell energy (METHOD.md §5.1): the
// yardstick the reduced (modal, modal-warping) solutions are measured against. Not real time.
//
// Both solvers work on the same energy E(x) of thesis eq. 1–4 (DiscreteShell), with the same
// constraints as the modal analysis (pinned vertices: all three DOFs removed, not penalised, so
// their displacement is exactly zero) and forces given per vertex in world coordinates.
//
// Newton's method: a sparse LDLᵀ (Eigen::SimplicialLDLT) of the free block of the Hessian and a
// backtracking Armijo line search on the minimised objective. The exact Hessian is used when its
// factorization is positive definite (quadratic convergence near a stable equilibrium); otherwise
// the per-element PSD-projected Hessian (HessianMode::Projected, METHOD.md §6 item 1). The
// projected Hessian alone converges only linearly under large bending (measured: ×0.86 per
// iteration on a strip at 45° tip rotation), because it drops the compressive membrane terms.
// When a factorization of the projected Hessian fails, the solver adds a growing multiple of the
// mean diagonal and retries.
#pragma once

#include <vector>

#include "myoshell/core/types.h"
#include "myoshell/shell/discrete_shell.h"

namespace myo {

// Newton settings shared by the static and the dynamic reference solvers.
struct ReferenceOptions {
  // Static: number of load increments F·k/loadSteps, k = 1..loadSteps, each solved from the
  // previous solution (continuation). 1 solves in one go.
  int loadSteps = 10;
  // Convergence: ‖g_F‖ ≤ relTol·‖F_F‖ (static) or ‖∇Φ_F‖ ≤ relTol·scale (dynamic, see
  // ImplicitReference), g_F the free part of the residual, dyn.
  double relTol = 1e-8;
  // Residual floor: round-off keeps ‖g_F‖ from going far below ~1e-8‖F‖ (METHOD.md §5.1). When the
  // line search can make no further progress and ‖g_F‖ ≤ floorTol·‖F_F‖, the solve is accepted
  // with reachedTolerance = false instead of failing.
  double floorTol = 1e-6;
  int maxNewtonIterations = 100;  // per load step (static) or per time step (dynamic)
  double armijo = 1e-4;           // sufficient-decrease constant c₁ of the line search
  int maxLineSearchHalvings = 40;
};

// Outcome of a static reference solve.
struct StaticReferenceResult {
  MatX3 x;                      // n×3 equilibrium positions, cm
  MatX3 u;                      // n×3 displacement x − X̄, cm (rows of pinned vertices exactly 0)
  double residual = 0.0;        // final ‖g_F‖ = ‖∇E_F − F_F‖, dyn
  double relativeResidual = 0;  // residual / ‖F_F‖ (0 when F = 0)
  bool reachedTolerance = true; // false when accepted at the floor (see ReferenceOptions)
  int loadSteps = 0;            // increments used
  int newtonIterations = 0;     // Newton iterations summed over all increments
  int factorizationRetries = 0; // times a regularization had to be added
  double seconds = 0.0;         // wall time of the solve
};

// Static equilibrium x* = argmin_x E(x) − Fᵀ(x − X̄) with x_i = X̄_i for i ∈ pinned (METHOD.md
// §5.1). F: n×3 world forces, dyn (rows of pinned vertices are ignored); pinned: vertex indices.
// With F = 0 the answer is X̄ (E ≥ 0 = E(X̄)) and no iteration is made.
// Throws NumericalError when a load step does not converge, CheckError on bad shapes or indices.
StaticReferenceResult solveStaticReference(const DiscreteShell& shell, const std::vector<int>& pinned,
                                           const MatX3& F, const ReferenceOptions& options = {});

// The linear full-space static displacement u = K_FF⁻¹ F_F with K = stiffnessAtRest() (n×3, cm;
// pinned rows 0). Throws NumericalError when K_FF is singular (under-constrained).
MatX3 solveLinearStatic(const DiscreteShell& shell, const std::vector<int>& pinned, const MatX3& F);

// Time discretisation of the dynamic reference.
enum class ImplicitScheme {
  Euler,  // backward Euler (first order, numerical damping ∝ h·ω²)
  BDF2,   // second-order backward differentiation (first step taken with backward Euler)
};

// What a model adds to the shell's energy and mass in the full space (the anatomical model,
// anatomical_skin.h): E_x = ½(x − X̄)ᵀK_x(x − X̄), K_x = K_att + ΣK_c (3n×3n, dyn/cm, symmetric
// positive semi-definite), and its own lumped vertex masses (n, g; empty: the shell's).
struct ReferenceExtras {
  SparseMat stiffness;
  VecX vertexMass;
};

// Dynamic full-space reference: M ẍ + C ẋ + ∇E(x) = F with lumped M and Rayleigh damping
// C = ξM + ζK̄ (K̄ = stiffnessAtRest(), thesis eq. 6–7), pinned vertices fixed at rest.
// Backward Euler solves each step as the minimisation of METHOD.md §5.1's
//   Φ(x) = (1/(2h²))‖x − x_n − h v_n‖²_M + E(x) + (1/(2h))(x − x_n)ᵀC(x − x_n) − F_{n+1}ᵀx,
// whose stationarity is exactly M(v⁺ − v_n)/h = F − ∇E(x) − C v⁺, then v_{n+1} = (x_{n+1} − x_n)/h.
// BDF2 has the same form with h → 2h/3 and shifted centres (see the .cpp).
// Precomputes M, K̄, C and the free-DOF map; step() does the Newton solve. Keeps a reference to
// the shell, which must outlive it.
class ImplicitReference {
 public:
  // xi: mass-proportional damping ξ (1/s); zeta: stiffness-proportional damping ζ (s).
  // With `extras`, E becomes E_shell + E_x, M the extras' masses and K̄ = stiffnessAtRest() + K_x.
  ImplicitReference(const DiscreteShell& shell, std::vector<int> pinned, double xi, double zeta,
                    ImplicitScheme scheme = ImplicitScheme::Euler, ReferenceOptions options = {},
                    ReferenceExtras extras = {});

  // Sets the state: x, v are n×3 (cm, cm/s); pinned rows are reset to rest position, zero velocity.
  // Also restarts BDF2's history (the next step is a backward-Euler step).
  void setState(const MatX3& x, const MatX3& v);

  // Advances one step of size h (s) with the external force F_{n+1} (n×3, dyn) held at the end of
  // the step. Throws NumericalError when Newton does not converge.
  void step(double h, const MatX3& F);

  const MatX3& positions() const { return x_; }   // n×3, cm
  const MatX3& velocities() const { return v_; }  // n×3, cm/s
  MatX3 displacement() const { return x_ - shell_.rest(); }
  // Kinetic ½vᵀMv + elastic E(x) energy of the current state, erg.
  double mechanicalEnergy() const;
  int lastNewtonIterations() const { return lastIterations_; }
  int totalNewtonIterations() const { return totalIterations_; }

 private:
  const DiscreteShell& shell_;
  std::vector<int> pinned_;
  double xi_, zeta_;
  ImplicitScheme scheme_;
  ReferenceOptions options_;
  std::vector<int> freeDof_;   // free DOF indices (3n numbering), ascending
  VecX mass3_;                 // 3n lumped mass per DOF, g
  SparseMat C_;                // 3n×3n damping ξM + ζK̄, g/s
  SparseMat Kx_;               // 3n×3n extra quadratic stiffness (empty: none), dyn/cm
  double roundoff_ = 0.0;      // residual (dyn) below which a step counts as converged
  MatX3 x_, v_, xPrev_, vPrev_;
  bool haveHistory_ = false;
  int lastIterations_ = 0;
  int totalIterations_ = 0;
};

}  // namespace myo
