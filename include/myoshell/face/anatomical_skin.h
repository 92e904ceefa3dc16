// The anatomical face's one skin system (docs/anatomical_model.md; METHOD.md §9): the skin shell
// held by the skull (tissue_attachment.h), coupled to feed-forward muscles at their closest skin
// points (muscle_coupling.h), loaded by gravity relative to the rest pose and by drags, all on one
// basis of load-dependent Ritz vectors (ritz_basis.h), warped (modal_warping.h).
//
//   K̂ = K_shell + K_att + Σ_m K_c,m   (3n×3n, dyn/cm, positive definite: no pins)
//   M = diag(ρ h_i A_i) ⊗ I₃           (the skin and the soft tissue it carries, g)
//   loads (n×3, dyn, world = head space): a_m F_m (muscle m at activation a_m ∈ [0, 1]),
//   gravity relative to the rest pose (GravityReading), drags.
//
// Precompute once (constructor); settle() solves the reduced static equilibrium directly;
// AnatomicalStepper steps it in time with the per-mode exact stepper. With a BasisCache the Ritz
// basis (the expensive part: factorising K̂, its d lowest modes, the static responses) is kept
// between runs under anatomicalBasisKey; a hit is the very basis a fresh build makes (bit for bit),
// and K̂ is then factorised only when something needs it (addDrag, linearFullResponse).
#pragma once

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "myoshell/core/types.h"
#include "myoshell/reduce/basis_cache.h"
#include "myoshell/face/contact_penalty.h"
#include "myoshell/face/head.h"
#include "myoshell/face/jaw.h"
#include "myoshell/face/muscle_coupling.h"
#include "myoshell/face/skin_placement.h"
#include "myoshell/face/tissue_attachment.h"
#include "myoshell/reduce/modal_warping.h"
#include "myoshell/reduce/ritz_basis.h"
#include "myoshell/shell/discrete_shell.h"

