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
//
// Its settings are skin_settings.h; its time stepping AnatomicalStepper (anatomical_stepper.h); the
// relaxed muscles' release is muscle_release.cpp.
#pragma once

#include <Eigen/Cholesky>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "myoshell/anatomy/contact_penalty.h"
#include "myoshell/anatomy/skin_placement.h"
#include "myoshell/anatomy/skin_settings.h"
#include "myoshell/core/types.h"
#include "myoshell/head/head.h"
#include "myoshell/head/jaw.h"
#include "myoshell/muscles/muscle_coupling.h"
#include "myoshell/muscles/tissue_attachment.h"
#include "myoshell/reduce/basis_cache.h"
#include "myoshell/reduce/modal_warping.h"
#include "myoshell/reduce/ritz_basis.h"
#include "myoshell/shell/discrete_shell.h"

namespace myo {

// Loads of the one skin system: activations (one per muscle, [0, 1]) and gravity (head space).
struct SkinLoads {
  VecX activations;                 // m
  Vec3 gravity = Vec3::Zero();      // g(t), cm/s² (head space); the rest value is g_rest
  std::vector<Vec3> drags;          // one force per registered drag (dyn, spread over its vertices)
  // The jaw the shape will be placed with: the contact penalty places its candidates with it.
  JawPose jaw;
  // The eyes' turn the shape will be placed with: the lids the penalty places follow it.
  EyeGaze gaze;
  // Whether the contact penalty acts (when the skin has one: a head with eyeballs or teeth and
  // AnatomicalSettings::contact). false keeps the settle and the step exactly linear in the loads
  // (the fit's activation columns).
  bool contact = false;
  // An extra reduced force Φᵀf (d, the skin's basis; f in dyn) the caller projected itself, added to
  // the modal force as it is: a load no pattern of the skin holds, with no factorisation (the web
  // page's mouse grab: a force at the grabbed vertices; docs/web.md). Empty = none. Linear modes
  // only: the stepper refuses it when warping (its n×3 force would need f itself).
  VecX modalForce;
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
  void buildModiolusPatterns();                       // modiolusLoads_, modiolusFirst_
  void setHeldBandLoad(size_t m, const VecX& Pc);     // a hoop band's α_m (c_m − G r), Pc = Φᵀc_m
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
  // A hoop band's ends held at the modioli (docs/muscles.md, "The band's ends are held at the
  // modioli"): per hoop muscle, six reaction patterns (each end's modiolus patch, ê_x, ê_y, ê_z,
  // spread by weight); their static responses join the basis, and the band's load carries the
  // reaction that keeps each patch's mean motion at zero.
  std::vector<MatX3> modiolusLoads_;
  std::vector<int> modiolusFirst_;     // per muscle: its first pattern in modiolusLoads_, −1 for none
  std::shared_ptr<const ContactPenalty> penalty_;
};

}  // namespace myo
