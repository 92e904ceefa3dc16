// The skin held by the skull (docs/anatomical_model.md; METHOD.md §9): every skin vertex is tied to
// its rest place by a zero-length spring of stiffness k_att(x)·A_i (fascia, retaining ligaments),
// and carries the mass of the soft tissue under it (ρ·h(x)·A_i). Both maps come from regions placed
// in the face frame (face_frame.h), so they do not depend on where the head sits, how it is turned
// or its units: distances below are in face-frame units (fractions of the outer-canthus distance).
//
//   E_att = ½ Σ_i k_att,i A_i ‖u_i‖²,   K_att = diag(k_att,i A_i) ⊗ I₃       (3n×3n, dyn/cm)
//   k_att(x) = (1 − w(x))·G_fat/h(x) + w(x)·k_held                           (dyn/cm³)
// with w ∈ [0, 1] the smooth "held" weight (scalp behind the hairline, ears and the back of the
// head, neck, nasal dorsum, zygomatic arch, the orbital, zygomatic and mandibular retaining
// ligaments) and h(x) the soft-tissue thickness (cm). The mandibular ligament's w is the one whose
// k_att falls geometrically with distance, G_fat/h · (k_held h/G_fat)^b(d) (docs/anatomical_model.md,
// "The chin's notch").
#pragma once

#include <vector>

#include "myoshell/core/types.h"
#include "myoshell/head/head.h"

namespace myo {

struct AttachmentSettings {
  // Shear modulus of the subcutaneous fat layer between skin and skull, dyn/cm² (1 kPa; adipose
  // tissue E ≈ 3 kPa, Samani et al. 2003, G = E/3). k_att = G/h where the skin is not held.
  double fatShearModulus = 1.0e4;
  // k_att where the skin is held (retaining ligaments, scalp, ears, nose, zygomatic arch, neck),
  // dyn/cm³: dense connective tissue (≈ 10 kPa shear) over a 3–4 mm layer.
  double heldStiffness = 3.0e5;
  // Soft-tissue thickness (skin to bone), cm (forensic tissue-depth tables, docs/anatomical_model.md):
  double thinTissue = 0.6;     // forehead, brows, lids, nose, scalp, zygoma, ears, neck
  double cheekTissue = 1.8;    // the cheek over the buccal fat and masseter
  double lipChinTissue = 1.1;  // lips and chin
  double tissueDensity = 1.0;  // ρ of skin and soft tissue, g/cm³
  // The forehead's column keeps its volume (docs/muscles.md, "The forehead's column keeps its
  // volume"): skin, dense layer and galea/frontalis slide as one over the loose areolar layer on the
  // frontal bone, so the skin moves along its normal only as the column thickens,
  // u·n = −h div_s(u). Penalty stiffness of that constraint, dyn/cm³ (0: off).
  double foreheadColumnStiffness = 3.0e6;
};

// Per-vertex maps over the n skin vertices.
struct TissueMap {
  VecX attachment;  // k_att,i, dyn/cm³
  VecX thickness;   // h_i, cm (soft tissue carried by the vertex)
  VecX held;        // w_i ∈ [0, 1], 1 = held by ligament/fascia/bone-backed region
  VecX area;        // A_i, lumped vertex area (a third of each incident triangle), cm²
  VecX forehead;    // f_i ∈ [0, 1], 1 = over the frontal bone, from the brows up (the column's region)
  double density = 1.0;  // g/cm³

  int size() const { return static_cast<int>(attachment.size()); }
  // Vertex masses ρ·h_i·A_i (n, g): what the skin carries under gravity and in its dynamics.
  VecX vertexMass() const;
  // K_att = diag(k_att,i A_i) ⊗ I₃, 3n×3n (dyn/cm).
  SparseMat stiffness() const;
};

// A column of tissue that keeps its volume (docs/muscles.md, "The forehead's column keeps its
// volume"): where the skin, its dense layer and a muscle bound to them slide as one over a loose
// layer on bone, the skin moves along its rest normal n_i only as the column, h_i thick, thickens
// under the surface's compression (incompressible, its deep face on the loose layer):
//   c_i(u) = n_iᵀu_i + h_i div_s(u)_i = 0,   div_s(u)_i = Σ_{t∋i} (A_t/3A_i) Σ_{j∈t} ∇φ_j,tᵀ u_j,
// ∇φ_j,t the gradient of vertex j's hat function on triangle t (in its plane), A_i the lumped
// area. Held by the penalty E = ½ Σ_i κ_i c_i², K = Cᵀ diag(κ) C (3n×3n, dyn/cm), κ_i in dyn/cm
// (0: no row). Exact: a uniform in-plane compression ε with u·n = h ε costs nothing.
SparseMat columnVolumeStiffness(const MatX3& V, const MatX3i& F, const VecX& depth, const VecX& area, const VecX& kappa);
// The forehead's column: κ_i = k f_i A_i over the frontal bone (TissueMap::forehead), h_i the
// soft-tissue thickness; empty for k = 0.
SparseMat foreheadColumnStiffness(const Head& head, const TissueMap& map, double stiffness);

// The region maps of a head (its landmarks give the face frame and the regions' places).
TissueMap tissueMap(const Head& head, const AttachmentSettings& settings = {});

// A per-vertex override of k_att (the scene key `skin.attachment` reads into this).
struct AttachmentOverride {
  int vertex = -1;
  double stiffness = 0.0;  // dyn/cm³, > 0
};
// Throws InputError naming the entry for a vertex outside [0, n) or a stiffness ≤ 0 / not finite.
void applyAttachmentOverrides(TissueMap& map, const std::vector<AttachmentOverride>& overrides);

// Lumped vertex areas (n, cm²): a third of each incident triangle's area.
VecX lumpedVertexAreas(const MatX3& V, const MatX3i& F);

}  // namespace myo
