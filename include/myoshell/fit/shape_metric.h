// The shape metric (docs/shape_metric.md): how well a displacement field u (a result) matches a
// target field e (an artist's shape, a reference solution). One definition, used by tests, docs
// and the fitting.
#pragma once

#include "myoshell/core/types.h"

namespace myo {

struct ShapeMetricSettings {
  double threshold = 0.05;  // cm: a vertex is compared when |e_i| > threshold OR |u_i| > threshold
  int topCount = 20;        // vertices whose rest positions give the centroid of the largest motion
};

struct ShapeComparison {
  int comparedVertices = 0;     // vertices in the compared set S
  // Σ_S u_i·e_i / (‖u‖_S ‖e‖_S); 0 when either field is zero over S (or S is empty).
  double cosine = 0.0;
  // ‖u‖_S / ‖e‖_S (Frobenius over S); +∞ when e is zero over S and u is not, 0 when S is empty.
  double magnitudeRatio = 0.0;
  double resultNorm = 0.0;      // ‖u‖_S, cm
  double targetNorm = 0.0;      // ‖e‖_S, cm
  // Mean rest position (cm) of the topCount vertices with the largest |u_i| (|e_i|), and the
  // distance between the two centroids (cm).
  Vec3 resultCentroid = Vec3::Zero();
  Vec3 targetCentroid = Vec3::Zero();
  double centroidDistance = 0.0;
  // The vertex that moves most in each field, and how far (cm).
  int resultPeakVertex = -1;
  int targetPeakVertex = -1;
  double resultPeak = 0.0;
  double targetPeak = 0.0;
  double peakDistance = 0.0;    // |rest[resultPeak] − rest[targetPeak]|, cm
};

// Compares u (result) with e (target): both n×3 displacements (cm) of the same n vertices whose
// rest positions are `rest` (n×3, cm). Throws InputError when the shapes differ or n = 0.
ShapeComparison compareShapes(const MatX3& result, const MatX3& target, const MatX3& rest,
                              const ShapeMetricSettings& settings = {});

// The centroid (cm) of the rest positions of the `count` vertices that move most in u (n×3, cm);
// ties broken by the lower index. count is clamped to [1, n].
Vec3 largestMotionCentroid(const MatX3& u, const MatX3& rest, int count);

}  // namespace myo
