// Muscles that pull where they insert (docs/anatomical_model.md; METHOD.md §9 "coupling at a
// surface point"). The skin over a muscle is tied to it by the tissue between them: every skin
// vertex i over the muscle gets a zero-length linear spring to the muscle's surface point below it
// (its closest point on the muscle, barycentric over the muscle's nodes b with weights β_b):
//   E_c = ½ k_i ‖Σ_b β_b u_b − u_i‖²
// The muscle is fed forward (u_b known), so on the skin side K_c = diag(k_i) ⊗ I₃ joins the
// skin's stiffness and the load is f_i = k_i Σ_b β_b u_b. The muscle moves in one shape, its static
// response to the activation load, u_b = a·U_b (a ∈ [0, 1]): the skin load is linear in a. Tied
// this way, the coupling does not depend on how finely the muscle is meshed, and no two springs
// pull one skin vertex towards different places (docs/anatomical_model.md, "Couplings").
//
// Stiffness: a shear layer, k_i = G(t)·A_i/δ_i (dyn/cm) with A_i the vertex's lumped area (cm²),
// δ_i its distance to the muscle (cm) and G(t) (dyn/cm²) a profile along the muscle, t = 0 at the
// origin, 1 at the insertion: none at the origin, weak along the belly (loose areolar tissue),
// strong at the insertion (fibres into the dermis); faded to 0 as δ_i reaches `footprintReach` ×
// the muscle's depth there (the footprint's edge). A head twice as large keeps G and the strain,
// so its muscles move twice as far.
//
// Strength: one head-independent rule: at a = 1 the muscle shortens by `shortening` × its rest
// length (the insertion ring's mean motion along the muscle: along its chord, or with slideOverBed
// along the fibres' direction at the insertion), whatever the muscle and head.
#pragma once

#include <string>
#include <vector>

#include "myoshell/core/types.h"
#include "myoshell/head/head.h"
#include "myoshell/muscles/coupling_profile.h"
#include "myoshell/muscles/muscle.h"
#include "myoshell/shell/shell_material.h"

namespace myo {

struct MuscleCouplingSettings {
  CouplingProfile profile;  // for every muscle whose definition has no profile of its own (MuscleDef::coupling)
  // Shortening at a = 1 (a maximal contraction) as a fraction of the rest length. Measured maximal
  // smiles move the mouth corner 13.7 mm (Bae et al. 2003, J Korean Soc Plast Reconstr Surg 30:393,
  // 50 subjects) and 9.28 mm (Vicon, 12 subjects, Braz J Otorhinolaryngol), 12.8 mm weighted by
  // their subjects; the zygomaticus major, 6.38 cm on ICT's generic neutral head, carries the corner
  // with its insertion, so a maximal smile is 12.8 / 63.8 = 0.20 of its length. A posed joyful
  // expression held in an MRI scanner shortens it by 14.4 % (Rams et al. 2024, Aesthetic Plast
  // Surg 48:2722), the value before 2026-11-27 (docs/anatomical_model.md, "The shortening at a = 1").
  double shortening = 0.20;
  // The footprint: skin vertices within footprintReach × the muscle's depth (at the point below
  // them) of the muscle's surface, the muscle beneath them. 2: the fibres fan out to about 1.7
  // depths beyond the muscle's edge (docs/anatomical_model.md, "Couplings").
  double footprintReach = 2.0;
  // Linear muscles slide over their bed: at a = 1 every node of the muscle keeps its rest depth
  // under the skin, so a curved muscle follows the face instead of straightening through the fat,
  // teeth and bone under it (docs/anatomical_model.md, "Muscles slide over their bed"). false: the
  // pinned tube's own static response, as before 2026-11-26. Rings keep their shape (docs/muscles.md).
  bool slideOverBed = true;
  ShellMaterial muscle = [] {  // as the thesis face's muscles (docs/face_model.md)
    ShellMaterial m;
    m.kA = 1.0e3;
    m.kL = 1.0e2;
    m.kB = 1.0e5;
    m.density = 1.06;
    m.thickness = 0.2;
    return m;
  }();
};

// One muscle, fed forward: its shape at a = 1 and its springs to the skin.
struct CoupledMuscle {
  Muscle muscle;
  MatX3 fullShape;       // U_m: the muscle's displacement at a = 1 (nodes×3, cm), origin rows 0
  // The direction a relaxed muscle follows the skin along (nodes×3, cm; empty: fullShape). The
  // release is a small motion about the rest, so it takes the shape's tangent there: for a ring in a
  // lip's body the lip's growth in height linearised, ½σ h instead of (1/√(1 − σ) − 1) h
  // (docs/muscles.md, "The relaxed lip's release").
  MatX3 releaseShape;
  double naturalFrequency = 0.0;  // ω = √(φᵀKφ/φᵀMφ) of that shape (rad/s), for its dynamics
  struct Spring {
    int skin = -1;                 // the skin vertex
    std::vector<int> nodes;        // the muscle's nodes around the point below it
    std::vector<double> weights;   // their barycentric weights β_b (Σ = 1)
    double t = 0.0;              // position along the muscle (0 origin, 1 insertion; 1 + s over a continuation, MuscleDef::continuesInto)
    double depth = 0.0;          // δ: distance to the muscle at rest, cm
    double stiffness = 0.0;      // k_i, dyn/cm (> 0)
    // A push (MuscleDef::pushes) ties the skin along this unit direction only, the lip sliding
    // freely across the pad: K_i = k_i â âᵀ. Zero: a shear layer, K_i = k_i I.
    Vec3 along = Vec3::Zero();
    // Σ_b β_b U_b (cm) for a muscle displacement U (nodes×3).
    Vec3 muscleDisplacement(const MatX3& muscleU) const;
    // K_i v (dyn for v in cm), scaled by `share`.
    Vec3 tie(const Vec3& v, double share = 1.0) const {
      return along.isZero() ? (share * stiffness) * v : (share * stiffness * along.dot(v)) * along;
    }
  };
  std::vector<Spring> springs;   // nodes with k_c > 0 only
};

// Builds the muscle (buildMuscle), its static shape at a = 1 scaled to the shortening rule, and its
// skin springs, with the muscle's own profile (def.coupling) or else settings.profile. Throws InputError naming the muscle for bad settings, NumericalError if the pinned
// muscle is singular.
// `skin`, when given, is a SurfaceLocator over head.mesh that answers the skin's closest-point
// queries (the same muscle, built faster: AnatomicalSkin shares one over all its muscles).
CoupledMuscle coupleMuscle(const MuscleDef& def, const Head& head, const MuscleCouplingSettings& settings = {},
                           const SurfaceLocator* skin = nullptr);

// Σ over springs of K_c = k_i I₃ at the spring's skin vertex, into a 3n×3n triplet list (dyn/cm).
void addCouplingStiffness(const CoupledMuscle& m, std::vector<Triplet>& triplets);
// The skin load at a = 1 (n×3, dyn): f_i = Σ_springs at i k_i Σ_b β_b U_b.
MatX3 couplingLoad(const CoupledMuscle& m, int skinVertexCount);

}  // namespace myo
