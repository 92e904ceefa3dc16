#include "myoshell/reduce/modal_warping.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "myoshell/core/check.h"
#include "myoshell/core/errors.h"
#include "myoshell/reduce/rotation_operator.h"

namespace myo {

namespace {

void checkForce(const ModalBasis& basis, const MatX3& F) {
  MYO_CHECK_EQ(F.rows(), static_cast<Eigen::Index>(basis.freeCount()));
}

// Per-mode step coefficients for q̈ + c q̇ + λ q = f with f constant over a step h:
//   q⁺ = a q + b v + g f,   v⁺ = cq q + e v + k f.
struct StepCoefficients {
  double a, b, g, cq, e, k;
};

// Exact (METHOD.md §3.5), valid for any λ (including 0 and slightly negative round-off values)
// and any c ≥ 0, without cancellation near critical damping or λ → 0.
StepCoefficients exactCoefficients(double lambda, double c, double h) {
  const double alpha = 0.5 * c;
  const double D = lambda - alpha * alpha;
  const double z = D * h * h;
  StepCoefficients s{};
  if (std::abs(z) >= 1.0 && D < 0.0) {
    // Strongly overdamped: real roots r1 = −λ/(α+ω) (small, computed without cancellation) and
    // r2 = −α − ω; ωh ≥ 1 so r1 − r2 = 2ω is well conditioned.
    const double w = std::sqrt(-D);
    const double r1 = -lambda / (alpha + w), r2 = -alpha - w;
    const double e1 = std::exp(r1 * h), e2 = std::exp(r2 * h);
    const double SE = (e1 - e2) / (r1 - r2);  // e^{−αh} sinh(ωh)/ω
    const double CE = 0.5 * (e1 + e2);        // e^{−αh} cosh(ωh)
    s.a = CE + alpha * SE;
    s.b = SE;
    s.cq = -lambda * SE;
    s.e = CE - alpha * SE;
    s.k = SE;
    const double i1 = r1 == 0.0 ? h : std::expm1(r1 * h) / r1;
    const double i2 = std::expm1(r2 * h) / r2;
    s.g = (i1 - i2) / (r1 - r2);  // ∫₀ʰ e^{−αs} sinh(ωs)/ω ds
    return s;
  }
  double C, S;  // cos(√D h) and sin(√D h)/√D, continued analytically for D < 0
  if (std::abs(z) < 1.0) {
    // C = Σ (−z)^k/(2k)!, S/h = Σ (−z)^k/(2k+1)!, to k = 11 (< 1e-22 at |z| = 1).
    double c2 = 0.0, s2 = 0.0;
    for (int k = 11; k >= 0; --k) {
      double f2k = 1.0, f2k1 = 1.0;
      for (int i = 2; i <= 2 * k; ++i) f2k *= i;
      f2k1 = f2k * (2 * k + 1);
      c2 = 1.0 / f2k - z * c2;
      s2 = 1.0 / f2k1 - z * s2;
    }
    C = c2;
    S = s2 * h;
  } else {  // D > 0, underdamped
    const double w = std::sqrt(D);
    C = std::cos(w * h);
    S = std::sin(w * h) / w;
  }
  const double E = std::exp(-alpha * h);
  s.a = E * (C + alpha * S);
  s.b = E * S;
  s.cq = -lambda * E * S;
  s.e = E * (C - alpha * S);
  s.k = E * S;
  if (std::abs(lambda) * h * h >= 1e-3) {
    s.g = (1.0 - s.a) / lambda;
  } else {
    // Step response q(h) = Σ_{k≥2} m_k h^k/k! with m_2 = 1, m_{k+2} = −c m_{k+1} − λ m_k; here
    // |λ|h² < 1e-3 and ch < 2.1, so 40 terms reach round-off with no cancellation.
    double mPrev = 0.0, mCur = 1.0;  // m_{k-2}, m_{k-1}, starting at k = 3
    double hk = h * h / 2.0;         // h^k/k!
    double sum = hk;
    for (int k = 3; k < 64; ++k) {
      const double mk = -c * mCur - lambda * mPrev;
      mPrev = mCur;
      mCur = mk;
      hk *= h / k;
      sum += mk * hk;
    }
    s.g = sum;
  }
  return s;
}

StepCoefficients semiImplicitCoefficients(double lambda, double c, double h) {
  // v⁺ = v + h(f − c v − λ q);  q⁺ = q + h v⁺.
  StepCoefficients s{};
  s.cq = -h * lambda;
  s.e = 1.0 - h * c;
  s.k = h;
  s.a = 1.0 + h * s.cq;
  s.b = h * s.e;
  s.g = h * h;
  return s;
}

// g = R(w)ᵀ F = F − s (w×F) + a w×(w×F).
inline void rotateBack(double wx, double wy, double wz, double fx, double fy, double fz, double& gx,
                       double& gy, double& gz) {
  const auto c = rotationCoefficients(wx * wx + wy * wy + wz * wz);
  const double cx = wy * fz - wz * fy, cy = wz * fx - wx * fz, cz = wx * fy - wy * fx;
  const double ccx = wy * cz - wz * cy, ccy = wz * cx - wx * cz, ccz = wx * cy - wy * cx;
  gx = fx - c.s * cx + c.a * ccx;
  gy = fy - c.s * cy + c.a * ccy;
  gz = fz - c.s * cz + c.a * ccz;
}

// u = R̃(w) uL = uL + a (w×uL) + b w×(w×uL).
inline void warp(double wx, double wy, double wz, double lx, double ly, double lz, double* u) {
  const auto c = rotationCoefficients(wx * wx + wy * wy + wz * wz);
  const double cx = wy * lz - wz * ly, cy = wz * lx - wx * lz, cz = wx * ly - wy * lx;
  const double ccx = wy * cz - wz * cy, ccy = wz * cx - wx * cz, ccz = wx * cy - wy * cx;
  u[0] = lx + c.a * cx + c.b * ccx;
  u[1] = ly + c.a * cy + c.b * ccy;
  u[2] = lz + c.a * cz + c.b * ccz;
}

// The kernels over the interleaved basis (row-major, rows × d) — the anatomical read and the thesis's
// float read and projection — compiled for AVX-512, AVX2 + FMA and the x86-64 baseline and chosen
// when the program starts (GCC function multi-versioning, MYO_KERNEL): one portable binary uses the
// machine's widest vectors. The clones may differ in the last bits (FMA contraction), never on one
// machine between runs. A clone is a call through the loader's table, never inlined: a whole loop
// is cloned, not its per-row body (cloning the projection's per-vertex rows made the thesis's step
// 2.7× slower; cloning the whole passes made it 1.5× faster; docs/PERFORMANCE.md, "History").
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && !defined(__SANITIZE_ADDRESS__)
#define MYO_KERNEL __attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")))
#else
#define MYO_KERNEL
#endif
// What a clone calls must be inlined into it to be compiled for its target: forced, not left to
// the inliner's size limits (a call out of a clone runs the baseline build).
#if defined(__GNUC__)
#define MYO_INLINE inline __attribute__((always_inline))
#define MYO_FLATTEN __attribute__((flatten))
#else
#define MYO_INLINE inline
#define MYO_FLATTEN
#endif

// y = B q, one row at a time with independent partial sums: for d ≈ 70 Eigen's row-major
// matrix-vector product ran at a third of the basis's stream rate (u on the ICT whole face's
// 3n × 73: 1,250 µs, this 408 µs, the stream ~400 µs; docs/PERFORMANCE.md, 2026-11-25).
template <class S, int kLanes>
inline void rowDotsImpl(const S* __restrict b, Eigen::Index rows, Eigen::Index d, const S* __restrict x, S* __restrict y) {
  for (Eigen::Index i = 0; i < rows; ++i, b += d) {
    S a[kLanes] = {};
    Eigen::Index j = 0;
    for (; j + kLanes <= d; j += kLanes)
      for (int k = 0; k < kLanes; ++k) a[k] += b[j + k] * x[j + k];
    for (; j < d; ++j) a[j % kLanes] += b[j] * x[j];
    for (int width = kLanes / 2; width >= 1; width /= 2)  // pairwise: the same tree in every clone
      for (int k = 0; k < width; ++k) a[k] += a[k + width];
    y[i] = a[0];
  }
}
MYO_KERNEL void rowDots(const double* b, Eigen::Index rows, Eigen::Index d, const double* x, double* y) {
  rowDotsImpl<double, 8>(b, rows, d, x, y);
}

// The thesis's float kernels, each a whole pass over a channel's vertices cloned as one function
// (one dispatch per call; the per-vertex body inlines and vectorises inside each clone).
//
// The read: Y = B q over the interleaved rows (stride 6: Φ_i then Ψ_i), then u_i = R̃(w_i) Φ_i q
// with w_i = Ψ_i q (or u = Φq when not warped). u is f × 3, row-major. A vertex's R = stride rows
// are taken together, eight partial sums per row, so each load of q serves R rows. q is padded with
// zeros to dPad (a multiple of 8, q[d..dPad) = 0), so a row's last chunk runs over into the next
// row's first values times zero: the kernel runs whole chunks without a scalar tail. The last
// vertex (or few, for d < 8), which would run past the basis, is read from a copy in `tail` (R·d + 8
// floats of workspace).
template <int R>
MYO_INLINE void vertexDots(const float* __restrict b, Eigen::Index d, Eigen::Index dPad, const float* __restrict x,
                       float* __restrict y) {
  float a[R][8] = {};
  for (Eigen::Index j = 0; j < dPad; j += 8)
    for (int r = 0; r < R; ++r)
      for (int k = 0; k < 8; ++k) a[r][k] += b[r * d + j + k] * x[j + k];
  for (int r = 0; r < R; ++r) {
    for (int width = 4; width >= 1; width /= 2)  // pairwise: the same tree in every clone
      for (int k = 0; k < width; ++k) a[r][k] += a[r][k + width];
    y[r] = a[r][0];
  }
}

template <int R>
MYO_INLINE void readFloatImpl(const float* b, Eigen::Index f, Eigen::Index d, bool warped, const float* q,
                          float* y, double* u, float* tail) {
  const Eigen::Index dPad = (d + 7) / 8 * 8;
  Eigen::Index direct = f;  // vertices whose last chunk stays inside the basis
  while (direct > 0 && R * d * (direct - 1) + (R - 1) * d + dPad > R * d * f) --direct;
  for (Eigen::Index i = 0; i < direct; ++i) vertexDots<R>(b + R * d * i, d, dPad, q, y + R * i);
  for (Eigen::Index i = direct; i < f; ++i) {
    std::copy(b + R * d * i, b + R * d * (i + 1), tail);
    std::fill(tail + R * d, tail + R * d + 8, 0.0f);
    vertexDots<R>(tail, d, dPad, q, y + R * i);
  }
  if (!warped) {
    for (Eigen::Index i = 0; i < 3 * f; ++i) u[i] = double(y[i]);
    return;
  }
  for (Eigen::Index i = 0; i < f; ++i, y += R, u += 3) warp(y[3], y[4], y[5], y[0], y[1], y[2], u);
}

MYO_KERNEL MYO_FLATTEN void readFloat(const float* b, Eigen::Index f, Eigen::Index d, int stride, bool warped,
                          const float* q, float* y, double* u, float* tail) {
  if (stride == 6) readFloatImpl<6>(b, f, d, warped, q, y, u, tail);
  else readFloatImpl<3>(b, f, d, warped, q, y, u, tail);
}

// The projection: f̃ = Σ_i Φ_iᵀ (R_iᵀ F_i) over the rows of F (f × 3, row-major) that are not zero,
// R_i from w_i = Ψ_i q of the last read (y). Reads only the Φ rows of the loaded vertices, sparse
// (a muscle's ROI) or dense (gravity, a drag) alike. Summed in float over blocks of kBlock loaded
// vertices (a loop over modes that vectorises; a: d floats of workspace), the block sums in double.
MYO_KERNEL MYO_FLATTEN void projectFloat(const float* b, Eigen::Index f, Eigen::Index d, int stride, bool warped,
                             const double* F, const float* y, float* a, double* ft) {
  constexpr int kBlock = 64;
  for (Eigen::Index j = 0; j < d; ++j) ft[j] = 0.0, a[j] = 0.0f;
  int inBlock = 0;
  for (Eigen::Index i = 0; i < f; ++i, F += 3) {
    double gx = F[0], gy = F[1], gz = F[2];
    if (gx == 0.0 && gy == 0.0 && gz == 0.0) continue;
    if (warped) {
      const float* w = y + stride * i + 3;
      rotateBack(w[0], w[1], w[2], F[0], F[1], F[2], gx, gy, gz);
    }
    const float sx = float(gx), sy = float(gy), sz = float(gz);
    const float* __restrict px = b + stride * i * d;
    const float* __restrict py = px + d;
    const float* __restrict pz = py + d;
    float* __restrict acc = a;
    for (Eigen::Index j = 0; j < d; ++j) acc[j] += px[j] * sx + py[j] * sy + pz[j] * sz;
    if (++inBlock == kBlock) {
      for (Eigen::Index j = 0; j < d; ++j) ft[j] += double(a[j]), a[j] = 0.0f;
      inBlock = 0;
    }
  }
  for (Eigen::Index j = 0; j < d; ++j) ft[j] += double(a[j]);
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// Displacement maps.

MatX3 linearDisplacement(const ModalBasis& basis, const VecX& q) {
  MYO_CHECK_EQ(q.size(), static_cast<Eigen::Index>(basis.modeCount()));
  VecX u = basis.Phi * q;
  return rows3(u);
}

MatX3 warpedDisplacement(const ModalBasis& basis, const VecX& q) {
  MYO_CHECK_EQ(q.size(), static_cast<Eigen::Index>(basis.modeCount()));
  const VecX uL = basis.Phi * q;
  const VecX w = basis.Psi * q;
  MatX3 u(basis.freeCount(), 3);
  for (int i = 0; i < basis.freeCount(); ++i)
    warp(w[3 * i], w[3 * i + 1], w[3 * i + 2], uL[3 * i], uL[3 * i + 1], uL[3 * i + 2], u.row(i).data());
  return u;
}

VecX modalForce(const ModalBasis& basis, const VecX& q, const MatX3& freeForce, bool warped) {
  checkForce(basis, freeForce);
  if (!warped) return basis.Phi.transpose() * flat(freeForce);
  const VecX w = basis.Psi * q;
  VecX g(3 * basis.freeCount());
  for (int i = 0; i < basis.freeCount(); ++i)
    rotateBack(w[3 * i], w[3 * i + 1], w[3 * i + 2], freeForce(i, 0), freeForce(i, 1), freeForce(i, 2),
               g[3 * i], g[3 * i + 1], g[3 * i + 2]);
  return basis.Phi.transpose() * g;
}

// ---------------------------------------------------------------------------------------------
// The integrator.

// The per-vertex interleaved basis: rows stride·i .. stride·i+2 hold Φ_i (x, y, z) and, with warping,
// rows stride·i+3 .. +5 hold Ψ_i; so one matvec Y = B q gives Φq and Ψq, streaming the basis once.
struct ModalWarpingIntegrator::Kernel {
  ModalPrecision precision;
  int stride = 6;
  Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> Bf;
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> Bd;
  Eigen::VectorXf qf, Yf, accf, tailf;  // qf padded with zeros to a multiple of 8
  Eigen::VectorXd Yd, accd, Gd;

  template <class Mat, class Vec>
  static void fill(Mat& B, Vec& Y, const ModalBasis& basis, int stride) {
    const int f = basis.freeCount(), d = basis.modeCount();
    B.resize(static_cast<Eigen::Index>(stride) * f, d);
    for (int i = 0; i < f; ++i) {
      B.middleRows(stride * i, 3) = basis.Phi.middleRows(3 * i, 3).cast<typename Mat::Scalar>();
      if (stride == 6)
        B.middleRows(stride * i + 3, 3) = basis.Psi.middleRows(3 * i, 3).cast<typename Mat::Scalar>();
    }
    Y = Vec::Zero(B.rows());
  }

  // f̃ = Σ_i Φ_iᵀ (R_iᵀ F_i) over the rows of F that are not zero; R from the cached w = Ψq.
  // Contributions are summed in the basis's precision over blocks of kBlock loaded vertices (a
  // loop over modes that vectorizes), and the block sums in double, which keeps the float path's
  // error at the level of one block's sum.
  template <class Mat, class Vec, class Acc>
  static void project(const Mat& B, const Vec& Y, int stride, bool warped, const MatX3& F, Acc& acc,
                      VecX& ft) {
    using S = typename Mat::Scalar;
    constexpr int kBlock = 64;
    const Eigen::Index d = B.cols(), f = F.rows();
    ft.setZero();
    acc.setZero();
    S* __restrict a = acc.data();
    int inBlock = 0;
    for (Eigen::Index i = 0; i < f; ++i) {
      double gx = F(i, 0), gy = F(i, 1), gz = F(i, 2);
      if (gx == 0.0 && gy == 0.0 && gz == 0.0) continue;
      if (warped) {
        const auto* w = Y.data() + stride * i + 3;
        rotateBack(w[0], w[1], w[2], F(i, 0), F(i, 1), F(i, 2), gx, gy, gz);
      }
      const S sx = S(gx), sy = S(gy), sz = S(gz);
      const S* __restrict px = B.data() + stride * i * d;
      const S* __restrict py = px + d;
      const S* __restrict pz = py + d;
      for (Eigen::Index j = 0; j < d; ++j) a[j] += px[j] * sx + py[j] * sy + pz[j] * sz;
      if (++inBlock == kBlock) {
        ft += acc.template cast<double>();
        acc.setZero();
        inBlock = 0;
      }
    }
    ft += acc.template cast<double>();
  }

  // Dense-load variant: G holds R_iᵀF_i in the Φ rows (zeros in the Ψ rows), then f̃ = BᵀG as one
  // streaming matvec. Used when most vertices are loaded (gravity, drag).
  template <class Mat, class Vec>
  static void projectDense(const Mat& B, const Vec& Y, int stride, bool warped, const MatX3& F, Vec& G,
                           Vec& acc, VecX& ft) {
    using S = typename Mat::Scalar;
    const Eigen::Index f = F.rows();
    S* g = G.data();
    for (Eigen::Index i = 0; i < f; ++i, g += stride) {
      double gx = F(i, 0), gy = F(i, 1), gz = F(i, 2);
      if (warped && (gx != 0.0 || gy != 0.0 || gz != 0.0)) {
        const auto* w = Y.data() + stride * i + 3;
        rotateBack(w[0], w[1], w[2], F(i, 0), F(i, 1), F(i, 2), gx, gy, gz);
      }
      g[0] = S(gx);
      g[1] = S(gy);
      g[2] = S(gz);
    }
    acc.noalias() = B.transpose() * G;  // into a preallocated d-vector: no temporary
    ft = acc.template cast<double>();
  }

  template <class Vec>
  static void output(const Vec& Y, int stride, bool warped, MatX3& u) {
    const Eigen::Index f = u.rows();
    double* pu = u.data();
    const auto* y = Y.data();
    if (!warped) {
      for (Eigen::Index i = 0; i < 3 * f; ++i) pu[i] = double(y[i]);
      return;
    }
    for (Eigen::Index i = 0; i < f; ++i, y += stride, pu += 3)
      warp(y[3], y[4], y[5], y[0], y[1], y[2], pu);
  }
};

ModalWarpingIntegrator::ModalWarpingIntegrator(std::shared_ptr<const ModalBasis> basis,
                                               const ModalWarpingSettings& settings)
    : basis_(std::move(basis)), settings_(settings) {
  MYO_CHECK(basis_ != nullptr, "null basis");
  const ModalBasis& b = *basis_;
  const std::string ch = "channel '" + settings_.channel + "': ";
  if (!(settings_.dt > 0.0) || !std::isfinite(settings_.dt))
    throw InputError(ch + "the time step dt must be positive");
  if (!(settings_.rayleighMass >= 0.0) || !(settings_.rayleighStiffness >= 0.0))
    throw InputError(ch + "Rayleigh damping coefficients must be non-negative");
  MYO_CHECK(b.modeCount() >= 1, ch << "empty basis");
  MYO_CHECK_EQ(b.Phi.rows(), static_cast<Eigen::Index>(3 * b.freeCount()));
  MYO_CHECK_EQ(b.Phi.cols(), static_cast<Eigen::Index>(b.modeCount()));
  if (settings_.warping) {
    MYO_CHECK_EQ(b.Psi.rows(), b.Phi.rows());
    MYO_CHECK_EQ(b.Psi.cols(), b.Phi.cols());
  }
  const int d = b.modeCount(), f = b.freeCount();
  q_ = VecX::Zero(d);
  v_ = VecX::Zero(d);
  ftilde_ = VecX::Zero(d);
  u_ = MatX3::Zero(f, 3);
  kernel_ = std::make_unique<Kernel>();
  kernel_->precision = settings_.precision;
  kernel_->stride = settings_.warping ? 6 : 3;
  if (settings_.precision == ModalPrecision::Float) {
    Kernel::fill(kernel_->Bf, kernel_->Yf, b, kernel_->stride);
    kernel_->qf = Eigen::VectorXf::Zero((d + 7) / 8 * 8);
    kernel_->tailf = Eigen::VectorXf::Zero(kernel_->stride * d + 8);
    kernel_->accf = Eigen::VectorXf::Zero(d);
  } else {
    Kernel::fill(kernel_->Bd, kernel_->Yd, b, kernel_->stride);
    kernel_->accd = Eigen::VectorXd::Zero(d);
    kernel_->Gd = Eigen::VectorXd::Zero(kernel_->Bd.rows());
  }
  const VecX rowNorm2 = b.Phi.rowwise().squaredNorm();
  for (int i = 0; i < f; ++i) rowNormMax_ = std::max(rowNormMax_, std::sqrt(rowNorm2.segment(3 * i, 3).sum()));
  computeCoefficients();
}

ModalWarpingIntegrator::~ModalWarpingIntegrator() = default;
ModalWarpingIntegrator::ModalWarpingIntegrator(ModalWarpingIntegrator&&) noexcept = default;
ModalWarpingIntegrator& ModalWarpingIntegrator::operator=(ModalWarpingIntegrator&&) noexcept = default;

double ModalWarpingIntegrator::maxSemiImplicitDt() const {
  const double lmax = scale_ * basis_->lambda.maxCoeff();
  return lmax > 0.0 ? 2.0 / std::sqrt(lmax) : std::numeric_limits<double>::infinity();
}

void ModalWarpingIntegrator::computeCoefficients() {
  const ModalBasis& b = *basis_;
  const int d = b.modeCount();
  const double h = settings_.dt;
  if (settings_.stepper == ModalStepper::SemiImplicit) {
    const double lmax = scale_ * b.lambda.maxCoeff();
    if (lmax > 0.0 && h * std::sqrt(lmax) >= 2.0) {
      std::ostringstream os;
      os << "channel '" << settings_.channel << "': semi-implicit Euler is unstable at dt = " << h
         << " s: the highest mode has lambda_max = " << lmax
         << " 1/s^2, so dt must be below 2/sqrt(lambda_max) = " << 2.0 / std::sqrt(lmax)
         << " s (use the exact stepper, a smaller dt or fewer modes)";
      throw InputError(os.str());
    }
  }
  lambdaEff_ = scale_ * b.lambda;
  damping_ = (settings_.rayleighMass + settings_.rayleighStiffness * lambdaEff_.array()).matrix();
  for (VecX* c : {&ca_, &cb_, &cg_, &cc_, &ce_, &ck_}) c->resize(d);
  for (int j = 0; j < d; ++j) {
    const StepCoefficients s = settings_.stepper == ModalStepper::Exact
                                   ? exactCoefficients(lambdaEff_[j], damping_[j], h)
                                   : semiImplicitCoefficients(lambdaEff_[j], damping_[j], h);
    ca_[j] = s.a;
    cb_[j] = s.b;
    cg_[j] = s.g;
    cc_[j] = s.cq;
    ce_[j] = s.e;
    ck_[j] = s.k;
  }
}

void ModalWarpingIntegrator::setStiffnessScale(double s) {
  if (!(s > 0.0) || !std::isfinite(s))
    throw InputError("channel '" + settings_.channel + "': the stiffness scale must be positive");
  const double old = scale_;
  scale_ = s;
  try {
    computeCoefficients();
  } catch (...) {
    scale_ = old;
    computeCoefficients();
    throw;
  }
}

void ModalWarpingIntegrator::updateDisplacement() const {
  Kernel& k = *kernel_;
  stale_ = false;
  if (k.precision == ModalPrecision::Float) {
    k.qf.head(q_.size()) = q_.cast<float>();  // the rest stays zero (readFloat's padding)
    readFloat(k.Bf.data(), u_.rows(), k.Bf.cols(), k.stride, settings_.warping, k.qf.data(), k.Yf.data(), u_.data(),
              k.tailf.data());
  } else if (!settings_.warping) {
    rowDots(k.Bd.data(), k.Bd.rows(), k.Bd.cols(), q_.data(), u_.data());  // the interleaved Φ rows are u's layout: no copy
  } else {
    rowDots(k.Bd.data(), k.Bd.rows(), k.Bd.cols(), q_.data(), k.Yd.data());
    Kernel::output(k.Yd, k.stride, settings_.warping, u_);
  }
}

void ModalWarpingIntegrator::step(const MatX3& freeForce) {
  projectForce(freeForce);
  // 4: per-mode advance.
  advance(ftilde_);
  // 5: w = Ψq, u = R̃(w)Φq.
  updateDisplacement();
}

void ModalWarpingIntegrator::stepAbout(const MatX3& freeForce, const VecX& before, const VecX& after) {
  MYO_CHECK_EQ(after.size(), q_.size());
  projectForce(freeForce);
  ftilde_.array() -= lambdaEff_.array() * after.array();
  advanceAbout(ftilde_, before, after);
  updateDisplacement();
}

void ModalWarpingIntegrator::projectForce(const MatX3& freeForce) {
  checkForce(*basis_, freeForce);
  Kernel& k = *kernel_;
  // 1–3: f̃ = Φᵀ R(Ψq)ᵀ F with w = Ψq cached from the last displacement update (same q).
  if (k.precision == ModalPrecision::Float) {
    projectFloat(k.Bf.data(), freeForce.rows(), k.Bf.cols(), k.stride, settings_.warping, freeForce.data(),
                 k.Yf.data(), k.accf.data(), ftilde_.data());
  } else {
    // Count loaded rows (cheap, f×3 doubles): sparse loads (a muscle's ROI) take the gather loop,
    // dense loads (gravity) one streaming matvec.
    Eigen::Index loaded = 0;
    for (Eigen::Index i = 0; i < freeForce.rows(); ++i)
      loaded += static_cast<int>(freeForce(i, 0) != 0.0) | static_cast<int>(freeForce(i, 1) != 0.0) |
                static_cast<int>(freeForce(i, 2) != 0.0);
    if (4 * loaded > freeForce.rows())
      Kernel::projectDense(k.Bd, k.Yd, k.stride, settings_.warping, freeForce, k.Gd, k.accd, ftilde_);
    else
      Kernel::project(k.Bd, k.Yd, k.stride, settings_.warping, freeForce, k.accd, ftilde_);
  }
}

void ModalWarpingIntegrator::stepModal(const VecX& modalForce) {
  MYO_CHECK(!settings_.warping, "channel '" << settings_.channel << "': stepModal needs warping off");
  MYO_CHECK_EQ(modalForce.size(), q_.size());
  advance(modalForce);
  stale_ = true;
}

void ModalWarpingIntegrator::stepModalAbout(const VecX& modalForce, const VecX& before, const VecX& after) {
  MYO_CHECK(!settings_.warping, "channel '" << settings_.channel << "': stepModalAbout needs warping off");
  MYO_CHECK_EQ(modalForce.size(), q_.size());
  advanceAbout(modalForce, before, after);
  stale_ = true;
}

void ModalWarpingIntegrator::advanceAbout(const VecX& ft, const VecX& before, const VecX& after) {
  MYO_CHECK_EQ(before.size(), q_.size());
  MYO_CHECK_EQ(after.size(), q_.size());
  const Eigen::Index d = q_.size();
  for (Eigen::Index j = 0; j < d; ++j) {
    const double r = q_[j] - before[j], v = v_[j], f = ft[j];
    q_[j] = after[j] + (ca_[j] * r + cb_[j] * v + cg_[j] * f);
    v_[j] = cc_[j] * r + ce_[j] * v + ck_[j] * f;
  }
}

void ModalWarpingIntegrator::advance(const VecX& ft) {
  const Eigen::Index d = q_.size();
  for (Eigen::Index j = 0; j < d; ++j) {
    const double q = q_[j], v = v_[j], f = ft[j];
    q_[j] = ca_[j] * q + cb_[j] * v + cg_[j] * f;
    v_[j] = cc_[j] * q + ce_[j] * v + ck_[j] * f;
  }
}

void ModalWarpingIntegrator::step() {
  const Eigen::Index d = q_.size();
  for (Eigen::Index j = 0; j < d; ++j) {
    const double q = q_[j], v = v_[j];
    q_[j] = ca_[j] * q + cb_[j] * v;
    v_[j] = cc_[j] * q + ce_[j] * v;
  }
  updateDisplacement();
}

size_t ModalWarpingIntegrator::basisBytes() const {
  const Kernel& k = *kernel_;
  return k.precision == ModalPrecision::Float ? sizeof(float) * static_cast<size_t>(k.Bf.size())
                                              : sizeof(double) * static_cast<size_t>(k.Bd.size());
}

double ModalWarpingIntegrator::streamBasis() const {
  const Kernel& k = *kernel_;
  return k.precision == ModalPrecision::Float ? double(k.Bf.sum()) : k.Bd.sum();
}

void ModalWarpingIntegrator::addDisplacementTo(MatX3& full) const {
  MYO_CHECK_EQ(full.rows(), static_cast<Eigen::Index>(basis_->fullVertexCount));
  const auto& fv = basis_->freeVertices;
  const MatX3& u = freeDisplacement();
  for (size_t i = 0; i < fv.size(); ++i) full.row(fv[i]) += u.row(static_cast<Eigen::Index>(i));
}

MatX3 ModalWarpingIntegrator::freeRotations() const {
  const Kernel& k = *kernel_;
  const int f = basis_->freeCount();
  MatX3 w = MatX3::Zero(f, 3);
  if (!settings_.warping) return w;
  for (int i = 0; i < f; ++i)
    for (int c = 0; c < 3; ++c)
      w(i, c) = k.precision == ModalPrecision::Float ? double(k.Yf[6 * i + 3 + c]) : k.Yd[6 * i + 3 + c];
  return w;
}

void ModalWarpingIntegrator::reset() {
  q_.setZero();
  v_.setZero();
  if (settings_.warping) updateDisplacement();  // the next step's rotations read Ψq
  else stale_ = true;                           // u = Φq = 0 when read
}

void ModalWarpingIntegrator::setState(const VecX& q, const VecX& qdot) {
  MYO_CHECK_EQ(q.size(), q_.size());
  MYO_CHECK_EQ(qdot.size(), v_.size());
  q_ = q;
  v_ = qdot;
  updateDisplacement();
}

bool ModalWarpingIntegrator::isAtRest(double tol) const {
  return q_.cwiseAbs().maxCoeff() < tol && v_.cwiseAbs().maxCoeff() < tol;
}

double ModalWarpingIntegrator::energy() const {
  return 0.5 * v_.squaredNorm() + 0.5 * q_.dot(lambdaEff_.cwiseProduct(q_));
}

}  // namespace myo
