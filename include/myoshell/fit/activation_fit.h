// Fitting activations to a shape (docs/fitting.md): which activations a ∈ [0, 1]^m of the anatomical
// face (anatomical_skin.h) reproduce a target displacement field, or target positions of a few
// marker vertices, best.
//
// The linear model (warping off, the default) is exactly u(a) = Σ_m a_m u_m (gravity off), u_m the
// settled n×3 displacement (cm) of muscle m at a = 1. The fit minimises
//   ‖A a − e‖²_W + λ ‖e‖²_W Σ_m a_m      subject to 0 ≤ a_m ≤ 1
// (A the 3k×m column matrix over the k weighted vertices, e the aligned target, W selecting the
// vertices: all for a dense target, the markers otherwise): an L1 sparsity term, linear on the box,
// scaled by the target's own squared norm so that λ is dimensionless (a muscle is used only when a
// unit of it removes more than the fraction λ of the target's squared norm). A bounded QP on the
// m×m normal equations, solved by an active-set method in the style of Lawson–Hanson (solveBoxQp).
// An alignment (rigid or similarity, Umeyama 1991) of the target to the rest mesh + the fitted
// displacement is alternated with the fit. With warping on, a few Gauss–Newton steps on the warped
// static solve follow (finite-difference Jacobian); with warping off that refinement is a no-op.
#pragma once

#include <string>
#include <vector>

#include "myoshell/anatomy/anatomical_skin.h"
#include "myoshell/anatomy/skin_placement.h"
#include "myoshell/core/types.h"
#include "myoshell/fit/shape_metric.h"

namespace myo {

enum class FitAlignment { None, Rigid, Similarity };
const char* toString(FitAlignment a);

// The shape to fit, in the head's space (cm). Either dense (displacement n×3, every vertex) or
// markers (vertices k ids, positions k×3: where those vertices should be).
struct FitTarget {
  MatX3 displacement;             // n×3, cm (dense), or empty
  std::vector<int> markerVertices;
  MatX3 markerPositions;          // k×3, cm (markers)
  bool isMarkers() const { return !markerVertices.empty(); }
};

struct FitSettings {
  FitAlignment alignment = FitAlignment::None;
  std::vector<std::string> muscles;  // the muscles to fit (empty: all); the others stay at 0
  double lambda = 0.0;               // dimensionless sparsity weight (above); ≥ 0
  int maxAlignmentRounds = 100;      // alternations of alignment and fit (1 without alignment)
  int refineSteps = 3;               // Gauss–Newton steps on the nonlinear shape (warping on, or a lid fitted)
  double threshold = 0.05;           // cm: the compared vertices (shape_metric.h), 0.5 mm
  void validate() const;             // InputError naming the field
};

// x ↦ s R x + t (head space, cm).
struct SimilarityTransform {
  double scale = 1.0;
  Mat3 rotation = Mat3::Identity();
  Vec3 translation = Vec3::Zero();
  MatX3 apply(const MatX3& points) const;  // k×3 → k×3
};

// The rigid (withScale = false) or similarity transform T minimising Σ_i |T(from_i) − to_i|²
// (Umeyama 1991; a proper rotation, det R = +1). from, to: k×3, k ≥ 3 (InputError otherwise).
SimilarityTransform fitSimilarity(const MatX3& from, const MatX3& to, bool withScale);

struct BoxQpResult {
  VecX x;
  int iterations = 0;   // active-set changes
  bool converged = true;
};
// min ½ xᵀHx − cᵀx subject to lo ≤ x ≤ hi (H m×m symmetric positive semidefinite; lo ≤ hi):
// active set in the style of Lawson–Hanson (1974): free the bound variable whose multiplier is
// most wrong, solve the free variables' equations, step back to the first bound crossed.
BoxQpResult solveBoxQp(const MatX& H, const VecX& c, const VecX& lo, const VecX& hi);

struct ActivationFit {
  VecX activations;              // one per muscle of the skin (unfitted muscles 0)
  std::vector<int> fitted;       // indices of the fitted muscles
  MatX3 displacement;            // n×3, cm: the model's settled shape at the activations
  MatX3 target;                  // the aligned target displacement (n×3 dense; k×3 markers), cm
  SimilarityTransform alignment; // applied to the target
  // The compared vertices: shape_metric.h's set (target or result moves > threshold) for a dense
  // target, the markers for markers.
  ShapeComparison metric;
  double rmsMm = 0.0;            // RMS |u_i − e_i| over the compared vertices, mm
  double maxMm = 0.0;            // max |u_i − e_i| over them, mm
  int iterations = 0;            // alignment rounds + Gauss–Newton steps
  int solverIterations = 0;      // active-set iterations, summed
  double seconds = 0.0;          // wall time, columns included
  double conditionNumber = 0.0;  // σ_max/σ_min of the column matrix over the compared vertices
  bool refined = false;          // Gauss–Newton on the nonlinear shape ran
};

// Throws InputError (unknown muscle, shapes, marker vertex out of range, non-finite target),
// NumericalError (the warped solve fails).
// Shapes are placed by `placement` (anatomy/skin_placement.h: the lids and the contact, the jaw at
// rest), built from the skin's head and muscles when null; pass one to fit many shapes.
// `everyColumn`, when given, holds activationColumns for every muscle of the skin in order (made
// once for many fits: a column is a static solve); null computes the fitted muscles' columns.
ActivationFit fitActivations(const AnatomicalSkin& skin, const FitTarget& target, const FitSettings& settings = {},
                             const SkinPlacement* placement = nullptr, const std::vector<MatX3>* everyColumn = nullptr);

// A shape and its mirror image fitted together (fit-rig's left/right pairs, docs/fitting.md "Mirror
// pairs"): one activation vector a for `shape`, and `mirrorShape`'s equations use each muscle's twin
// (mirror[k]: the skin's index of muscle k's twin, k itself on the midline; mirroredMuscles()):
//   ‖A a − e‖² + ‖A_twin a − e_mirror‖² + λ (‖e‖² + ‖e_mirror‖²) Σ_m a_m,   0 ≤ a_m ≤ 1,
// A_twin's column for muscle m being the column of its twin. No vertex is mirrored: each side is
// compared on the head as it is. `mirrorFit`'s activations are `fit`'s by twin (exactly), each side's
// displacement, target, alignment and figures its own. Throws as fitActivations, and InputError when a
// fitted muscle's twin is missing from the library or not fitted.
struct MirroredFit {
  ActivationFit fit;        // `shape`'s
  ActivationFit mirrorFit;  // `mirrorShape`'s
};
MirroredFit fitMirroredActivations(const AnatomicalSkin& skin, const FitTarget& shape, const FitTarget& mirrorShape,
                                   const std::vector<int>& mirror, const FitSettings& settings = {},
                                   const SkinPlacement* placement = nullptr,
                                   const std::vector<MatX3>* everyColumn = nullptr);

// Each muscle's mirror twin (muscles/muscle_def.h, mirroredMuscleName) as an index into the skin's
// muscles, −1 where the library has no such muscle.
std::vector<int> mirroredMuscles(const AnatomicalSkin& skin);

// The linear columns: u_m (n×3, cm) of each listed muscle at a = 1, gravity off (rest gravity).
std::vector<MatX3> activationColumns(const AnatomicalSkin& skin, const std::vector<int>& muscles);

}  // namespace myo
