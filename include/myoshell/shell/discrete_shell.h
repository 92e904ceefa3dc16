// The discrete-shell energy of thesis eq. 1–4 (Grinspun et al. 2003, as used by Choi, Woo & Ko 2007):
//
//   E = k_A Σ_t (|A_t| − |Ā_t|)²/|Ā_t|  +  k_L Σ_e (|e| − |ē|)²/|ē|  +  k_B Σ_{interior e} 3 (θ_e − θ̄_e)² |ē|/h̄_e
//
// with h̄_e = (Ā_1 + Ā_2)/|ē| the average rest height of the two faces over e, so that the bending
// weight is 3|ē|²/(Ā_1 + Ā_2) (METHOD.md §1.2). Rest quantities are precomputed once.
#pragma once

#include <memory>
#include <vector>

#include "myoshell/core/types.h"
#include "myoshell/mesh/edge_table.h"
#include "myoshell/shell/shell_material.h"

namespace myo {

namespace detail {
struct ShellHessianLayout;  // discrete_shell.cpp
}

// The three energies before multiplying by their stiffnesses, and the weighted total.
struct ShellEnergy {
  double EA = 0.0;     // Σ (A − Ā)²/Ā, cm²
  double EL = 0.0;     // Σ (l − l̄)²/l̄, cm
  double EB = 0.0;     // Σ 3(θ − θ̄)²|ē|/h̄_e, dimensionless
  double total = 0.0;  // k_A E_A + k_L E_L + k_B E_B, erg
};

// How to treat the indefinite parts of the Hessian.
enum class HessianMode {
  Exact,      // the true Hessian (for finite-difference tests and analysis)
  Projected,  // each element's block projected to positive semi-definite (Newton's method)
};

class DiscreteShell {
 public:
  // rest: n×3 rest positions (cm); F: m×3 triangles; edges: buildEdgeTable(F, n).
  DiscreteShell(const MatX3& rest, const MatX3i& F, const EdgeTable& edges, const ShellMaterial& material);

  // Energy at positions x (n×3, cm). When grad is non-null it receives ∂E/∂x (3n, dyn, vertex-major
  // x0,y0,z0,x1,…); when hess is non-null it receives ∂²E/∂x² (3n×3n sparse, symmetric, dyn/cm).
  // The Hessian always has the same compressed pattern (every 3×3 block of two vertices sharing a
  // triangle or a hinge, zeros stored), whatever x, mode and material: a solver can analyse it once.
  // Collapsed elements (zero area or length, hinge normals |n| ≤ 1e-10|e|²) keep their energy but
  // contribute no force and no stiffness.
  ShellEnergy energy(const MatX3& x, VecX* grad = nullptr, SparseMat* hess = nullptr,
                     HessianMode mode = HessianMode::Exact) const;

  // The linearized stiffness K = ∇²E(X̄) at rest (3n×3n, dyn/cm, symmetric PSD), built from rest
  // gradients only (METHOD.md §1.5): the thesis's constant K of eq. 7. Same pattern as the Hessian.
  SparseMat stiffnessAtRest() const;

  // Lumped mass per vertex (n): m_i = ρ·t·Σ_{t∋i} Ā_t/3, grams.
  const VecX& lumpedMass() const { return mass_; }

  const MatX3& rest() const { return rest_; }
  const MatX3i& triangles() const { return F_; }
  const EdgeTable& edgeTable() const { return edges_; }
  const ShellMaterial& material() const { return material_; }
  int vertexCount() const { return static_cast<int>(rest_.rows()); }
  // Rest dihedral angle θ̄ per edge of edgeTable() (rad; 0 on boundary edges), positive on a
  // convex surface with outward normals (METHOD.md §1.1).
  const std::vector<double>& restDihedralAngles() const { return restTheta_; }
  // Bending weight c_e = 3|ē|²/(Ā1 + Ā2) per edge (dimensionless; 0 on boundary edges).
  const std::vector<double>& bendingWeights() const { return bendWeight_; }

  // Returns a copy of this shell with another material (same mesh, same rest state).
  DiscreteShell withMaterial(const ShellMaterial& material) const;

 private:
  MatX3 rest_;
  MatX3i F_;
  EdgeTable edges_;
  ShellMaterial material_;
  std::vector<double> restArea_;     // per triangle, cm²
  std::vector<double> restLength_;   // per edge, cm
  std::vector<double> restTheta_;    // per edge (0 on boundary edges), rad
  std::vector<double> bendWeight_;   // per edge: 3|ē|²/(Ā_1 + Ā_2), 0 on boundary edges
  VecX mass_;                        // per vertex, g
  // The fixed sparsity of ∇²E and K (3×3 blocks for every vertex pair sharing an element) and each
  // element's positions in it, so Hessians are filled in place instead of through triplets.
  // Defined in discrete_shell.cpp; shared by copies (withMaterial).
  std::shared_ptr<const detail::ShellHessianLayout> layout_;

  void computeMass();  // mass_ from restArea_ and material_
};

}  // namespace myo
