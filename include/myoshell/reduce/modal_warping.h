// Modal warping (Choi & Ko 2005; thesis eq. 10; METHOD.md §3): the linear modal system written in
// per-vertex rotated frames,
//
//   q̈ + (ξ + ζΛ) q̇ + Λ q = Φᵀ R(Ψq)ᵀ F,      u = R̃(Ψq) Φq   (per vertex)
//
// with R(w) = exp([w]×) rotating the forces into the local frames and R̃(w) = ∫₀¹exp(s[w]×)ds
// bending the linear displacement onto an arc (rotation_operator.h). All fields here are over the
// basis's free vertices only ("free" f×3 fields, row i = vertex basis.freeVertices[i]); pinned
// vertices never move.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "myoshell/core/errors.h"
#include "myoshell/core/types.h"
#include "myoshell/reduce/modal_basis.h"

namespace myo {

// ---------------------------------------------------------------------------------------------
// Displacement maps (the static modal solves built on them are in verify/modal_statics.h).

// Linear modal displacement u = Φq, free f×3 (cm). q: d (cm·g^1/2).
MatX3 linearDisplacement(const ModalBasis& basis, const VecX& q);
// Warped displacement u_i = R̃(Ψ_i q)·(Φ_i q), free f×3 (cm) (METHOD.md §3.4).
MatX3 warpedDisplacement(const ModalBasis& basis, const VecX& q);
// Projected modal force Φᵀ R(Ψq)ᵀ F (d, dyn·g^-1/2) of a free force F (f×3, dyn); with
// warped = false it is ΦᵀF.
VecX modalForce(const ModalBasis& basis, const VecX& q, const MatX3& freeForce, bool warped = true);

// ---------------------------------------------------------------------------------------------
// The time integrator.

enum class ModalStepper {
  Exact,         // exact per-mode step for a force held constant over the step (METHOD.md §3.5):
                 // unconditionally stable, no numerical damping, coefficients precomputed. Default.
  SemiImplicit,  // the thesis's semi-implicit (symplectic) Euler: v += h(f − cv − λq); q += h v.
                 // Stable only for h·√λ_max < 2: the constructor refuses larger steps.
};

enum class ModalPrecision {
  Float,   // basis streamed in float (half the memory traffic); q, q̇ and the warp stay double
  Double,  // everything in double (accuracy tests, reference comparisons)
};

struct ModalWarpingSettings {
  double dt = 1.0 / 60.0;                     // time step h, s (> 0)
  ModalStepper stepper = ModalStepper::Exact;
  bool warping = true;                        // false: plain linear modal u = Φq, forces unrotated
  double rayleighMass = 0.0;                  // ξ, 1/s   (C = ξM + ζK; per mode c_j = ξ + ζλ_j)
  double rayleighStiffness = 0.0;             // ζ, s
  ModalPrecision precision = ModalPrecision::Float;
  std::string channel = "channel";            // name used in error messages
};

// Steps one channel's modal-warping system. The constructor precomputes everything (interleaved
// per-vertex basis, per-mode step coefficients); step() allocates nothing and costs one pass over
// the basis (Φq and Ψq as one matvec) plus a pass over the loaded vertices' Φ rows.
class ModalWarpingIntegrator {
 public:
  // Throws InputError naming the channel for dt ≤ 0, negative damping, or (SemiImplicit) an
  // unstable dt: "channel 'NAME': semi-implicit Euler is unstable at dt = H s: the highest mode has
  // λ_max = L 1/s², so dt must be below 2/√λ_max = D s (use the exact stepper, a smaller dt or
  // fewer modes)".
  ModalWarpingIntegrator(std::shared_ptr<const ModalBasis> basis,
                         const ModalWarpingSettings& settings);

  // Advances one step of settings.dt under the free force F (f×3, dyn, world frame), held
  // constant over the step and rotated with R(Ψq) at the start of the step (METHOD.md §3.3).
  // Rows that are exactly zero are skipped. Then updates the displacement u = R̃(Ψq)Φq.
  void step(const MatX3& freeForce);
  // A step without force (free vibration / relaxation).
  void step();
  // Advances one step under a force already projected, f̃ = ΦᵀF (d, dyn·g^-1/2): the same per-mode
  // update as step(F). Linear integrators only (warping off: f̃ does not depend on q, so a caller
  // can form it from precomputed ΦᵀF of fixed load patterns). Does not touch the basis: u = Φq is
  // computed when it is next read (freeDisplacement, addDisplacementTo).
  void stepModal(const VecX& modalForce);
  // The follow response (docs/live.md, "Lag"): q = c + r, c a part the caller takes at once (the
  // quasi-static response to the activations), moving from `before` to `after` over the step, and
  // r = q − c stepped exactly under f̃, the force on r: r⁺ = a r + b ṙ + g f̃, q⁺ = after + r⁺,
  // ṙ⁺ = c r + e ṙ + k f̃ (qdot() then holds ṙ). Linear: as stepModal. With before = after = 0 it
  // is stepModal.
  void stepModalAbout(const VecX& modalForce, const VecX& before, const VecX& after);
  // Warped (or linear) with a free force: f̃ = Φᵀ R(Ψq)ᵀ F − Λ·after (the part of the force `after`
  // already balances), then as stepModalAbout; u updated as step(F).
  void stepAbout(const MatX3& freeForce, const VecX& before, const VecX& after);

