// Reduced penalty forces for the anatomical skin's contact (docs/mouth_contact.md and
// docs/eyelids.md, "Penalty forces"; issue 17): the lids against the eyeball proxies, the lips
// against the teeth proxies and against each other, felt by the physics rather than only projected
// at output.
//
// The contact candidates are the rows SkinPlacement::place reads to place the contact vertices: the
// lid vertices and margins, the orbit vertices, the mouth's tested vertices and its lip pairs. For
// modal amplitudes q (d), their residual is u_i = Φ_i q (Φ_i the basis's 3 rows of vertex i), their
// placed position x_i (the jaw's turn, then the lids', as place does), and every violated constraint t
// (a vertex inside an eyeball: depth R_c − |x − c|; inside the teeth: the projection's depth along the
// ray from the arch's axis; a lip pair crossing: its violation along the frame's y) adds
//   E_t = ½ k_t δ_t²,     k_t = κ m_t (dyn/cm),
// κ the penalty stiffness per unit mass (1/s², AnatomicalSettings::contactStiffness) and m_t the
// vertex mass (a lip pair: half the lighter one's). The reduced force is −∂E/∂q = −Σ_i Φ_iᵀ J_iᵀ ∂E/∂x_i
// with J_i = R_lid,i R_jaw,i, the rotations the lid and the jaw turned the residual by (the change of
// the distance from the eye's axis a closure adds, and the closure's dependence on the margins' own
// residual, are left out of J: exact with the lids open or only raised). Only the candidates' rows
// are read, and only the violated ones' rows are projected. With no violation the force is exactly
// zero (the unloaded results stay bit for bit). Bound: Σ_t k_t (Φᵀ Jᵀ∇δ_t)(…)ᵀ ≤ κ Φᵀ M Φ = κ I for
// unit ∇δ and one term per vertex, so the penalty's reduced stiffness is at most about κ.
#pragma once

#include <array>
#include <vector>

#include "myoshell/anatomy/eyelids.h"
#include "myoshell/anatomy/skin_placement.h"
#include "myoshell/core/types.h"
#include "myoshell/head/jaw.h"
#include "myoshell/reduce/modal_basis.h"

namespace myo {

// The static responses' load patterns for the contact (n×3 each, dyn per unit: m_i times a unit
// direction, weighted): per eye the upper and the lower lid's orbit vertices pushed along the
// eyeball's outward normal (weighted by the lid weight |w|); the upper and the lower lip's tested
// vertices pushed out of the teeth along the arch's outward ray (weighted by nearness to the arch at
// rest, 1 on it, 0 from 5 mm out); the upper lip's paired vertices pushed up (+y) and the lower
// lip's down (−y). Empty for a head with nothing to touch; a pattern with no vertex is left out.
std::vector<MatX3> contactLoadPatterns(const SkinPlacement& placement, const MatX3& rest, const VecX& vertexMass);

class ContactPenalty {
 public:
  // κ (1/s², > 0). The basis's rows of the candidates are copied (3 × d each).
  ContactPenalty(const SkinPlacement& placement, const MatX3& rest, const VecX& vertexMass, const ModalBasis& basis,
                 double stiffnessPerMass);

  // Scratch for evaluate (one per thread; made once, reused without allocating).
  struct Workspace {
    MatX3 positions;                               // n×3: only the candidates' rows are kept up to date
    VecX u;                                        // 3k: the candidates' residual
    std::vector<Mat3> J;                           // k: J_i = R_lid,i R_jaw,i
    std::array<std::vector<Mat3>, 2> lidTurns;     // the lids' rotation per lid vertex
    LidFissure fissure;                            // the lids' margins, measured at each turn
    MatX3 gradient;                                // k×3: ∂E/∂x per candidate, head space
    std::vector<int> active;                       // candidate indices in a violated constraint
    std::vector<char> flagged;                     // k: whether a candidate is in `active`
    VecX a;                                        // d: one term's a_t
  };
  Workspace workspace() const;

  // The penalty at q: returns E (erg). Adds −∂E/∂q to *force (d) and the Gauss–Newton stiffness
  // Σ_t k_t a_t a_tᵀ (a_t = Σ_i Φ_iᵀ J_iᵀ ∇δ_t) to *stiffness (d×d) when given; *maxDepth receives
  // the deepest violation (cm); *stiffness must be symmetric (it stays so). `rowForce`, when given (n×3, head space, the residual's frame),
  // receives −J_iᵀ ∂E/∂x_i added at each violated vertex (the warped step's world force).
  double evaluate(const VecX& q, const JawPose& jaw, const LidPose& lids, Workspace& ws, VecX* force,
                  MatX* stiffness = nullptr, double* maxDepth = nullptr, MatX3* rowForce = nullptr) const;

  double stiffnessPerMass() const { return kappa_; }
  const std::vector<int>& candidates() const { return rows_; }

 private:
  const SkinPlacement* placement_;  // outlives this (the skin holds both)
  MatX3 rest_;                      // the candidates' rest rows only (k×3)
  VecX mass_;                       // k
  std::vector<int> rows_;           // candidate vertices, ascending
  std::vector<int> rowOf_;          // n: the candidate index of a vertex, −1 for none
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> Phi_;  // 3k × d
  int n_ = 0;
  double kappa_ = 0.0;
};

}  // namespace myo
