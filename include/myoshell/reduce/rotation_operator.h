// The linearized rotation of a shell displacement field, and the rotation formulas of modal
// warping (METHOD.md §3.2–3.4).
//
// Per triangle t (rest X_0, X_1, X_2, unit normal n, area Ā), for k = 0, 1, 2:
//   ∇N_k = n × (X_{k+2} − X_{k+1}) / (2Ā)                 in-plane gradient of the hat function
//   B_k  = ½ n nᵀ [∇N_k]×  −  (n × ∇N_k) nᵀ                3×3
//   w_t  = Σ_k B_k u_k
// The first term is the drilling rotation about n (half the in-plane curl), the second the tilt
// n × δn with δn = −Σ_k ∇N_k (n·u_k) the linearized change of the unit normal; w_t is the exact
// linearization of log(polar(F_t)) of the triangle's 3-D deformation gradient. Per node, the
// uniform average over incident triangles: w_i = (1/|T(i)|) Σ_{t∋i} w_t. Pinned neighbours enter
// with u = 0. An infinitesimal rigid rotation u = ω × X gives w = ω at every node.
#pragma once

#include <array>
#include <cmath>
#include <vector>

#include "myoshell/core/types.h"

namespace myo {

// The 3×3 blocks B_0, B_1, B_2 of one triangle (rad/cm), so that w_t = Σ_k B_k u_k.
std::array<Mat3, 3> triangleRotationBlocks(const Vec3& X0, const Vec3& X1, const Vec3& X2);

// The rotation operator W (3n×3n sparse, rad/cm): w = W u gives per-vertex rotation vectors (rows
// vertex-major) of the full-mesh displacement u (3n, cm). rest: n×3 rest positions; F: m×3.
SparseMat rotationOperator(const MatX3& rest, const MatX3i& F);

// Per-vertex rotation vectors (n×3, rad) of a displacement field u (n×3, cm): W·u.
MatX3 nodalRotations(const MatX3& rest, const MatX3i& F, const MatX3& u);

// Ψ = WΦ restricted to the free vertices: Phi is 3f×d over freeVertices (sorted, into the n-vertex
// mesh); the result is 3f×d (rad per unit q). Pinned vertices contribute u = 0; their own rows are
// not computed (they never move).
MatX modalRotationMatrix(const MatX3& rest, const MatX3i& F, const std::vector<int>& freeVertices,
                         const MatX& Phi);

// R = exp([w]×) (Rodrigues), with a series below θ = |w| < 1e-4.
Mat3 rotationFromVector(const Vec3& w);
// The principal rotation vector of a rotation matrix (log map), |result| ≤ π.
Vec3 rotationVector(const Mat3& R);
// The warp matrix R̃(w) = ∫₀¹ exp(s[w]×) ds = I + ((1−cosθ)/θ²)[w]× + ((θ−sinθ)/θ³)[w]×²
// (METHOD.md §3.4); not a rotation. Series for small θ.
Mat3 warpMatrix(const Vec3& w);

// The coefficients a(θ²) = (1−cosθ)/θ², b(θ²) = (θ−sinθ)/θ³ and s(θ²) = sinθ/θ, evaluated from
// θ² without cancellation (Taylor series for θ² < 1, closed form above).
struct RotationCoefficients {
  double s, a, b;
};
inline RotationCoefficients rotationCoefficients(double theta2) {
  if (theta2 < 0.25) {
    // Σ (−x)^k/(2k+1)!, Σ (−x)^k/(2k+2)!, Σ (−x)^k/(2k+3)! to k = 7 (next term < 1e-19 at x = 0.25).
    const double x = theta2;
    double s = 1.0 / 1307674368000.0, a = 1.0 / 20922789888000.0, b = 1.0 / 355687428096000.0;
    constexpr double kInvFact[16] = {  // 1/i!
        1.0,         1.0,          1.0 / 2,          1.0 / 6,           1.0 / 24,
        1.0 / 120,   1.0 / 720,    1.0 / 5040,       1.0 / 40320,       1.0 / 362880,
        1.0 / 3628800, 1.0 / 39916800, 1.0 / 479001600, 1.0 / 6227020800.0, 1.0 / 87178291200.0,
        1.0 / 1307674368000.0};
    for (int k = 6; k >= 0; --k) {
      s = kInvFact[2 * k + 1] - x * s;
      a = kInvFact[2 * k + 2] - x * a;
      b = kInvFact[2 * k + 3] - x * b;
    }
    return {s, a, b};
  }
  const double t = std::sqrt(theta2), st = std::sin(t), ct = std::cos(t);
  return {st / t, (1.0 - ct) / theta2, (t - st) / (theta2 * t)};
}

}  // namespace myo
