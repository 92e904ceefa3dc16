// Static solves of the reduced (modal, modal-warping) system: the reduced side of the reference
// comparisons of `myoshell validate` (validation.h) and the yardstick of the integrator's tests.
// Not used by the simulator: a running face only ever steps (reduce/modal_warping.h).
//
// Fields are over the basis's free vertices only ("free" f×3 fields, row i = vertex
// basis.freeVertices[i]), as in reduce/modal_warping.h.
#pragma once

#include "myoshell/core/types.h"
#include "myoshell/reduce/modal_basis.h"

namespace myo {

struct StaticSolveSettings {
  int maxIterations = 100;   // Newton iterations in total (over all load steps)
  int loadSteps = 1;         // continuation: the load is applied in this many equal increments
  double tolerance = 1e-12;  // stop when |Λq − Φᵀ R(Ψq)ᵀ F| ≤ tolerance·|ΦᵀF|
};

struct StaticSolveResult {
  VecX q;                    // d modal amplitudes at equilibrium
  MatX3 u;                   // free displacement f×3 (cm): warped or linear
  int iterations = 0;        // Newton iterations used (0 for the linear solve)
  double residual = 0.0;     // final |Λq − Φᵀ R(Ψq)ᵀ F| / |ΦᵀF| (0 when F = 0)
  bool converged = true;
};

// Linear static response q = Λ⁻¹ΦᵀF, u = Φq (the baseline of METHOD.md §5.1). F: free f×3 (dyn).
// Needs a constrained basis: throws NumericalError if some λ_j ≤ 1e-9·λ_max (rigid modes).
StaticSolveResult solveStaticLinear(const ModalBasis& basis, const MatX3& freeForce);

// Static modal-warping equilibrium Λq = Φᵀ R(Ψq)ᵀ F (METHOD.md §5.3), by Newton's method with
// the exact Jacobian Λ − Σ_i Φ_iᵀ R_iᵀ [F_i]× R̃(w_i) Ψ_i, a backtracking line search on the
// residual, and optional load continuation; then u = R̃(Ψq)Φq. Returns converged = false (never
// throws for non-convergence) with the last iterate. Same rigid-mode precondition as the linear solve.
StaticSolveResult solveStaticWarped(const ModalBasis& basis, const MatX3& freeForce,
                                    const StaticSolveSettings& settings = {});

}  // namespace myo
