// Load-dependent Ritz vectors (Wilson, Yuan & Dickens 1982; METHOD.md §9): a basis for a positive
// definite system K (no pins) that holds its d lowest modes and, for each expected load pattern f,
// the static response K⁻¹f, so that the reduced static response of every such load is exact:
//
//   1. Φ₀: the d lowest modes of K φ = λ M φ (M lumped, ΦᵀMΦ = I);
//   2. per load f_k: r = K⁻¹f_k from the kept factorisation; M-orthogonalise against the basis
//      twice (classical Gram–Schmidt, repeated); drop r when ‖r‖_M after / before < tolerance
//      (deflation: f_k's response is already in the span), else normalise (‖r‖_M = 1), append;
//   3. the reduced eigenproblem K_r Z = Z Λ with K_r = ΦᵀKΦ (M_r = I): Φ ← ΦZ, so ΦᵀKΦ = Λ is
//      diagonal again and the per-mode stepper (METHOD.md §3.5) applies unchanged;
//   4. Ψ = WΦ (rotation_operator.h): W is linear, so Ψ ← ΨZ after step 3.
// Because span(Φ) ∋ K⁻¹f_k and Φ is K-orthogonal, ΦΛ⁻¹Φᵀf_k = K⁻¹f_k (to round-off).
//
// Units: as ModalBasis (modal_basis.h): Φ in g^-1/2, λ in 1/s², f in dyn.
#pragma once

#include <memory>
#include <vector>

#include <Eigen/SparseCholesky>

#include "myoshell/core/types.h"
#include "myoshell/reduce/modal_analysis.h"
#include "myoshell/reduce/modal_basis.h"

namespace myo {

struct RitzSettings {
  ModalSettings modes;                  // d and the eigen-solver of step 1 (modes.modeCount ≥ 0)
  double deflationTolerance = 1e-8;     // step 2's drop threshold
};

class RitzBasisBuilder {
 public:
  // K: 3n×3n symmetric positive definite (dyn/cm); vertexMass: n (g, > 0); rest: n×3 (cm) and
  // triangles F (m×3) for the rotation operator. Factorises K (kept) and computes step 1 (with
  // modes.modeCount = 0 the basis starts empty). Throws NumericalError when K is not positive
  // definite or the eigen-solve fails, InputError on bad shapes or settings.
  RitzBasisBuilder(const SparseMat& K, const VecX& vertexMass, const MatX3& rest, const MatX3i& F,
                   const RitzSettings& settings = {});
  // Continues from `start`, a diagonalised basis a builder with the same K, masses, mesh and
  // settings made earlier (a cached one): factorises K but skips step 1, so further loads give
  // what they would have given on the builder that made `start`. InputError when start's shape
  // does not fit (n vertices, all free; Phi, Psi 3n×d; d eigenvalues).
  RitzBasisBuilder(const SparseMat& K, const VecX& vertexMass, const MatX3& rest, const MatX3i& F,
                   const RitzSettings& settings, ModalBasis start);

  // Step 2 for one load f (n×3, dyn): returns true when a vector was appended, false when it was
  // deflated (or f = 0). The reduced system is not re-diagonalised until diagonalize().
  bool addLoad(const MatX3& f);
  // addLoad for each load in order, with the solves spread over parallelThreads() (core/parallel.h):
  // the same basis, bit for bit, as the serial calls. Returns how many vectors were appended.
  int addLoads(const std::vector<MatX3>& loads);
  // Step 3–4. Idempotent.
  void diagonalize();
  // addLoad + diagonalize: a load added at run time (a drag grabbed by the user).
  bool addLoadAndDiagonalize(const MatX3& f);

  // The current basis over all n vertices (freeVertices = 0..n−1). Call diagonalize() first after
  // adding loads (otherwise lambda holds the diagonal of ΦᵀKΦ only and is flagged by isDiagonal()).
  const ModalBasis& basis() const { return basis_; }
  bool isDiagonal() const { return diagonal_; }
  int loadVectors() const { return appended_; }   // static responses appended so far
  int deflated() const { return deflated_; }      // loads dropped by deflation
  // K⁻¹f with the kept factorisation (n×3, cm).
  MatX3 staticResponse(const MatX3& f) const;
  const SparseMat& stiffness() const { return K_; }
  // W (3n×3n, rotation_operator.h): Ψ = WΦ for a vector a caller appends to a copy of the basis.
  const SparseMat& rotationOperator() const { return W_; }

 private:
  SparseMat K_;
  SparseMat W_;
  VecX mass3_;  // 3n
  Eigen::SimplicialLDLT<SparseMat> ldlt_;
  RitzSettings settings_;
  ModalBasis basis_;
  bool diagonal_ = true;
  int appended_ = 0;
  int deflated_ = 0;
  bool appendResponse(VecX r);  // step 2 after the solve: orthogonalise, deflate or append
  void prepare(const VecX& vertexMass, const MatX3& rest, const MatX3i& F);  // checks, W, M
  void factorize();                                                           // K = LDLᵀ, kept
};

}  // namespace myo