namespace myo {

// How gravity loads the warped skin, relative to the rest pose (METHOD.md §9). The rest mesh is in
// equilibrium under M g_rest (upright); both readings give zero load upright.
enum class GravityReading {
  RotatedPrestress,  // (a): Φᵀ Rᵀ M g(t) − Φᵀ M g_rest (the rest pre-stress turns with the tissue)
  ChangeOnly,        // (b): Φᵀ Rᵀ M (g(t) − g_rest) (only the change of gravity is a load)
};

// What a muscle's strength rule holds to its shortening σ at a = 1, alone among the relaxed others
// (docs/anatomical_model.md, "Strength").
enum class StrengthRule {
  MuscleShortens,  // the muscle's own coordinate: q_m = 1 (the skin over it lags behind)
  SkinFollows,     // the skin it is tied to: its coupling-weighted motion along the shape, cᵀu/s = 1
};

struct AnatomicalSettings {
  // Skin (dermis) as a membrane + bending shell from a Young's modulus and thickness (ν = 0.5):
  // k_A = E h/6, k_L = 0.385 E h ℓ̄ (ℓ̄ the mean edge length), k_B = E h³/(12(1 − ν²))
  // (docs/anatomical_model.md derives the factors for an equilateral mesh).
  double skinYoungModulus = 1.0e6;  // dyn/cm² (0.1 MPa)
  double skinThickness = 0.15;      // cm
  AttachmentSettings attachment;
  std::vector<AttachmentOverride> attachmentOverrides;
  MuscleCouplingSettings coupling;
  int skinModes = 30;               // d lowest modes in the Ritz basis
  double gravity = 981.0;           // cm/s²; the rest pose is upright: g_rest = −gravity·ŷ (head space)
  GravityReading gravityReading = GravityReading::ChangeOnly;
  // Linear modes: against the full-space nonlinear reference (zygomaticus, a = 1) they err 15.0 %,
  // modal warping 17.5 %, and warping stretches a mouth-corner edge by 140 % where the reference
  // stretches it by 29 % (docs/anatomical_model.md, "Warping or linear modes").
  bool warping = false;
  double dampingMass = 8.0;         // ξ, 1/s (Rayleigh)
  double dampingStiffness = 2e-4;   // ζ, s
  double dt = 1.0 / 240.0;          // s
  // Relaxed muscles follow the skin (docs/anatomical_model.md, "Relaxed muscles follow the skin"):
  // each muscle's coordinate along its shape is condensed out with the passive stiffness
  // κ_m = E_p A_m σ_m² L_m of its belly (A_m its cross-section, L_m its length, σ_m its shortening at
  // a = 1), E_p this modulus along the fibres of a muscle at rest. 0: every muscle holds the skin
  // over it at its rest place whatever its activation (the couplings fed forward only).
  double relaxedMuscleModulus = 1.0e5;  // dyn/cm² (10 kPa, passive skeletal muscle at rest length)
  // Release each relaxed muscle across its fibres too: besides its shape, the muscle moves with the
  // skin in the three directions (its motion weighted as its shape's, S-orthogonal to the shape), with
  // the same passive stiffness per unit of coupling energy (docs/anatomical_model.md, "Released
  // across"). false: only along the shape, the model of the first release.
  bool releaseAcross = true;
  // Release a ring muscle in its two halves, each with its own coordinates (along and across) and
  // half the belly: the mouth's upper and lower parts into their right and left quadrants, the eye's
  // rings into their upper and lower arcs between the canthi (docs/anatomical_model.md, "A ring is
  // released in halves"). false: one release for the whole ring, which ties the two mouth corners.
  bool releaseRingHalves = true;
  // The fibres insert into the dermis: at a = 1 the skin over the insertion moves with the muscle end.
  StrengthRule strength = StrengthRule::SkinFollows;
  // Contact (docs/mouth_contact.md, docs/eyelids.md): on a head with eyeballs or teeth proxies, the
  // penalty forces in the step and the settle (for loads with SkinLoads::contact) and the projection
  // out of the proxies when a shape is placed. false: neither (the shape without contact; the basis
  // is the same, so the switch costs no rebuild). The scene's "contact": "on" | "off".
  bool contact = true;
  // κ (1/s²): the penalty stiffness per unit vertex mass, k_i = κ m_i (contact_penalty.h). The
  // penalty's reduced stiffness is at most about κ, so the explicit penalty in the step is stable for
  // κ below the limit docs/mouth_contact.md ("Penalty forces") measures.
  double contactStiffness = 1.0e9;
  // β (s): each violated constraint also has a normal dashpot c_t = β k_t in the step, taken with
  // the step's own motion (Δ/h), so the step's force is f_c − (1 + β/h) K_c Δ. Without it the
  // linearly implicit penalty sends a vertex that met a constraint back out as fast as it came in
  // (a bounce with restitution 1), and the bounces of the lips on the teeth rang through the reduced
  // modes: the built-in head's smile (demo.json) stepped to 0.29–0.41 cm mean displacement where its
  // settle has 0.239. β = 1/240 s (66 times the critical c = 2√(k m)): soft tissue meeting teeth does
  // not bounce. A face at rest in contact (Δ = 0) settles where the static solve does, whatever β
  // (docs/mouth_contact.md, "Penalty forces").
  double contactDamping = 1.0 / 240.0;
  void validate() const;            // InputError naming the field
};

// The skin material AnatomicalSettings describes, for a mesh of mean edge length ℓ̄ (cm).
ShellMaterial anatomicalSkinMaterial(const AnatomicalSettings& s, double meanEdgeLength);

// Gravity in the head's space (cm/s²) for a head pose [pitch, yaw, roll] in degrees about the face
// frame's x, y, z (applied in that order): g = −|g|·R(pose)ᵀ ŷ_world with the world's up = the head's
// +y at rest. Face-down is +90° pitch (gravity along the face frame's +z, out of the face).
Vec3 gravityForPose(const FaceFrame& frame, const Vec3& pitchYawRollDeg, double gravity);

// Loads of the one skin system: activations (one per muscle, [0, 1]) and gravity (head space).
struct SkinLoads {
  VecX activations;                 // m
  Vec3 gravity = Vec3::Zero();      // g(t), cm/s² (head space); the rest value is g_rest
  std::vector<Vec3> drags;          // one force per registered drag (dyn, spread over its vertices)
  // The jaw the shape will be placed with: the contact penalty places its candidates with it.
  JawPose jaw;
  // Whether the contact penalty acts (when the skin has one: a head with eyeballs or teeth and
  // AnatomicalSettings::contact). false keeps the settle and the step exactly linear in the loads
  // (the fit's activation columns).
  bool contact = false;
};

// A drag known when the skin is built: a force spread over the vertices within `radius` (cm) of
// `vertex` (as addDrag).
struct DragSite {
  int vertex = -1;
  double radius = 0.0;
};

struct SettledSkin {
  MatX3 u;              // n×3 displacement, cm
  VecX q;               // d modal amplitudes
  int iterations = 0;   // Newton iterations (0 for linear)
  double residual = 0;  // |r(q)| / |force scale|
  bool converged = true;
  int contactIterations = 0;  // the penalty's Newton iterations (0: no contact, or none touched)
  double contactDepth = 0.0;  // cm: the deepest violation the penalty left (before any projection)
};

class AnatomicalSkin {
 public:
  // Throws InputError (bad settings, muscles, landmarks), NumericalError (solves).
  AnatomicalSkin(const Head& head, const std::vector<MuscleDef>& muscles, const AnatomicalSettings& settings = {});
  // As above, with `drags` registered at build time (as addDrag, in order) and the basis taken
  // from `cache` when it holds this skin's key, else computed and stored there (cache may be null).
  AnatomicalSkin(const Head& head, const std::vector<MuscleDef>& muscles, const AnatomicalSettings& settings,
                 const std::vector<DragSite>& drags, BasisCache* cache);