  const VecX& q() const { return q_; }        // d, cm·g^1/2
  // The per-mode update's coefficients of q⁺ = a q + b q̇ + g f̃ (d each): what a caller with a force
  // that depends on q⁺ (a contact penalty taken implicitly) needs to solve for it.
  const VecX& stepQFromQ() const { return ca_; }
  const VecX& stepQFromQdot() const { return cb_; }
  const VecX& stepQFromForce() const { return cg_; }
  const VecX& qdot() const { return v_; }     // d, cm·g^1/2/s
  // The current displacement of the free vertices, f×3 (cm). After stepModal the first read
  // computes it (one pass over the basis), so two threads must not make that first read at once.
  const MatX3& freeDisplacement() const {
    if (stale_) updateDisplacement();
    return u_;
  }
  // A bound of every coordinate of the displacement, max_i ‖Φ_i‖_F ‖q‖₂ (cm, Φ_i the vertex's 3×d
  // rows), without computing it (the warp R̃ is an average of rotations: it does not lengthen).
  double displacementBound() const { return rowNormMax_ * q_.norm(); }
  // Adds the displacement into a full-mesh field (n×3, cm); rows of pinned vertices untouched.
  void addDisplacementTo(MatX3& full) const;
  // The current per-vertex rotation vectors w = Ψq, free f×3 (rad) (zeros when warping is off).
  MatX3 freeRotations() const;

  // Back to rest: q = q̇ = 0, u = 0.
  void reset();
  // Sets the modal state (d each) and recomputes u.
  void setState(const VecX& q, const VecX& qdot);
  // True when every |q_j| and |q̇_j| is below tol.
  bool isAtRest(double tol) const;
  // Modal energy ½q̇ᵀq̇ + ½qᵀ(sΛ)q (erg): kinetic + linear elastic in the local frames.
  double energy() const;

  // Scales the stiffness: Λ ← sΛ (s > 0), damping c_j = ξ + ζ sλ_j recomputed, Φ and Ψ kept (so
  // mode shapes do not change, frequencies scale by √s). The state is kept. Throws like the
  // constructor if the semi-implicit stepper becomes unstable (the previous scale is kept then).
  void setStiffnessScale(double s);
  double stiffnessScale() const { return scale_; }

  const ModalBasis& basis() const { return *basis_; }
  const ModalWarpingSettings& settings() const { return settings_; }
  // What a step streams from the basis when it touches every free vertex: the interleaved Φ rows
  // (and Ψ rows when warping) in the storage precision, 3 (or 6) × f × d values, in bytes.
  size_t basisBytes() const;
  // Reads each of those stored values once, in storage order, and returns their sum: the memory
  // floor of a step over every free vertex (myoshell bench's floor_ratio). Allocates nothing.
  double streamBasis() const;
  // Largest stable semi-implicit step for this basis and scale: 2/√(sλ_max) (s); +∞ if λ_max ≤ 0.
  double maxSemiImplicitDt() const;

  ~ModalWarpingIntegrator();
  ModalWarpingIntegrator(ModalWarpingIntegrator&&) noexcept;
  ModalWarpingIntegrator& operator=(ModalWarpingIntegrator&&) noexcept;

 private:
  struct Kernel;  // precision-specific interleaved basis and scratch buffers
  void computeCoefficients();
  void updateDisplacement() const;
  void advance(const VecX& modalForce);  // the per-mode update of q and q̇ under f̃
  void advanceAbout(const VecX& modalForce, const VecX& before, const VecX& after);
  void projectForce(const MatX3& freeForce);  // ftilde_ = Φᵀ R(Ψq)ᵀ F

  std::shared_ptr<const ModalBasis> basis_;
  ModalWarpingSettings settings_;
  double scale_ = 1.0;
  VecX q_, v_, ftilde_;
  // Per-mode step coefficients (Exact): q⁺ = a q + b v + g f, v⁺ = c q + e v + k f.
  VecX ca_, cb_, cg_, cc_, ce_, ck_;
  VecX lambdaEff_, damping_;  // sλ_j and c_j
  mutable MatX3 u_;
  mutable bool stale_ = false;  // u_ (and the kernel's Φq) lag q_ (after stepModal)
  double rowNormMax_ = 0.0;     // max_i ‖Φ_i‖_F
  std::unique_ptr<Kernel> kernel_;
};

}  // namespace myo
