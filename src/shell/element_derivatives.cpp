// Derivatives of triangle area, edge length and signed dihedral angle (METHOD.md §1.3–1.4).
// All derived here by the chain rule; docs/shell_energy.md writes the derivation out.
#include "myoshell/shell/element_derivatives.h"

#include <cmath>
#include <numbers>


namespace myo {

namespace {

// [a]×, so that cross(a) * b = a × b.
inline Mat3 cross(const Vec3& a) {
  Mat3 m;
  m << 0.0, -a.z(), a.y(), a.z(), 0.0, -a.x(), -a.y(), a.x(), 0.0;
  return m;
}

}  // namespace

double wrapAngle(double delta) {
  constexpr double kPi = std::numbers::pi;
  // One step is enough for differences of two angles in (−π, π].
  if (delta > kPi) return delta - 2.0 * kPi;
  if (delta <= -kPi) return delta + 2.0 * kPi;
  return delta;
}

bool triangleAreaDerivatives(const Vec3& x0, const Vec3& x1, const Vec3& x2, double& area,
                             Vec9* grad, Mat9* hess) {
  // n = (x1 − x0) × (x2 − x0), A = |n|/2; ∂n/∂x_i = [c_i]× with c_i = x_{i+2} − x_{i+1}.
  const Vec3 c[3] = {x2 - x1, x0 - x2, x1 - x0};
  const Vec3 n = c[2].cross(x2 - x0);
  const double nNorm = n.norm();
  area = 0.5 * nNorm;
  const double scale = c[0].squaredNorm() + c[1].squaredNorm() + c[2].squaredNorm();
  const bool ok = nNorm > kHingeDegenerateRatio * scale && nNorm > 0.0;
  if (!ok) {
    if (grad) grad->setZero();
    if (hess) hess->setZero();
    return false;
  }
  const Vec3 nh = n / nNorm;
  if (grad)
    for (int i = 0; i < 3; ++i) grad->segment<3>(3 * i) = 0.5 * nh.cross(c[i]);  // ½ n̂ × c_i
  if (hess) {
    // ∂²A/∂x_i∂x_j = ½ [c_i]×ᵀ (I − n̂n̂ᵀ)/|n| [c_j]× + ½ n̂·∂²n/∂x_i∂x_j. The second part comes
    // from n = x0×x1 + x1×x2 + x2×x0: n̂·(u × v) = uᵀ(−[n̂]×)v for the pair (i, i+1).
    const Mat3 P = (Mat3::Identity() - nh * nh.transpose()) / (2.0 * nNorm);
    Mat3 C[3];
    for (int i = 0; i < 3; ++i) C[i] = cross(c[i]);
    const Mat3 N = 0.5 * cross(nh);
    for (int i = 0; i < 3; ++i) {
      const Mat3 CiP = C[i].transpose() * P;
      for (int j = i; j < 3; ++j) {
        Mat3 block = CiP * C[j];
        if (j == (i + 1) % 3) block -= N;
        else if (j == (i + 2) % 3) block += N;
        hess->block<3, 3>(3 * i, 3 * j) = block;
        if (j != i) hess->block<3, 3>(3 * j, 3 * i) = block.transpose();
      }
    }
  }
  return true;
}

bool edgeLengthDerivatives(const Vec3& xa, const Vec3& xb, double& length, Vec6* grad,
                           Mat6* hess) {
  const Vec3 e = xb - xa;
  length = e.norm();
  if (!(length > 0.0)) {
    if (grad) grad->setZero();
    if (hess) hess->setZero();
    return false;
  }
  const Vec3 eh = e / length;
  if (grad) {
    grad->head<3>() = -eh;
    grad->tail<3>() = eh;
  }
  if (hess) {
    // ∂ê/∂x_b = (I − êêᵀ)/l, and x_a enters with the opposite sign.
    const Mat3 B = (Mat3::Identity() - eh * eh.transpose()) / length;
    hess->topLeftCorner<3, 3>() = B;
    hess->bottomRightCorner<3, 3>() = B;
    hess->topRightCorner<3, 3>() = -B;
    hess->bottomLeftCorner<3, 3>() = -B;
  }
  return true;
}

bool dihedralAngleDerivatives(const Vec3& x0, const Vec3& x1, const Vec3& x2, const Vec3& x3,
                              double& theta, Vec12* grad, Mat12* hess) {
  const Vec3 e = x1 - x0;
  const double L2 = e.squaredNorm();
  const double L = std::sqrt(L2);
  const Vec3 n0 = e.cross(x2 - x0);      // face f0 = (x0, x1, x2), |n0| = 2A0
  const Vec3 n1 = (x0 - x1).cross(x3 - x1);  // face f1 = (x1, x0, x3), |n1| = 2A1
  // Exactly geometry.h's dihedralAngle (same operations, so θ and θ̄ agree bit for bit; tested),
  // inlined to share n0, n1 with the derivatives.
  theta = L == 0.0 ? 0.0 : std::atan2(n0.cross(n1).dot(e) / L, n0.dot(n1));
  const double N0 = n0.squaredNorm(), N1 = n1.squaredNorm();
  const double tol = kHingeDegenerateRatio * L2;
  const bool ok = L > 0.0 && N0 > tol * tol && N1 > tol * tol;
  if (!ok) {
    if (grad) grad->setZero();
    if (hess) hess->setZero();
    return false;
  }
  if (!grad && !hess) return true;

  // Gradient (METHOD.md §1.3): g2 = ∇_{x2}θ = −|e| n0/|n0|², g3 = ∇_{x3}θ = −|e| n1/|n1|²,
  // ∇_{x0}θ = α2 g2 + α3 g3, ∇_{x1}θ = β2 g2 + β3 g3 with α_k = (x_k − x1)·e/|e|², β_k = −1 − α_k.
  const Vec3 g2 = -L / N0 * n0;
  const Vec3 g3 = -L / N1 * n1;
  const Vec3 a = x2 - x1, b = x3 - x1;
  const double alpha2 = a.dot(e) / L2, alpha3 = b.dot(e) / L2;
  const double beta2 = -1.0 - alpha2, beta3 = -1.0 - alpha3;
  Vec12 g;
  g.segment<3>(0) = alpha2 * g2 + alpha3 * g3;
  g.segment<3>(3) = beta2 * g2 + beta3 * g3;
  g.segment<3>(6) = g2;
  g.segment<3>(9) = g3;
  if (grad) *grad = g;
  if (!hess) return true;

  // Hessian: differentiate the gradient above (docs/shell_energy.md §4).
  //   ∂g2 = q0 dL + P0 dn0, q0 = −n0/|n0|², P0 = −|e| (I − 2 n̂0 n̂0ᵀ)/|n0|², dL = êᵀ(dx1 − dx0),
  //   dn0 = [x2−x1]× dx0 − [x2−x0]× dx1 + [e]× dx2;   likewise for g3 with
  //   dn1 = −[x3−x1]× dx0 + [x3−x0]× dx1 − [e]× dx3.
  const Vec3 eh = e / L;
  const Vec3 q0 = -n0 / N0, q1 = -n1 / N1;
  const Mat3 P0 = (-L / N0) * (Mat3::Identity() - (2.0 / N0) * n0 * n0.transpose());
  const Mat3 P1 = (-L / N1) * (Mat3::Identity() - (2.0 / N1) * n1 * n1.transpose());
  const Mat3 Ee = cross(e);
  Eigen::Matrix<double, 3, 12> J2, J3;  // ∂g2/∂x, ∂g3/∂x
  const Mat3 q0e = q0 * eh.transpose(), q1e = q1 * eh.transpose();
  J2.block<3, 3>(0, 0) = -q0e + P0 * cross(x2 - x1);
  J2.block<3, 3>(0, 3) = q0e - P0 * cross(x2 - x0);
  J2.block<3, 3>(0, 6) = P0 * Ee;
  J2.block<3, 3>(0, 9).setZero();
  J3.block<3, 3>(0, 0) = -q1e - P1 * cross(b);
  J3.block<3, 3>(0, 3) = q1e + P1 * cross(x3 - x0);
  J3.block<3, 3>(0, 6).setZero();
  J3.block<3, 3>(0, 9) = -P1 * Ee;
  // ∇α2 = ((−a + 2α2 e), (a − e − 2α2 e), e, 0)/|e|², ∇α3 likewise with b and x3; ∇β = −∇α.
  Vec12 dA2, dA3;
  dA2 << (-a + 2.0 * alpha2 * e) / L2, (a - e - 2.0 * alpha2 * e) / L2, e / L2, Vec3::Zero();
  dA3 << (-b + 2.0 * alpha3 * e) / L2, (b - e - 2.0 * alpha3 * e) / L2, Vec3::Zero(), e / L2;
  Mat12& H = *hess;
  H.block<3, 12>(0, 0) = g2 * dA2.transpose() + alpha2 * J2 + g3 * dA3.transpose() + alpha3 * J3;
  H.block<3, 12>(3, 0) = -g2 * dA2.transpose() + beta2 * J2 - g3 * dA3.transpose() + beta3 * J3;
  H.block<3, 12>(6, 0) = J2;
  H.block<3, 12>(9, 0) = J3;
  // Symmetric in exact arithmetic; symmetrize the rounding.
  H = 0.5 * (H + H.transpose()).eval();
  return true;
}

}  // namespace myo
