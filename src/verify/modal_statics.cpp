#include "myoshell/verify/modal_statics.h"

#include <Eigen/LU>

#include <algorithm>
#include <sstream>

#include "myoshell/core/check.h"
#include "myoshell/core/errors.h"
#include "myoshell/reduce/modal_warping.h"
#include "myoshell/reduce/rotation_operator.h"

namespace myo {

namespace {

Mat3 cross(const Vec3& a) {
  Mat3 m;
  m << 0, -a.z(), a.y(), a.z(), 0, -a.x(), -a.y(), a.x(), 0;
  return m;
}

void checkForce(const ModalBasis& basis, const MatX3& F) {
  MYO_CHECK_EQ(F.rows(), static_cast<Eigen::Index>(basis.freeCount()));
}

void checkConstrained(const ModalBasis& basis) {
  const double lmax = basis.lambda.cwiseAbs().maxCoeff();
  for (int j = 0; j < basis.modeCount(); ++j)
    if (!(basis.lambda[j] > 1e-9 * lmax)) {
      std::ostringstream os;
      os << "static modal solve needs a constrained basis, but mode " << j << " has lambda = "
         << basis.lambda[j] << " 1/s^2 (a rigid mode): pin two non-collinear rows of vertices";
      throw NumericalError(os.str());
    }
}

}  // namespace

StaticSolveResult solveStaticLinear(const ModalBasis& basis, const MatX3& freeForce) {
  checkForce(basis, freeForce);
  checkConstrained(basis);
  StaticSolveResult r;
  r.q = (basis.Phi.transpose() * flat(freeForce)).cwiseQuotient(basis.lambda);
  r.u = linearDisplacement(basis, r.q);
  return r;
}

StaticSolveResult solveStaticWarped(const ModalBasis& basis, const MatX3& freeForce,
                                    const StaticSolveSettings& settings) {
  checkForce(basis, freeForce);
  checkConstrained(basis);
  const int d = basis.modeCount(), f = basis.freeCount();
  StaticSolveResult r;
  r.q = VecX::Zero(d);
  const double ref = (basis.Phi.transpose() * flat(freeForce)).norm();
  if (ref == 0.0) {
    r.u = MatX3::Zero(f, 3);
    return r;
  }
  const int steps = std::max(1, settings.loadSteps);
  auto residual = [&](const VecX& q, const MatX3& F) {
    return VecX(basis.lambda.cwiseProduct(q) - modalForce(basis, q, F, true));
  };
  MatX J(d, d), T(3, d);
  bool ok = true;
  double relRes = 0.0;
  for (int l = 1; l <= steps; ++l) {
    const MatX3 F = freeForce * (double(l) / steps);
    const double refl = ref * double(l) / steps;
    VecX res = residual(r.q, F);
    for (;;) {
      relRes = res.norm() / refl;
      if (relRes <= settings.tolerance) break;
      if (r.iterations >= settings.maxIterations) {
        ok = false;
        break;
      }
      // J = Λ − Σ_i Φ_iᵀ R_iᵀ [F_i]× R̃(w_i) Ψ_i  (∂(R(w)ᵀF)/∂w = Rᵀ[F]× R̃(w)).
      const VecX w = basis.Psi * r.q;
      J = basis.lambda.asDiagonal();
      for (int i = 0; i < f; ++i) {
        const Vec3 Fi = F.row(i).transpose();
        if (Fi.squaredNorm() == 0.0) continue;
        const Vec3 wi = w.segment<3>(3 * i);
        const Mat3 A = rotationFromVector(wi).transpose() * cross(Fi) * warpMatrix(wi);
        T.noalias() = A * basis.Psi.middleRows(3 * i, 3);
        J.noalias() -= basis.Phi.middleRows(3 * i, 3).transpose() * T;
      }
      const VecX dq = -J.partialPivLu().solve(res);
      ++r.iterations;
      double t = 1.0;
      const double r0 = res.norm();
      VecX qt, rt;
      for (;;) {
        qt = r.q + t * dq;
        rt = residual(qt, F);
        if (rt.norm() <= (1.0 - 1e-4 * t) * r0 || t < 1e-6) break;
        t *= 0.5;
      }
      if (!(rt.norm() < r0)) {  // no progress at all: stop here
        ok = false;
        relRes = r0 / refl;
        break;
      }
      r.q = qt;
      res = rt;
    }
    if (!ok) break;
  }
  r.residual = relRes;
  r.converged = ok;
  r.u = warpedDisplacement(basis, r.q);
  return r;
}

}  // namespace myo
