// Per-element geometry with first and second derivatives: the building blocks of the discrete-shell
// energy (thesis eq. 1–4). Each function returns the quantity g ∈ {A_t, l_e, θ_e} and, when the
// pointers are non-null, its gradient ∇g and Hessian ∇²g over the element's stacked vertex
// positions (vertex-major: x0, y0, z0, x1, …). Fixed-size Eigen types only: no heap allocation,
// so these are safe to call in the hot loops of DiscreteShell.
//
// Degenerate elements (zero area, zero length, collapsed hinge normals) return the value and
// report `false`; their derivatives are then set to zero so callers skip the force (METHOD.md §6.2).
#pragma once

#include "myoshell/core/types.h"

namespace myo {

using Vec6 = Eigen::Matrix<double, 6, 1>;
using Vec9 = Eigen::Matrix<double, 9, 1>;
using Vec12 = Eigen::Matrix<double, 12, 1>;
using Mat6 = Eigen::Matrix<double, 6, 6>;
using Mat9 = Eigen::Matrix<double, 9, 9>;
using Mat12 = Eigen::Matrix<double, 12, 12>;

// Hinge normals with |n| ≤ kHingeDegenerateRatio·|e|² count as collapsed (no force, no NaN).
inline constexpr double kHingeDegenerateRatio = 1e-10;

// Area A of triangle (x0, x1, x2), cm²; grad: 9, cm; hess: 9×9, dimensionless (METHOD.md §1.3–1.4).
// Returns false (and zero derivatives) when the triangle has zero area.
bool triangleAreaDerivatives(const Vec3& x0, const Vec3& x1, const Vec3& x2, double& area,
                             Vec9* grad = nullptr, Mat9* hess = nullptr);

// Length l of edge (xa, xb), cm; grad: 6 (−ê, ê); hess: 6×6, 1/cm. False when l = 0.
bool edgeLengthDerivatives(const Vec3& xa, const Vec3& xb, double& length, Vec6* grad = nullptr,
                           Mat6* hess = nullptr);

// Signed dihedral angle θ of the hinge (x0, x1, x2, x3) of edge_table.h, radians in (−π, π]
// (the value of dihedralAngle() in geometry.h); grad: 12, 1/cm; hess: 12×12, 1/cm².
// False (θ still returned) when either face's normal has collapsed, |n| ≤ kHingeDegenerateRatio·|e|².
bool dihedralAngleDerivatives(const Vec3& x0, const Vec3& x1, const Vec3& x2, const Vec3& x3,
                              double& theta, Vec12* grad = nullptr, Mat12* hess = nullptr);

// θ − θ̄ wrapped into (−π, π], so a hinge whose angle crosses the atan2 branch cut at ±π does not
// see a jump of 2π (METHOD.md §6.3).
double wrapAngle(double delta);

}  // namespace myo
