// Every frame of a skin animation as a base mesh plus a few morph targets, one weight per target
// and frame: the animation GLB's layout (io/animation_export.h, docs/exports.md "The animation
// GLB"). The frames' displacements from the rest, D (F × 3n, frame f's row d_f), are reduced by a
// truncated SVD D ≈ W Vᵀ (V: 3n × k orthonormal, W = D V: the least-squares weights). The SVD comes
// from the eigendecomposition of the small matrix H = B Bᵀ with B = Qᵀ D: Q = I (H the F × F Gram
// matrix D Dᵀ) for up to kExactRangeFrames frames; for longer takes Q is a randomized range finder's
// orthonormal basis of D's column space (Halko, Martinsson & Tropp 2011, Algorithm 4.4: a Gaussian
// sketch and two power iterations), r = maxTargets + 16 columns, so the cost stays O(F · 3n · r).
// D is never formed: it is read in blocks of vertices (columns) or frames (rows) from the frames.
//
// With Q = I the weights come straight from the eigenvectors (W = D V = U Σ) and only the columns
// of V the search may use are formed. k is the smallest target count whose largest vertex error
// over ALL frames — the distance between what a player computes (base + Σ s_fk T_k) and the frame —
// is at most the tolerance; it is found by bisection on k between two bounds from each frame's
// residual norm (no vertex is off by more than it, the worst by at least its RMS), every tested k
// measured over every frame (the error falls with k). The
// weights are then mapped affinely into [0, 1] (s = (w − lo) / (hi − lo), lo and hi the weight's
// extremes over the frames), so no player clamps them (Blender's shape-key sliders and Unity's blend
// shapes clamp to their ranges): T_k = (hi_k − lo_k) V_k and base = rest + Σ lo_k V_k. The error
// reported is measured on the values as the GLB stores them (float32, scaled by `toFile`).
#pragma once

#include <vector>

#include "myoshell/core/types.h"

namespace myo {

// Frames up to this count use the exact Gram matrix; more use the randomized range finder.
inline constexpr int kExactRangeFrames = 1024;

struct MorphAnimation {
  MatX3 base;                  // n×3, in the frames' unit × toFile
  std::vector<MatX3> targets;  // k n×3 targets, in the frames' unit × toFile
  MatX weights;                // F×k, each in [0, 1]
  double maxError = 0.0;       // largest vertex distance over all frames, in the frames' unit (not × toFile)
  bool withinTolerance = true;  // false when maxTargets targets could not reach the tolerance
};

// The morph targets of `frames` (each n×3, same vertex order as `rest`) to `tolerance` (the frames'
// unit; > 0) with at most `maxTargets` (≥ 1) targets; `toFile` scales base and targets (e.g. 0.01:
// cm → m). At least one target, even when nothing moves. CheckError on empty or mismatched frames.
MorphAnimation compressToMorphTargets(const MatX3& rest, const std::vector<MatX3>& frames, double tolerance,
                                      int maxTargets, double toFile = 1.0);

}  // namespace myo