  const Head& head() const { return head_; }
  const AnatomicalSettings& settings() const { return settings_; }
  const DiscreteShell& shell() const { return *shell_; }
  const TissueMap& tissue() const { return tissue_; }
  const std::vector<CoupledMuscle>& muscles() const { return muscles_; }
  std::vector<std::string> muscleNames() const;  // in the muscles' order
  int muscleIndex(const std::string& name) const;  // InputError naming the unknown muscle
  // K_att + Σ K_c (3n×3n, dyn/cm): the quadratic terms the full-space reference adds to the shell.
  const SparseMat& extraStiffness() const { return Kextra_; }
  const SparseMat& stiffness() const { return Khat_; }  // K̂
  const VecX& vertexMass() const { return mass_; }                     // n, g
  // The basis the skin is stepped and settled in: the Ritz basis of K̂, turned so that it is
  // diagonal for the stiffness with the relaxed muscles released (K̂ − Σ_m ρ_m C̃_m C̃_mᵀ), or K̂'s own
  // with relaxedMuscleModulus = 0. Released across, it is cut back to the d lowest modes of the
  // released stiffness and the static responses of the load patterns (exact for every load).
  std::shared_ptr<const ModalBasis> basis() const { return basis_; }
  const Vec3& restGravity() const { return gRest_; }
  // The skin load of muscle m at a = 1 (dyn): α_m c_m, c_m = K_c,m U_m its couplings' pull, α_m the
  // strength that makes it shorten by σ_m against the skin with the other muscles relaxed (1 when
  // muscles are held).
  const MatX3& muscleLoad(int m) const { return muscleLoads_[static_cast<size_t>(m)]; }
  // γ_m = 1/(κ_m + s_m), s_m = U_mᵀ K_c,m U_m: how far muscle m lets go of the skin along its shape
  // (0 when held).
  double muscleRelease(int m) const { return release_.size() ? release_(m) : 0.0; }
  // How a shape of this skin is placed (jaw, lids, contact projection; AnatomicalSettings::contact).
  const SkinPlacement& placement() const { return *placement_; }
  std::shared_ptr<const SkinPlacement> placementPtr() const { return placement_; }
  // The contact penalty in the step and the settle; null on a head with nothing to touch, with
  // contact off or with no basis.
  const ContactPenalty* contactPenalty() const { return penalty_.get(); }
  // The contact's load patterns whose static responses are in the basis (contactLoadPatterns).
  int contactPatternCount() const { return static_cast<int>(contactLoads_.size()); }
  // True when the basis came from the BasisCache given to the constructor.
  bool basisFromCache() const { return fromCache_; }
  // The cache key of this skin's basis as built (before any later addDrag): a hash of K̂ (its
  // sparsity and values: mesh, skin material, attachment map with its overrides, muscle
  // couplings), the masses, rest positions and triangles, the Ritz settings (d, eigen-solver,
  // deflation), every load pattern in the order it enters (muscle coupling loads: muscle defs,
  // coupling settings, shortening; gravity along x, y, z; the build-time drags' vertex sets; the
  // contact's load patterns, when the head has any), the
  // build sequence's version and kModalBasisFormatVersion. The magnitude of gravity is not in it:
  // the gravity patterns are M·ê_a whatever |g| is.
  const BasisKey& basisKey() const { return key_; }
  // The cache key of the released basis the skin steps in (a hash of basisKey() and the release's
  // settings: E_p, releaseAcross), stored beside the held one; a warm start reads only this one.
  // Zero when muscles are held.
  const BasisKey& releasedBasisKey() const { return releasedKey_; }

