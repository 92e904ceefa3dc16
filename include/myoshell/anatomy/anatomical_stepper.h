// Time stepping of the anatomical face's one skin (anatomical_skin.h): the muscles' activation levels,
// the modal step, contact in the step, and grips moved at run time (anatomical_grab.cpp).
#pragma once

#include <Eigen/LU>
#include <memory>
#include <vector>

#include "myoshell/anatomy/anatomical_skin.h"
#include "myoshell/anatomy/contact_penalty.h"
#include "myoshell/core/types.h"
#include "myoshell/reduce/modal_warping.h"

namespace myo {

// Time stepping of one AnatomicalSkin: each muscle's activation level follows its target with a
// critically damped second-order response at the muscle's natural frequency (its one mode), the
// skin with the per-mode exact stepper of modal_warping. Gravity reading (b). step() allocates
// nothing, but for the lids' fissure curves when a lid is driven and the contact penalty is on.
//
// Contact (loads.contact, linear modes): the penalty (contact_penalty.h) at q_n, taken linearly
// implicitly, one d×d solve on steps where something touches; it reads the contact candidates' rows
// of Φ every step (docs/mouth_contact.md, "Penalty forces"). Warped: no penalty in the step.
//
// Linear modes (warping off, the default): the loads are fixed patterns scaled by the levels,
// g − g_rest and the drag forces, so the modal force ΦᵀF is the product of their reduced patterns
// (AnatomicalSkin::modalLoadPatterns, d × (M + 3 + 3·drags), made once) with those coordinates:
// a step reads no basis row and builds no n×3 force; u = Φq is computed when displacement() is
// read. Warped: the n×3 force is assembled and rotated per vertex (ModalWarpingIntegrator::step).
//
// Response (AnatomicalSettings::response; docs/live.md, "Lag"): Dynamic as above; Follow sets the
// levels to the targets and splits q = c + r, c = Λ⁻¹Φᵀ Σ a_m F_m taken at once, r stepped exactly
// under the force c does not balance (linear: gravity, drags, contact; warped: Φᵀ R(Ψq)ᵀ F − Λc).
// Both settle at the same q; a Follow step reads no basis row more (c is one d×M product).
class AnatomicalStepper {
 public:
  explicit AnatomicalStepper(std::shared_ptr<const AnatomicalSkin> skin);
  // Advances one dt under the loads (activation targets, gravity, drag forces, the jaw and the
  // contact switch for the penalty).
  void step(const SkinLoads& loads);
  // n×3, cm. Linear modes: the first read after a step computes u = Φq (one pass over the basis).
  const MatX3& displacement() const { return integrator_.freeDisplacement(); }
  // A bound of every coordinate of displacement() (cm), without computing it
  // (ModalWarpingIntegrator::displacementBound).
  double displacementBound() const { return integrator_.displacementBound(); }
  // The levels (Dynamic) or the targets (Follow: the levels are the targets).
  const VecX& muscleLevels() const { return level_; }
  // The response (skin_settings.h; docs/live.md, "Lag"), the skin's settings' at first. A switch
  // keeps the displacement: Follow takes the levels' quasi-static response as its centre (the rest
  // of q and q̇ becomes the dynamic part), Dynamic keeps q and q̇ with the levels at rest.
  void setResponse(SkinResponse response);
  SkinResponse response() const { return response_; }
  bool isAtRest(double tol) const;
  // Back to rest (levels, q, q̇ and u zero), as a new stepper on the same skin; grips moved by
  // grab() stay where they are (with their vectors in the basis).
  void reset();

