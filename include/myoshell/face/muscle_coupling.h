// Muscles that pull where they insert (docs/anatomical_model.md; METHOD.md §9 "coupling at a
// surface point"). Each muscle node m is tied by a zero-length linear spring to a patch of skin
// around its closest skin point s: the patch's weighted mean Σ_j w_j u_j, with weights w_j ∝ A_j
// (1 − (d_j/r)²)² (A_j the vertex area, d_j the distance from s along the surface's edges, r the
// patch radius: the muscle's half-width), Σ_j w_j = 1 (the fibres insert over an area, not at a
// point; a single triangle stretched 170 % at the mouth corner):
//   E_c = ½ k_c ‖u_m − Σ_j w_j u_j‖²
// The muscle is fed forward (u_m known), so on the skin side K_c = k_c w wᵀ ⊗ I₃ joins the skin's
// stiffness and the load is f_j = k_c w_j u_m. The muscle moves in one shape, its static response
// to the activation load, u_m = a·U_m (a ∈ [0, 1]): the skin load is linear in a.
//
// Stiffness: k_c = G(t)·A_node/depth (dyn/cm) with A_node the muscle's surface area per node (cm²),
// depth the node's distance to the skin (cm) and G(t) (dyn/cm²) a profile along the muscle,
// t = 0 at the origin, 1 at the insertion: none at the origin, weak along the belly (loose areolar
// tissue), strong at the insertion (fibres into the dermis). A head twice as large keeps G and the
// strain, so its muscles move twice as far.
//
// Strength: one head-independent rule: at a = 1 the muscle shortens by `shortening` × its rest
// length (the insertion ring's mean motion along the muscle), whatever the muscle and head.
#pragma once

#include <string>
#include <vector>

#include "myoshell/core/types.h"
#include "myoshell/face/coupling_profile.h"
#include "myoshell/face/head.h"
#include "myoshell/face/muscle.h"
#include "myoshell/shell/shell_material.h"

namespace myo {

struct MuscleCouplingSettings {
  CouplingProfile profile;  // for every muscle whose definition has no profile of its own (MuscleDef::coupling)
  // Shortening at a = 1 as a fraction of the rest length: zygomaticus major in a joyful expression
  // shortens to 85.6 % of its rest length (MRI, Rams et al. 2024, Aesthetic Plast Surg 48:2722).
  double shortening = 0.144;
  // Patch radius as a multiple of the muscle's half-width (its surface area / (4 × rest length) for
  // a flat ring), and never below 1.5 mean skin edges. 0: the closest point alone (barycentric).
  // 2: the fibres spread over the muscle's width (docs/anatomical_model.md, "Couplings").
  double patchRadius = 2.0;
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
  double naturalFrequency = 0.0;  // ω = √(φᵀKφ/φᵀMφ) of that shape (rad/s), for its dynamics
  struct Spring {
    int node = -1;               // muscle node
    std::vector<int> skin;         // the patch's skin vertices
    std::vector<double> weights;   // w_j ≥ 0, Σ w_j = 1
    double t = 0.0;              // position along the muscle (0 origin, 1 insertion)
    double depth = 0.0;          // distance to the skin at rest, cm
    double stiffness = 0.0;      // k_c, dyn/cm (> 0)
  };
  std::vector<Spring> springs;   // nodes with k_c > 0 only
};

// Builds the muscle (buildMuscle), its static shape at a = 1 scaled to the shortening rule, and its
// skin springs, with the muscle's own profile (def.coupling) or else settings.profile. Throws InputError naming the muscle for bad settings, NumericalError if the pinned
// muscle is singular.
CoupledMuscle coupleMuscle(const MuscleDef& def, const Head& head, const MuscleCouplingSettings& settings = {});

// Σ over springs of K_c = k_c w wᵀ ⊗ I₃ into a 3n×3n triplet list (dyn/cm).
void addCouplingStiffness(const CoupledMuscle& m, std::vector<Triplet>& triplets);
// The skin load at a = 1 (n×3, dyn): f_j = Σ_springs k_c w_j U_m(node).
MatX3 couplingLoad(const CoupledMuscle& m, int skinVertexCount);

}  // namespace myo
