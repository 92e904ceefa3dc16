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
// vertex mass (a lip pair: half the lighter one's). The reduced force is −∂E/∂q = −Σ_t k_t δ_t a_t,
// a_t = Σ_i (∂x_i/∂q)ᵀ ∇δ_t. Where a vertex's turn is fixed, ∂x_i/∂q = J_i Φ_i, J_i = R_lid,i R_jaw,i
// the rotations the lid (only raised) and the jaw turned the residual by. A vertex a lid turns while
// closing, or following the gaze, is placed by the fissure its margins have now and by its own
// distance along the eye's axis (eyelids.h), so its ∂x_i/∂q also holds the turn's dependence on those
// rows: there a_t is summed over the few rows the turn reads at the vertex (turnLidVertexGradient:
// the margin entries about its x and Δmax's, and its own). Without that chain the force was not a
// gradient where a lid closed onto the eyeball, and the step circled the settle's equilibrium instead
// of resting
// there (docs/mouth_contact.md, "A closed lid keeps the step from resting"). Only the candidates'
// rows are read, and only the violated ones' rows are projected. With no violation the force is
// exactly zero (the unloaded results stay bit for bit). Bound: Σ_t k_t (Φᵀ Jᵀ∇δ_t)(…)ᵀ ≤ κ Φᵀ M Φ = κ I for
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

  // An eyeball term on a vertex a lid turns: its candidate row, its lid slot (eye, index in
  // lidVertices), k_t, δ_t and ∇δ_t (the turn's chain, evaluate).
  struct ClosureTerm {
    int row = 0, eye = 0, slot = 0;
    double k = 0.0, depth = 0.0;
    Vec3 grad = Vec3::Zero();
  };
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
    // The turn's chain: the jawed rows before the lids' turn, moved ±h along a mode.
    MatX3 jawed;                                   // n×3: the margins' and the touching lid vertices' rows
    LidFissure movedFissure;
    std::vector<ClosureTerm> closureTerms;
    std::vector<std::pair<int, Vec3>> closureReads;  // one term's rows read and ∂(∇δ·x)/∂p
  };
  Workspace workspace() const;

  // The penalty at q: returns E (erg). Adds −∂E/∂q to *force (d) and the Gauss–Newton stiffness
  // Σ_t k_t a_t a_tᵀ to *stiffness (d×d) when given; *maxDepth receives the deepest violation (cm);
  // *stiffness must be symmetric (it stays so).
  double evaluate(const VecX& q, const JawPose& jaw, const LidPose& lids, Workspace& ws, VecX* force,
                  MatX* stiffness = nullptr, double* maxDepth = nullptr) const;

  double stiffnessPerMass() const { return kappa_; }
  const std::vector<int>& candidates() const { return rows_; }

 private:
  const SkinPlacement* placement_;  // outlives this (the skin holds both)
  MatX3 rest_;                      // the candidates' rest rows only (k×3)
  VecX mass_;                       // k
  std::vector<int> rows_;           // candidate vertices, ascending
  std::vector<int> rowOf_;          // n: the candidate index of a vertex, −1 for none
  std::vector<std::array<int, 2>> lidSlot_;  // k: (eye, index in its lidVertices) of a lid vertex, {−1, −1} else
  // A candidate's place before the lids' turn (the jaw's blended turn of rest + u), and that turn.
  Vec3 jawed(Eigen::Index r, const Vec3& u, const JawPose& jaw, Mat3* turn) const;
  // The eyeball terms on vertices a lid turns (ws.closureTerms): their a_t through the turn's chain,
  // added to the force and the stiffness as evaluate adds the other terms'.
  void closureChain(const JawPose& jaw, const LidPose& lids, Workspace& ws, VecX* force, MatX* stiffness) const;
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> Phi_;  // 3k × d
  int n_ = 0;
  double kappa_ = 0.0;
};

}  // namespace myo