  // Moves drag `drag`'s grip to the vertices within `radius` (cm, ≥ 0) of `vertex`, for this
  // stepper only: the skin is shared and immutable, so the basis is extended here, the way a drag
  // known at build time enters the skin's (docs/anatomical_model.md, "A grip moved at run time"):
  // the grip's three load patterns' static responses K⁻¹f (K = K̂ with the relaxed muscles
  // released: K̂⁻¹f from the skin's kept factorisation, the release by Woodbury through the held
  // basis) join the skin's basis with those of the other moved grips and the current state's two
  // fields Φq and Φq̇, M-orthonormalised (Ritz deflation), the reduced system re-diagonalised and the
  // state carried over by M-projection (the displacement does not jump: it lies in the new span).
  // Grabbing the grip it already has, or a vertex set the skin's own drag has, adds nothing of its
  // own. With linear modes (warping off) an extended basis carries no Ψ (the integrator reads it
  // only when warping). Allocates; returns the wall time (s, the grab latency). Safe while other steppers on the
  // same skin step or grab (the factorisation is made once under the skin's lock, then only read).
  // InputError for a vertex outside the mesh or a negative radius.
  double grab(int drag, int vertex, double radius);
  // Where the last grab's time went (s): making the factorisation and reading the held basis (the
  // first grab on a skin after a warm start; 0 after), the responses (the three solves, `solves`,
  // and the release), the new basis (orthonormalisation, reduced eigenproblem, Φ (and Ψ) turned),
  // the integrator, the load patterns and the contact penalty on it (`finish`).
  struct GrabTimes {
    double factorisation = 0.0, responses = 0.0, solves = 0.0, basis = 0.0, finish = 0.0, total = 0.0;
  };
  const GrabTimes& lastGrabTimes() const { return grabTimes_; }
  // The vertices drag `drag`'s force is spread over (the skin's drag until grabbed elsewhere).
  const std::vector<int>& dragVertices(int drag) const { return grips_[static_cast<size_t>(drag)].vertices; }
  // Wall time of the last step's phases (s): the activation levels, the force (linear: the modal
  // force from the reduced patterns; warped: the n×3 assembly of muscle loads, gravity, drags), the
  // modal step (the per-mode update; warped also Φᵀ R(Ψq)ᵀ f and u = R̃Φq).
  struct Times {
    double levels = 0.0, force = 0.0, modal = 0.0;
  };
  const Times& lastTimes() const { return times_; }
  // The skin's integrator (what myoshell bench streams for its floor).
  const ModalWarpingIntegrator& integrator() const { return integrator_; }

 private:
  std::shared_ptr<const AnatomicalSkin> skin_;
  Times times_;
  GrabTimes grabTimes_;
  // Per drag: the vertices its force is spread over and, once grabbed away from the skin's drag,
  // the static responses K⁻¹f of its x, y, z patterns (3n×3; empty while it is the skin's own).
  struct Grip {
    std::vector<int> vertices;
    MatX responses;
  };
  std::vector<Grip> grips_;
  ModalWarpingIntegrator integrator_;
  std::shared_ptr<const ContactPenalty> penalty_;  // the skin's, or one on this stepper's basis
  VecX level_, levelRate_;
  SkinResponse response_ = SkinResponse::Dynamic;
  // Follow: Λ⁻¹Φᵀ[F_1 … F_M] (d × M, the activations' quasi-static modal response, made on the
  // basis when Follow is chosen), the centre c = quasiStatic_·level_ the last step ended on and the
  // next step's.
  MatX quasiStatic_;
  VecX centre_, centreNext_;
  MatX3 force_;         // warped: the n×3 world force (empty with linear modes)
  MatX loadModes_;      // linear: the skin's modalLoadPatterns for the integrator's basis
  VecX loadCoords_;     // linear: [levels, g − g_rest, drag forces]
  VecX modalForce_;     // linear: f̃ = loadModes_ · loadCoords_ (d)
  ContactPenalty::Workspace contact_;  // the penalty's scratch (when the skin has one)
  MatX contactStiffness_, contactSystem_;  // K_c and I + diag(g) K_c (d×d)
  VecX contactForce_, contactStep_;        // f_c and Δ (d)
  Eigen::PartialPivLU<MatX> contactLu_;
  // What depends on the integrator's basis: the reduced load patterns (the moved grips' columns
  // from their vertices) and the contact penalty's rows and scratch.
  void fitToBasis();
};

}  // namespace myo
