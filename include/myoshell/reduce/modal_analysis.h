// Constrained modal analysis (thesis eq. 7–8; METHOD.md §2): K Φ = M Φ Λ over the free DOFs of a
// discrete shell, pinned vertices removed (rows and columns deleted, not penalised), the d lowest
// modes, ΦᵀMΦ = I, eigenvalues ascending. Plus the modal rotation matrix Ψ = WΦ (§3.2) and the
// load-participation measure used to choose d (§2.5).
#pragma once

#include <vector>

#include "myoshell/core/errors.h"
#include "myoshell/core/types.h"
#include "myoshell/reduce/basis_cache.h"
#include "myoshell/reduce/modal_basis.h"
#include "myoshell/shell/discrete_shell.h"

namespace myo {

enum class EigenSolverKind {
  Auto,         // Dense when 3f ≤ denseMaxDofs, ShiftInvert otherwise
  Dense,        // M^-1/2 K M^-1/2 with Eigen::SelfAdjointEigenSolver (all modes; O((3f)³))
  ShiftInvert,  // Spectra SymGEigsShiftSolver, shift-invert over a SimplicialLDLT of K − σM
};

struct ModalSettings {
  int modeCount = 20;                          // d, the number of lowest modes kept (≥ 1)
  EigenSolverKind solver = EigenSolverKind::Auto;
  int denseMaxDofs = 600;                      // Auto switches to shift-invert above this 3f
  // Shift σ (1/s²) for shift-invert. 0 = automatic: σ = −1e-4·τ with τ = trace(K_FF)/trace(M_FF),
  // a mean-eigenvalue scale; K − σM is then SPD even with free rigid modes (METHOD.md §2.3).
  double shift = 0.0;
  double tolerance = 1e-12;                    // Spectra's relative Ritz tolerance
  int maxIterations = 2000;                    // Spectra restarts
  // Lanczos subspace size: max(2d+1, ncvMin), capped at 3f.
  int ncvMin = 40;
};

// The sorted free vertices: all of [0, n) not in `pinned`, and not isolated (a vertex in no
// triangle has no mass and no stiffness, so it is treated as pinned). `pinned` may be unsorted and
// contain duplicates; out-of-range indices throw InputError.
std::vector<int> freeVerticesOf(int vertexCount, const std::vector<int>& pinned,
                                const MatX3i& F);

// Rows and columns of a 3n×3n matrix restricted to the free vertices' DOFs (3f×3f).
SparseMat restrictToFree(const SparseMat& A, const std::vector<int>& freeVertices, int vertexCount);

// The cache key of computeModalBasis(shell, pinned, settings): a hash of the rest positions,
// triangles, sorted pins, material, d, solver settings and kModalBasisFormatVersion.
BasisKey modalBasisKey(const DiscreteShell& shell, const std::vector<int>& pinned,
                       const ModalSettings& settings);

// Version of the basis computation and of its cache payload. Bump it whenever the shell energy,
// the analysis or the serialization changes, so that stale cache entries are never reused.
inline constexpr uint32_t kModalBasisFormatVersion = 1;

// The constrained modal basis of a shell with the given pinned vertices. K = shell.stiffnessAtRest(),
// M = lumped masses. With a cache, a stored basis under modalBasisKey(...) is returned when present
// (basis.fromCache = true); otherwise the basis is computed and stored.
// Throws InputError on bad settings (d < 1, d > 3f, no free vertex) and NumericalError when the
// eigen-solver does not converge or the result fails the ΦᵀMΦ = I check.
ModalBasis computeModalBasis(const DiscreteShell& shell, const std::vector<int>& pinned,
                             const ModalSettings& settings, BasisCache* cache = nullptr);

// The same from explicit matrices: K (3n×3n full-mesh stiffness, dyn/cm, symmetric),
// vertexMass (n, g), rest (n×3, cm) and F (m×3) for the rotation operator.
ModalBasis computeModalBasis(const SparseMat& K, const VecX& vertexMass, const MatX3& rest,
                             const MatX3i& F, const std::vector<int>& pinned,
                             const ModalSettings& settings);

// Eigen-solve only: the d lowest eigenpairs of K_FF φ = λ M_FF φ (K_FF 3f×3f, massDiag 3f, g).
// Returns λ ascending (d) and Φ (3f×d, M-orthonormal). `solverUsed` receives "dense"/"shift-invert".
void lowestModes(const SparseMat& Kff, const VecX& massDiag, const ModalSettings& settings,
                 VecX& lambda, MatX& Phi, std::string* solverUsed = nullptr);

// Load participation of a static load (METHOD.md §2.5): how much of the static compliance
// FᵀK_FF⁻¹F of the free force F (f×3, dyn) the basis captures, Σ_j (φ_jᵀF)²/λ_j ÷ FᵀK_FF⁻¹F.
struct LoadParticipation {
  VecX perMode;         // d entries (φ_jᵀF)²/λ_j, erg (0 for modes with λ ≤ 0)
  double modal = 0.0;   // Σ perMode, erg
  double total = 0.0;   // FᵀK_FF⁻¹F, erg
  double ratio = 0.0;   // modal/total in [0, 1]
};
// Needs a constrained system (K_FF nonsingular); throws NumericalError otherwise.
LoadParticipation loadParticipation(const ModalBasis& basis, const DiscreteShell& shell,
                                    const MatX3& freeForce);
// Same with an already restricted K_FF (3f×3f) — e.g. reused across many loads.
LoadParticipation loadParticipation(const ModalBasis& basis, const SparseMat& Kff,
                                    const MatX3& freeForce);

}  // namespace myo
