// A constrained modal basis of one subsystem ("channel"): the d lowest modes of K Φ = M Φ Λ over
// the free vertices of a shell (thesis eq. 8; METHOD.md §2), with the modal rotation matrix
// Ψ = WΦ of modal warping (METHOD.md §3.2). Memory is proportional to the free region, not to
// the whole mesh.
//
// Units (cm–g–s): Φ is mass-orthonormal (ΦᵀMΦ = I), so Φ is in g^-1/2 and a modal amplitude q is
// in cm·g^1/2; λ = ω² is in 1/s²; Ψ maps q to nodal rotation vectors in rad, so Ψ is in
// rad/(cm·g^1/2).
#pragma once

#include <string>
#include <vector>

#include "myoshell/core/types.h"

namespace myo {

struct ModalBasis {
  // Vertex count of the full mesh the basis was built on.
  int fullVertexCount = 0;
  // The f free (unpinned) vertices, sorted ascending, as indices into the full mesh. Row i of
  // every f×3 "free" field, and rows 3i..3i+2 of Phi/Psi, belong to vertex freeVertices[i].
  std::vector<int> freeVertices;
  // 3f×d mode shapes over the free DOFs only (vertex-major x,y,z), g^-1/2; ΦᵀMΦ = I, ΦᵀKΦ = Λ.
  MatX Phi;
  // d eigenvalues λ_j = ω_j², 1/s², ascending. Rigid (unconstrained) modes give λ ≈ 0.
  VecX lambda;
  // 3f×d modal rotation matrix Ψ = WΦ: w = Ψq gives per-vertex rotation vectors (rad).
  MatX Psi;
  // f lumped masses of the free vertices (g), the diagonal of M_FF per vertex.
  VecX freeMass;

  // Bookkeeping, not part of the cached payload's identity:
  double solveSeconds = 0.0;  // wall time of the eigen-solve (0 when loaded from a cache)
  std::string solver;         // "dense" or "shift-invert"
  bool fromCache = false;     // true when returned by a BasisCache

  int freeCount() const { return static_cast<int>(freeVertices.size()); }
  int modeCount() const { return static_cast<int>(lambda.size()); }
  // Bytes held by the matrices (Phi, Psi, lambda, freeMass, freeVertices).
  size_t memoryBytes() const;
  // The full-mesh → free-row map: n entries, -1 for pinned vertices.
  std::vector<int> fullToFree() const;
};

// Scatters a free field (f×3, one row per free vertex) into a full-mesh field (n×3, zeros on
// pinned vertices).
MatX3 scatterToFull(const ModalBasis& basis, const MatX3& freeField);
// Gathers the free rows (f×3) of a full-mesh field (n×3), e.g. a force given on the whole mesh.
MatX3 gatherFree(const ModalBasis& basis, const MatX3& fullField);

}  // namespace myo