  // Registers a drag: a force spread equally over the vertices within radius (cm) of `vertex`; adds
  // its unit patterns' static responses (x, y, z) to the basis from the kept factorisation and
  // re-diagonalises. Returns the drag index; `seconds` receives the wall time (the grab latency).
  int addDrag(int vertex, double radius, double* seconds = nullptr);
  int dragCount() const { return static_cast<int>(drags_.size()); }

  // The world load (n×3, dyn) the loads put on the skin: Σ a_m F_m + M(g − g_rest) + drags.
  // activations must lie in [0, 1] (InputError naming the anatomical model otherwise).
  MatX3 worldLoad(const SkinLoads& loads) const;
  // The reduced static equilibrium: linear (q = Λ⁻¹(ΦᵀF + c)) or warped (Newton on q,
  // Λq = Φᵀ R(Ψq)ᵀ F + c, from the linear solution), c the rest-gravity term of reading (a).
  SettledSkin settle(const SkinLoads& loads, bool warped) const;
  // The full-space linear response (n×3, cm) of the world load (reading (b)): K⁻¹F with K = K̂ and
  // the relaxed muscles released (Woodbury: K̂⁻¹F + K̂⁻¹C (Ρ⁻¹ − CᵀK̂⁻¹C)⁻¹ CᵀK̂⁻¹F, C = [C̃_m]).
  MatX3 linearFullResponse(const SkinLoads& loads) const;
  // The same for a world load given as n×3 forces (dyn), e.g. a contact pattern.
  MatX3 linearFullResponse(const MatX3& load) const;
  // The release's stiffness, Σ_m ρ_m C̃_m C̃_mᵀ (3n×3n, sparse over the muscles' skin vertices,
  // dyn/cm): the skin's stiffness with the relaxed muscles released is K̂ − this (zero when held).
  SparseMat releaseStiffness() const;

 private:
  friend class AnatomicalStepper;
  void validateLoads(const SkinLoads& loads) const;
  std::vector<int> dragVertices(int vertex, double radius) const;
  RitzBasisBuilder& builder() const;  // made on first use after a cache hit
  // basis_ from heldBasis_: the relaxed muscles released and the muscle loads rescaled (α_m).
  void releaseRelaxedMuscles();
  // C̃ (3n × R) and ρ (R): the columns the relaxed muscles let go of, muscle by muscle (its shape
  // c_m/√s_m first, then the across columns); empty when muscles are held.
  void buildReleaseColumns();
  // The muscle loads α_m c_m from basis_ (AnatomicalSettings::strength).
  void setMuscleStrengths();
  void makeContactPenalty();  // penalty_ for basis_
  bool fitsSkin(const ModalBasis& b) const;  // a cached basis's sizes and masses fit this skin
  ModalBasis buildHeldBasis() const;          // from scratch (sets builder_)
  void ensureHeldBasis() const;               // read through heldReader_, else rebuilt
  // Φᵀ[F_1 … F_M, M·ê_x, M·ê_y, M·ê_z, drag 1's ê_x, ê_y, ê_z spread, …] (d × (M + 3 + 3·drags)):
  // every load pattern reduced once, so that a linear step's modal force is this times the loads'
  // coordinates (levels, g − g_rest, drag forces).
  MatX modalLoadPatterns(const ModalBasis& basis) const;
  SparseMat loadPatternColumns() const;  // [c_m, M·ê_x,y,z, drags' ê_x,y,z] (3n × (M + 3 + 3·drags))
  // loadPatternColumns and the contact patterns: what the released basis's cut-back keeps exact.
  SparseMat cutBackPatternColumns() const;
  MatX3 gravityPattern(int axis) const;                 // M·ê_axis
  MatX3 dragPattern(const std::vector<int>& vertices, int axis) const;  // ê_axis spread evenly
  Head head_;
  AnatomicalSettings settings_;
  std::unique_ptr<DiscreteShell> shell_;
  TissueMap tissue_;
  std::vector<CoupledMuscle> muscles_;
  std::vector<MatX3> muscleLoads_;     // α_m c_m
  std::vector<MatX3> couplingLoads_;   // c_m = K_c,m U_m
  VecX release_;                       // γ_m (empty when muscles are held)
  VecX shapeEnergy_;                   // s_m = Σ k_i |w_i|², the couplings' stiffness along the shape
  SparseMat couplingColumns_;          // [c_m], 3n × M
  VecX strength_;                      // α_m: muscleLoads_[m] = α_m c_m
  SparseMat releaseColumns_;           // C̃ = [C̃_m], 3n × R: the M shapes' columns first, then the across ones
  VecX releaseRho_;                    // ρ per column: s_m/(s_m + κ_m)
  // Columns beyond the muscles' first shapes (0: nothing to cut back): a split ring's other half's
  // shape, then every across column. Their static responses join the held basis as loads.
  int extraReleaseColumns_ = 0;
  mutable std::vector<MatX3> heldCouplingResponses_;  // K̂⁻¹C̃_j, for linearFullResponse
  // The release's part that no grip changes (a grab's Woodbury, anatomical_grab.cpp), made once
  // under the builder's lock from the held basis Φ_h, Λ_h: C̃ᵀΦ_h, C̃ᵀΦ_hΛ_h⁻¹, S = Ρ^½ and the
  // LDLᵀ of I − S C̃ᵀK̂⁻¹C̃ S. Dropped by addDrag (the held basis grows).
  struct ReleaseSolve {
    MatX CtPhi, PL;
    VecX S;
    Eigen::LDLT<MatX> D;
  };
  const ReleaseSolve& releaseSolve() const;
  mutable std::unique_ptr<ReleaseSolve> releaseSolve_;
  struct Drag {
    std::vector<int> vertices;
  };
  std::vector<Drag> drags_;
  SparseMat Kextra_;
  SparseMat Khat_;
  VecX mass_;
  Vec3 gRest_ = Vec3::Zero();
  RitzSettings ritz_;
  mutable std::mutex builderMutex_;
  mutable std::unique_ptr<RitzBasisBuilder> builder_;
  // Diagonal for K̂: the builder's start; null after a warm start until something needs it.
  mutable std::shared_ptr<const ModalBasis> heldBasis_;
  BasisCache::Reader heldReader_;      // where a warm start can read it later
  std::shared_ptr<const ModalBasis> basis_;
  BasisKey key_;
  BasisKey releasedKey_;               // the released basis's (when muscles are released)
  bool fromCache_ = false;
  std::shared_ptr<const SkinPlacement> placement_;
  std::vector<MatX3> contactLoads_;    // contactLoadPatterns (empty: nothing to touch)
  std::shared_ptr<const ContactPenalty> penalty_;
};

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
  const VecX& muscleLevels() const { return level_; }
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
