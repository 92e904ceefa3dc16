#include "myoshell/head/auto_landmarks.h"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <array>
#include <cmath>
#include <fmt/format.h>
#include <numbers>
#include <numeric>
#include <optional>

#include "myoshell/core/errors.h"
#include "myoshell/head/head_checks.h"
#include "myoshell/mesh/closest_point.h"
#include "myoshell/mesh/geometry.h"
#include "myoshell/mesh/ray_cast.h"
#include "myoshell/mesh/subdivision.h"

namespace myo {

namespace {

struct Similarity {
  double s = 1.0;
  Mat3 R = Mat3::Identity();
  Vec3 t = Vec3::Zero();
  Vec3 apply(const Vec3& p) const { return s * (R * p) + t; }
};

// Connected pieces of the triangles: label per vertex (-1: on no triangle).
std::vector<int> pieceLabels(const TriMesh& mesh, int& count) {
  const int n = mesh.vertexCount();
  std::vector<int> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](int a) {
    while (parent[a] != a) a = parent[a] = parent[parent[a]];
    return a;
  };
  std::vector<char> used(n, 0);
  for (int t = 0; t < mesh.triangleCount(); ++t)
    for (int k = 0; k < 3; ++k) {
      used[mesh.F(t, k)] = 1;
      const int a = find(mesh.F(t, k)), b = find(mesh.F(t, (k + 1) % 3));
      if (a != b) parent[std::max(a, b)] = std::min(a, b);
    }
  std::vector<int> label(n, -1), rootLabel(n, -1);
  count = 0;
  for (int v = 0; v < n; ++v) {
    if (!used[v]) continue;
    const int r = find(v);
    if (rootLabel[r] < 0) rootLabel[r] = count++;
    label[v] = rootLabel[r];
  }
  return label;
}

// The 24 rotations that map coordinate axes onto signed coordinate axes.
std::vector<Mat3> axisRotations() {
  std::vector<Mat3> out;
  const std::array<std::array<int, 3>, 6> perms = {{{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}}};
  for (const auto& p : perms)
    for (int signs = 0; signs < 8; ++signs) {
      Mat3 S = Mat3::Zero();
      for (int c = 0; c < 3; ++c) S(p[c], c) = (signs >> c & 1) ? -1.0 : 1.0;
      if (S.determinant() > 0) out.push_back(S);
    }
  return out;
}

// Principal axes (columns, by decreasing variance, right-handed) and the standard deviations.
std::pair<Mat3, Vec3> principalAxes(const MatX3& P) {
  const Eigen::RowVector3d c = P.colwise().mean();
  const MatX3 Q = P.rowwise() - c;
  const Mat3 C = Q.transpose() * Q / std::max<double>(1.0, static_cast<double>(P.rows()));
  Eigen::SelfAdjointEigenSolver<Mat3> es(C);
  Mat3 E;
  Vec3 sd;
  for (int k = 0; k < 3; ++k) {
    E.col(k) = es.eigenvectors().col(2 - k);
    sd(k) = std::sqrt(std::max(0.0, es.eigenvalues()(2 - k)));
  }
  // Deterministic signs: each axis points to where the larger part of the points lies along it.
  for (int k = 0; k < 3; ++k) {
    double third = 0.0;
    for (int i = 0; i < Q.rows(); ++i) third += std::pow(Q.row(i).dot(E.col(k)), 3);
    if (third < 0) E.col(k) = -E.col(k);
  }
  if (E.determinant() < 0) E.col(2) = -E.col(2);
  return {E, sd};
}

// The target: the skin piece in cm, with a closest-point locator and its boundary vertices.
struct Target {
  MatX3 V;  // all vertices, cm
  MatX3i F; // the skin's triangles
  MatX3 N;  // vertex normals of the skin
  std::vector<char> boundary;
  std::vector<int> skinIds;  // skin vertices
  const SurfaceLocator* loc = nullptr;
};

struct Match {
  Vec3 point, normal;
  double distance;
  bool onBoundary;
};

Match match(const Target& tg, const Vec3& p) {
  const SurfacePoint sp = tg.loc->closest(p);
  Match m{sp.point, sp.normal, sp.distance, false};
  bool allBoundary = true;
  for (int k = 0; k < 3; ++k)
    if (sp.barycentric(k) > 1e-6 && !tg.boundary[tg.F(sp.triangle, k)]) allBoundary = false;
  m.onBoundary = allBoundary;
  return m;
}

// A label's vertex: the skin vertex nearest the surface point closest to p, searched over every
// skin vertex rather than the closest triangle's three (on a coarse mesh's long triangles, such as
// a decimated nose ridge's, a neighbouring triangle's vertex can lie much nearer). A few hundred
// calls per search, each a pass over the skin's vertices.
int labelVertex(const Target& tg, const Vec3& p) {
  const Vec3 c = match(tg, p).point;
  int best = -1;
  double bestD = 1e300;
  for (int v : tg.skinIds) {
    const double d = (tg.V.row(v).transpose() - c).squaredNorm();
    if (d < bestD) {
      bestD = d;
      best = v;
    }
  }
  return best;
}

// Similarity ICP of template points X (with normals NX) onto the target, from `init`. Pairs whose
// normals differ by more than 60° or that land on the target's boundary are left out, and of the
// rest the farthest (1 − keep) fraction. Returns the score: the mean over all points of
// min(d, cap)², with cap for the left-out pairs.
double similarityIcp(const Target& tg, const MatX3& X, const MatX3& NX, Similarity& T, int iterations,
                     double keep, double cap, double minScale, double maxScale) {
  const int n = static_cast<int>(X.rows());
  std::vector<Match> m(n);
  std::vector<char> ok(n);
  double score = 0.0;
  for (int it = 0; it <= iterations; ++it) {
    std::vector<double> d;
    d.reserve(n);
    score = 0.0;
    for (int i = 0; i < n; ++i) {
      const Vec3 p = T.apply(X.row(i).transpose());
      m[i] = match(tg, p);
      const Vec3 nrm = T.R * NX.row(i).transpose();
      ok[i] = !m[i].onBoundary && nrm.dot(m[i].normal) > 0.5;
      score += ok[i] ? std::min(m[i].distance * m[i].distance, cap * cap) : cap * cap;
      if (ok[i]) d.push_back(m[i].distance);
    }
    score /= std::max(1, n);
    if (it == iterations || d.size() < 10) break;
    std::vector<double> sorted = d;
    const size_t k = std::min(sorted.size() - 1, static_cast<size_t>(keep * static_cast<double>(sorted.size())));
    std::nth_element(sorted.begin(), sorted.begin() + static_cast<long>(k), sorted.end());
    const double limit = sorted[k];
    Eigen::Matrix3Xd src(3, n), dst(3, n);
    int c = 0;
    for (int i = 0; i < n; ++i)
      if (ok[i] && m[i].distance <= limit) {
        src.col(c) = X.row(i).transpose();
        dst.col(c) = m[i].point;
        ++c;
      }
    if (c < 10) break;
    const Eigen::Matrix4d A = Eigen::umeyama(src.leftCols(c), dst.leftCols(c), true);
    Similarity next;
    next.s = A.block<3, 3>(0, 0).col(0).norm();
    next.R = A.block<3, 3>(0, 0) / next.s;
    next.t = A.block<3, 1>(0, 3);
    if (next.s < minScale || next.s > maxScale) {
      // Keep the face's size within a human range: refit the rotation at the clamped scale.
      next.s = std::clamp(next.s, minScale, maxScale);
      const Vec3 cs = src.leftCols(c).rowwise().mean(), cd = dst.leftCols(c).rowwise().mean();
      next.t = cd - next.s * (next.R * cs);
    }
    const double change = (next.R - T.R).norm() + std::abs(next.s - T.s) + (next.t - T.t).norm() * 1e-2;
    T = next;
    if (change < 1e-7) {
      iterations = it + 1;  // one more pass scores the final placement
    }
  }
  return score;
}

struct Template {
  Head head;
  MatX3 V;
  MatX3 N;
  std::vector<std::pair<int, int>> edges;
};

Template makeTemplate(int levels, const Head* custom) {
  Template t;
  if (custom) {
    t.head = *custom;
  } else {
    DefaultHeadOptions o;
    o.subdivisionLevels = levels;
    t.head = loadDefaultHead(o);
  }
  t.V = t.head.mesh.V;
  t.N = vertexNormals(t.V, t.head.mesh.F);
  const MatX3i& F = t.head.mesh.F;
  for (int f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = F(f, k), b = F(f, (k + 1) % 3);
      t.edges.emplace_back(std::min(a, b), std::max(a, b));
    }
  std::sort(t.edges.begin(), t.edges.end());
  t.edges.erase(std::unique(t.edges.begin(), t.edges.end()), t.edges.end());
  return t;
}

// Non-rigid ICP (Amberg et al. 2007, eq. 12): one affine map X_i (4×3) per template vertex,
// minimising α²‖(M ⊗ G) X‖² + ‖W (D X − U)‖², M the edge–vertex incidence, G = diag(1,1,1,γ), D
// the template's homogeneous vertices, U the closest target points, W 1 for a pair with compatible
// normals off the target's boundary, else 0. For each stiffness α of a decreasing schedule it
// solves until X changes by < 1e-4 (at most 3 solves). Returns the deformed template.
MatX3 nonRigidIcp(const Target& tg, const Template& tp, const MatX3& start, const std::vector<double>& alphas,
                  std::vector<double>& residual, std::vector<char>& valid) {
  const int n = static_cast<int>(start.rows());
  const int E = static_cast<int>(tp.edges.size());
  const double gamma = 1.0;
  // Stiffness term (M ⊗ G)ᵀ(M ⊗ G): constant.
  std::vector<Triplet> st;
  st.reserve(static_cast<size_t>(E) * 16);
  for (const auto& [a, b] : tp.edges)
    for (int k = 0; k < 4; ++k) {
      const double g2 = k == 3 ? gamma * gamma : 1.0;
      st.emplace_back(4 * a + k, 4 * a + k, g2);
      st.emplace_back(4 * b + k, 4 * b + k, g2);
      st.emplace_back(4 * a + k, 4 * b + k, -g2);
      st.emplace_back(4 * b + k, 4 * a + k, -g2);
    }
  SparseMat S(4 * n, 4 * n);
  S.setFromTriplets(st.begin(), st.end());
  Eigen::Matrix<double, Eigen::Dynamic, 4> Vh(n, 4);
  Vh.leftCols<3>() = start;
  Vh.col(3).setOnes();
  MatX X = MatX::Zero(4 * n, 3);
  for (int i = 0; i < n; ++i) X.block<3, 3>(4 * i, 0).setIdentity();

  Eigen::SimplicialLDLT<SparseMat> solver;
  bool analysed = false;
  MatX3 cur = start;
  residual.assign(n, 0.0);
  valid.assign(n, 0);
  for (const double alpha : alphas) {
    for (int inner = 0; inner < 3; ++inner) {
      const MatX3 Nc = vertexNormals(cur, tp.head.mesh.F);
      std::vector<Triplet> kt;
      kt.reserve(static_cast<size_t>(n) * 16);
      MatX B = MatX::Zero(4 * n, 3);
      for (int i = 0; i < n; ++i) {
        const Match m = match(tg, cur.row(i).transpose());
        residual[i] = m.distance;
        const bool ok = !m.onBoundary && Nc.row(i).dot(m.normal.transpose()) > 0.5;
        valid[i] = ok;
        // Zero weight keeps the entry, so the pattern (analysed once) never changes.
        const Eigen::Vector4d v = ok ? Eigen::Vector4d(Vh.row(i).transpose()) : Eigen::Vector4d::Zero();
        for (int r = 0; r < 4; ++r) {
          for (int c = 0; c < 4; ++c) kt.emplace_back(4 * i + r, 4 * i + c, v(r) * v(c));
          B.row(4 * i + r) += v(r) * m.point.transpose();
        }
      }
      SparseMat K(4 * n, 4 * n);
      K.setFromTriplets(kt.begin(), kt.end());
      K += alpha * alpha * S;
      if (!analysed) {
        solver.analyzePattern(K);
        analysed = true;
      }
      solver.factorize(K);
      if (solver.info() != Eigen::Success) throw NumericalError("non-rigid ICP: factorisation failed");
      const MatX Xn = solver.solve(B);
      const double change = (Xn - X).norm() / std::sqrt(static_cast<double>(n));
      X = Xn;
      for (int i = 0; i < n; ++i) cur.row(i) = Vh.row(i) * X.block<4, 3>(4 * i, 0);
      if (change < 1e-4) break;
    }
  }
  for (int i = 0; i < n; ++i) residual[i] = match(tg, cur.row(i).transpose()).distance;
  return cur;
}

// The boundary loop (if any) that is the opening between two corner points a and b: its centroid
// lies within 0.35·|a − b| of their midpoint and its length is at most 4·|a − b|.
const std::vector<int>* openingBetween(const std::vector<std::vector<int>>& loops, const MatX3& V,
                                       const Vec3& a, const Vec3& b) {
  const double w = (a - b).norm();
  const Vec3 mid = 0.5 * (a + b);
  const std::vector<int>* best = nullptr;
  double bestD = 0.35 * w;
  for (const auto& loop : loops) {
    Vec3 c = Vec3::Zero();
    double len = 0.0;
    for (size_t i = 0; i < loop.size(); ++i) {
      c += V.row(loop[i]).transpose();
      len += (V.row(loop[i]) - V.row(loop[(i + 1) % loop.size()])).norm();
    }
    c /= static_cast<double>(loop.size());
    const double d = (c - mid).norm();
    if (len <= 4.0 * w && d < bestD) {
      bestD = d;
      best = &loop;
    }
  }
  return best;
}

// The loop vertex farthest along direction dir.
int extremeAlong(const std::vector<int>& loop, const MatX3& V, const Vec3& dir) {
  int best = loop.front();
  for (int v : loop)
    if (V.row(v).dot(dir.transpose()) > V.row(best).dot(dir.transpose())) best = v;
  return best;
}


int nearestOf(const std::vector<int>& loop, const MatX3& V, const Vec3& p) {
  int best = loop.front();
  for (int v : loop)
    if ((V.row(v).transpose() - p).squaredNorm() < (V.row(best).transpose() - p).squaredNorm()) best = v;
  return best;
}

// A face frame from four points (cm): origin the outer eye corners' midpoint, x towards the
// subject's left eye corner, y up (away from the mouth corners' midpoint, orthogonal to x), z out
// of the face. Unit: the eye width along x and z; along y the eye width too, or (byMouth) the
// height of the eye corners above the mouth corners, so that a face longer or shorter for its
// width than the template keeps its proportions. The frame of frontalJawLine and of the lids' and
// brows' placement.
struct EyeFrame {
  Vec3 o = Vec3::Zero(), ex = Vec3::UnitX(), ey = Vec3::UnitY(), ez = Vec3::UnitZ();
  double s = 0.0, sy = 0.0;
  bool ok = false;
  Vec3 to(const Vec3& p) const {
    const Vec3 d = p - o;
    return {d.dot(ex) / s, d.dot(ey) / sy, d.dot(ez) / s};
  }
  Vec3 from(const Vec3& q) const { return o + s * q.x() * ex + sy * q.y() * ey + s * q.z() * ez; }
};

EyeFrame eyeFrame(const Vec3& r, const Vec3& l, const Vec3& mouthR, const Vec3& mouthL, bool byMouth = false) {
  EyeFrame f;
  f.o = 0.5 * (r + l);
  f.s = (l - r).norm();
  if (!(f.s > 0.0)) return f;
  f.ex = (l - r) / f.s;
  Vec3 ey = f.o - 0.5 * (mouthR + mouthL);
  ey -= ey.dot(f.ex) * f.ex;
  if (ey.norm() < 1e-9) return f;
  f.ey = ey.normalized();
  f.ez = f.ex.cross(f.ey);
  f.sy = byMouth ? ey.norm() : f.s;
  f.ok = true;
  return f;
}

// The frame's x axis from every mirror pair of the points found off the jaw line (Multi-PIE 17–67,
// multipieMirror), not from the outer eye corners alone: the sum of the pairs' right-to-left
// differences, so that one corner a few mm off (decimated ICT's 45: 2.6 mm high, the eye opening's
// coarse end) no longer turns the frame (1.6°, the chin 4 mm aside and the jaw's spokes along the
// outline). y is re-orthogonalised; origin and units are kept.
EyeFrame withSymmetricAxis(EyeFrame f, const std::vector<Vec3>& p68) {
  if (!f.ok) return f;
  Vec3 sum = Vec3::Zero();
  for (int k = 17; k < 68; ++k) {
    const int m = multipieMirror(k);
    if (m <= k) continue;
    Vec3 d = p68[static_cast<size_t>(m)] - p68[static_cast<size_t>(k)];
    if (d.dot(f.ex) < 0) d = -d;
    sum += d;
  }
  if (!(sum.norm() > 0.0)) return f;
  f.ex = sum.normalized();
  Vec3 ey = f.ey - f.ey.dot(f.ex) * f.ex;
  f.ey = ey.normalized();
  f.ez = f.ex.cross(f.ey);
  return f;
}

// The frame's x axis along a → b (the subject's right to left), y re-orthogonalised; origin and
// units kept.
EyeFrame withAxisThrough(EyeFrame f, const Vec3& a, const Vec3& b) {
  if (!f.ok || !((b - a).norm() > 0.0)) return f;
  f.ex = (b - a).normalized();
  const Vec3 ey = f.ey - f.ey.dot(f.ex) * f.ex;
  if (!(ey.norm() > 1e-9)) return f;
  f.ey = ey.normalized();
  f.ez = f.ex.cross(f.ey);
  return f;
}

// A boundary loop's centre: the mean of its edges' midpoints weighted by their lengths (the
// polyline's centroid), which moves little when a remeshing drops or adds vertices along the loop,
// unlike any one of its vertices.
Vec3 loopCentre(const std::vector<int>& loop, const MatX3& V) {
  Vec3 c = Vec3::Zero();
  double len = 0.0;
  for (size_t i = 0; i < loop.size(); ++i) {
    const Vec3 a = V.row(loop[i]).transpose(), b = V.row(loop[(i + 1) % loop.size()]).transpose();
    c += 0.5 * (a + b) * (b - a).norm();
    len += (b - a).norm();
  }
  return len > 0.0 ? Vec3(c / len) : Vec3(V.row(loop.front()).transpose());
}

// The share of the angle from the jaw line's end (point 0 or 16) to the chin (8) at which each jaw
// point lies, seen from the outer eye corners' midpoint in a frontal view, on the mean face of
// dlib's 68-point (iBUG 300-W) annotations: OpenFace's normalised template (Amos, Ludwiczuk &
// Satyanarayanan 2016, openface/align_dlib.py TEMPLATE), both halves averaged (angles 180.6°,
// 195.5°, 209.3°, 221.4°, 232.3°, 242.7°, 252.4°, 261.3°, 270° from the subject's right). Not even
// steps: annotators space the points closer towards the chin than along the sides.
constexpr std::array<double, 9> kJawAngleShare = {0.000, 0.167, 0.322, 0.457, 0.579, 0.695, 0.803, 0.903, 1.000};
// The share of the frontal arc length (in the image plane) from the jaw line's end to the chin at
// which each jaw point lies on the same mean face, both halves averaged: nearly even steps. The
// rule jawByAngle = false spaces the points by it; measured worse on ICT's remeshed copies
// (docs/heads.md, "One jaw spacing for both heads", 2026-12-07).
constexpr std::array<double, 9> kJawArcShare = {0.000, 0.126, 0.253, 0.380, 0.506, 0.632, 0.758, 0.882, 1.000};

// The brows' distances from the eye corners' midpoint across the face, in eye widths (17-21 on
// the subject's right, negated; 26-22 mirror them): the mean 68-point face's (OpenFace's template,
// see kJawAngleShare), in the eye frame of its outer eye corners, both halves averaged.
constexpr std::array<double, 5> kMeanFaceBrowX = {0.6665, 0.5615, 0.4205, 0.2760, 0.1385};
// The inner eye corners' (39, 42) distance from that midpoint, likewise (0.2147 and 0.2143).
constexpr double kMeanFaceInnerEyeX = 0.2145;

// The frontmost skin point on the line a + t·dir (largest t), if the line meets the skin: a
// frontal view's point at a's position across the face (mesh/ray_cast.h, per skin triangle).
std::optional<Vec3> frontmostAlong(const Target& tg, const Vec3& a, const Vec3& dir) {
  double bestT = -1e300;
  for (int t = 0; t < tg.F.rows(); ++t)
    if (const auto hit = lineMeetsTriangle(a, dir, tg.V.row(tg.F(t, 0)), tg.V.row(tg.F(t, 1)), tg.V.row(tg.F(t, 2))))
      bestT = std::max(bestT, hit->t);
  if (bestT < -1e299) return std::nullopt;
  return a + bestT * dir;
}

// The jaw line (Multi-PIE 0–16) on the head's frontal outline. Multi-PIE's jaw points are drawn
// on a frontal photograph's face contour, which the built-in template has no label for (its jaw
// labels are its rim, behind and below that contour). In a provisional frame of the found points
// (eye corners, mouth corners; eye widths), the skin's front-facing triangles are rasterised into a
// depth map (0.01 eye widths); along spokes from the eye corners' midpoint (150°–390°, every 1°,
// each starting 0.08 beyond the found points within 0.15 of it) the visible surface is followed
// outward until it turns away from the view (normal · view ≤ 0.08, the crossing interpolated; the
// view tilted from above by 20° times the spoke's downward share, −sin of its angle: 20° under the
// chin, 0° at the sides) or its depth drops by more than 0.1 (an ear or the neck behind it). The
// outline, smoothed over ±10 spokes, runs from its point at 0.1 eye widths above the eye corners on
// each side to the midline; 9 points per half go on it, by angle (byAngle: the mean face's shares,
// kJawAngleShare) or by frontal arc length (the mean face's, kJawArcShare). False (the fit's points
// kept) when too little outline is found.
bool frontalJawLine(const Target& tg, std::vector<int>& lm68, bool byAngle, bool symmetricAxis, bool onRim,
                    const std::optional<std::pair<Vec3, Vec3>>& eyeOpeningCentres, bool onSilhouette) {
  const auto at = [&](int v) { return Vec3(tg.V.row(v).transpose()); };
  EyeFrame fr = eyeFrame(at(lm68[36]), at(lm68[45]), at(lm68[48]), at(lm68[54]));
  if (symmetricAxis) {
    std::vector<Vec3> p68;
    for (int k = 0; k < 68; ++k) p68.push_back(at(lm68[static_cast<size_t>(k)]));
    fr = withSymmetricAxis(fr, p68);
  }
  if (eyeOpeningCentres) fr = withAxisThrough(fr, eyeOpeningCentres->first, eyeOpeningCentres->second);
  if (!fr.ok) return false;
  const Vec3 &o = fr.o, &ex = fr.ex, &ey = fr.ey, &ez = fr.ez;
  const double s = fr.s;
  const int n = static_cast<int>(tg.V.rows());
  MatX3 Q(n, 3), NQ(n, 3);
  for (int v = 0; v < n; ++v) {
    const Vec3 d = (at(v) - o) / s;
    Q.row(v) << d.dot(ex), d.dot(ey), d.dot(ez);
    const Vec3 nv = tg.N.row(v).transpose();
    NQ.row(v) << nv.dot(ex), nv.dot(ey), nv.dot(ez);
  }
  std::vector<int> rimIds;  // the skin's open boundary
  for (int v : tg.skinIds)
    if (tg.boundary[static_cast<size_t>(v)]) rimIds.push_back(v);
  // Depth map: the front-facing triangle nearest the viewer per cell.
  const double H = 0.01, X0 = -1.4, X1 = 1.4, Y0 = -2.2, Y1 = 0.8;
  const int W = static_cast<int>((X1 - X0) / H) + 1, Hh = static_cast<int>((Y1 - Y0) / H) + 1;
  std::vector<double> zb(static_cast<size_t>(W) * Hh, -1e300);
  std::vector<int> tb(static_cast<size_t>(W) * Hh, -1);
  for (int t = 0; t < tg.F.rows(); ++t) {
    const Vec3 a = Q.row(tg.F(t, 0)).transpose(), b = Q.row(tg.F(t, 1)).transpose(), c = Q.row(tg.F(t, 2)).transpose();
    const double det = (b.x() - a.x()) * (c.y() - a.y()) - (c.x() - a.x()) * (b.y() - a.y());
    if (!(det > 1e-12)) continue;  // back-facing or edge-on (counter-clockwise seen from +z faces the viewer)
    const int i0 = std::max(0, static_cast<int>((std::min({a.x(), b.x(), c.x()}) - X0) / H));
    const int i1 = std::min(W - 1, static_cast<int>((std::max({a.x(), b.x(), c.x()}) - X0) / H) + 1);
    const int j0 = std::max(0, static_cast<int>((std::min({a.y(), b.y(), c.y()}) - Y0) / H));
    const int j1 = std::min(Hh - 1, static_cast<int>((std::max({a.y(), b.y(), c.y()}) - Y0) / H) + 1);
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) {
        const double x = X0 + i * H, y = Y0 + j * H;
        const double l1 = ((x - a.x()) * (c.y() - a.y()) - (c.x() - a.x()) * (y - a.y())) / det;
        const double l2 = ((b.x() - a.x()) * (y - a.y()) - (x - a.x()) * (b.y() - a.y())) / det;
        if (l1 < 0 || l2 < 0 || l1 + l2 > 1) continue;
        const double z = a.z() + l1 * (b.z() - a.z()) + l2 * (c.z() - a.z());
        const size_t k = static_cast<size_t>(j) * W + i;
        if (z > zb[k]) {
          zb[k] = z;
          tb[k] = t;
        }
      }
  }
  // The visible surface at (x, y): depth and normal interpolated in the cell's triangle.
  auto sample = [&](double x, double y, double& z, Vec3& nrm) {
    const int i = static_cast<int>(std::lround((x - X0) / H)), j = static_cast<int>(std::lround((y - Y0) / H));
    if (i < 0 || j < 0 || i >= W || j >= Hh) return false;
    const int t = tb[static_cast<size_t>(j) * W + i];
    if (t < 0) return false;
    const int ia = tg.F(t, 0), ib = tg.F(t, 1), ic = tg.F(t, 2);
    const Vec3 a = Q.row(ia).transpose(), b = Q.row(ib).transpose(), c = Q.row(ic).transpose();
    const double det = (b.x() - a.x()) * (c.y() - a.y()) - (c.x() - a.x()) * (b.y() - a.y());
    double l1 = ((x - a.x()) * (c.y() - a.y()) - (c.x() - a.x()) * (y - a.y())) / det;
    double l2 = ((b.x() - a.x()) * (y - a.y()) - (x - a.x()) * (b.y() - a.y())) / det;
    l1 = std::clamp(l1, 0.0, 1.0);
    l2 = std::clamp(l2, 0.0, 1.0 - l1);
    const double l0 = 1.0 - l1 - l2;
    z = l0 * a.z() + l1 * b.z() + l2 * c.z();
    nrm = (l0 * NQ.row(ia) + l1 * NQ.row(ib) + l2 * NQ.row(ic)).transpose().normalized();
    return true;
  };
  const double tilt = 20.0 * std::numbers::pi / 180.0;
  const double turned = 0.08, drop = 0.1, step = 0.005;
  std::vector<Vec3> raw;
  for (int deg = 150; deg <= 390; ++deg) {
    const double th = deg * std::numbers::pi / 180.0;
    const Eigen::Vector2d u(std::cos(th), std::sin(th));
    // The view tilts from above only as far as the spoke points down: under the chin fully, along
    // the sides not at all (there the surface is seen edge-on and its normal's small downward
    // component would decide where the march stops; ICT's point 15 lay 7.8 mm off in depth).
    const double tiltHere = tilt * std::max(0.0, -std::sin(th));
    const Vec3 view(0.0, std::sin(tiltHere), std::cos(tiltHere));
    double r = 0.3;
    for (int k = 17; k < 68; ++k) {
      const Eigen::Vector2d q = Q.row(lm68[static_cast<size_t>(k)]).head<2>().transpose();
      if (std::abs(-q.x() * u.y() + q.y() * u.x()) < 0.15) r = std::max(r, q.dot(u) + 0.08);
    }
    bool have = false, prevOk = false;
    bool leftTheSurface = false;  // no front-facing surface beyond: the march ran off it
    Vec3 last = Vec3::Zero(), prevN = Vec3::Zero();
    double prevZ = 0.0;
    for (; r < 2.5; r += step) {
      double z;
      Vec3 nrm;
      if (!sample(r * u.x(), r * u.y(), z, nrm)) {
        leftTheSurface = true;
        break;
      }
      if (prevOk && z < prevZ - drop) break;
      if (nrm.dot(view) <= turned) {
        if (prevOk && prevN.dot(view) > turned) {
          const double f = (prevN.dot(view) - turned) / (prevN.dot(view) - nrm.dot(view));
          const double rr = r - step * (1.0 - f);
          last = Vec3(rr * u.x(), rr * u.y(), last.z() + f * (z - last.z()));
        }
        break;
      }
      last = Vec3(r * u.x(), r * u.y(), z);
      have = prevOk = true;
      prevN = nrm;
      prevZ = z;
    }
    if (!have) return false;  // a gap in the outline
    // A mask's rim: the march left the front-facing surface (neither turned away nor dropped
    // behind) with the mesh's open boundary near, within the depth band of an outline (0.1 eye
    // widths): there the visible outline is the rim, and the point goes onto its nearest vertex
    // (the built-in head: 223 of 241 spokes, the front-facing part ending 4–6 mm short of the rim
    // where it wraps round the sides).
    if (onRim && leftTheSurface) {
      int bestB = -1;
      double bestD = 0.1 * 0.1;
      for (int b : rimIds) {
        const double d = (Vec3(Q.row(b).transpose()) - last).squaredNorm();
        if (d < bestD) {
          bestD = d;
          bestB = b;
        }
      }
      if (bestB >= 0) last = Q.row(bestB).transpose();
    }
    raw.push_back(last);
  }
  // A jaw point's vertex (search version 7): the vertex nearest its outline point q is kept only
  // where no vertex on the outline lies about as near. Among the skin vertices within twice the
  // nearest one's distance from q (at most 0.1 eye widths, the outline's depth band), those on the
  // mesh's outline seen along the spoke's view — on its silhouette (with triangles facing the view
  // and triangles facing away) or on its open boundary (a mask's rim) — and not behind q, the one
  // nearest q. On a coarse mesh the vertex nearest an outline point can lie inside the outline
  // (decimated ICT's point 6: 4.4 mm from q, 2.7 mm inside it, while the silhouette vertex 5.4 mm
  // away is ICT's given one). "Not behind": the silhouette of a surface seen edge-on also runs
  // along its far side, deeper than the visible outline (decimated ICT's 0, 13 and 16 would go to
  // such vertices, 0 and 16 to 14-15 mm from ICT's points).
  auto jawVertex = [&](const Vec3& q, int spoke) {
    const int v0 = labelVertex(tg, o + s * (q.x() * ex + q.y() * ey + q.z() * ez));
    if (!onSilhouette) return v0;
    const double radius = std::min(0.1, 2.0 * (Vec3(Q.row(v0).transpose()) - q).norm());
    const double r2 = radius * radius;
    const double th = (150 + spoke) * std::numbers::pi / 180.0;  // spoke i is the one at 150° + i
    const double tiltHere = tilt * std::max(0.0, -std::sin(th));
    const Vec3 view(0.0, std::sin(tiltHere), std::cos(tiltHere));
    std::vector<char> front(static_cast<size_t>(n), 0), back(static_cast<size_t>(n), 0);
    for (int t = 0; t < tg.F.rows(); ++t) {
      const Vec3 a = Q.row(tg.F(t, 0)).transpose(), b = Q.row(tg.F(t, 1)).transpose(), c = Q.row(tg.F(t, 2)).transpose();
      if ((a - q).squaredNorm() > r2 && (b - q).squaredNorm() > r2 && (c - q).squaredNorm() > r2) continue;
      const bool faces = (b - a).cross(c - a).dot(view) > 0.0;
      for (int k = 0; k < 3; ++k) (faces ? front : back)[static_cast<size_t>(tg.F(t, k))] = 1;
    }
    int best = v0;
    double bestD = 1e300;
    for (int v : tg.skinIds) {
      const auto vi = static_cast<size_t>(v);
      const bool onOutline = (front[vi] && back[vi]) || (front[vi] && tg.boundary[vi]);
      if (!onOutline || Q(v, 2) < q.z()) continue;
      const double d = (Vec3(Q.row(v).transpose()) - q).squaredNorm();
      if (d <= r2 && d < bestD) {
        bestD = d;
        best = v;
      }
    }
    return best;
  };
  const int m = static_cast<int>(raw.size()), sm = 10;
  std::vector<Vec3> smooth(raw.size());
  for (int i = 0; i < m; ++i) {
    Vec3 acc = Vec3::Zero();
    int c = 0;
    for (int j = std::max(0, i - sm); j <= std::min(m - 1, i + sm); ++j, ++c) acc += raw[static_cast<size_t>(j)];
    smooth[static_cast<size_t>(i)] = acc / c;
  }
  int mid = -1;
  for (int i = 0; i < m; ++i)
    if (smooth[static_cast<size_t>(i)].y() < -0.5 &&
        (mid < 0 || std::abs(smooth[static_cast<size_t>(i)].x()) < std::abs(smooth[static_cast<size_t>(mid)].x())))
      mid = i;
  const double yEnd = 0.1;
  int first = -1, lastI = -1;
  for (int i = 0; i < mid && first < 0; ++i)
    if (smooth[static_cast<size_t>(i)].y() <= yEnd) first = i;
  for (int i = m - 1; i > mid && lastI < 0; --i)
    if (smooth[static_cast<size_t>(i)].y() <= yEnd) lastI = i;
  if (mid < 0 || first < 0 || lastI < 0 || mid - first < 20 || lastI - mid < 20) return false;
  // Point k on the spoke (fractional index, rounded) at the mean face's share of the angle
  // (kJawAngleShare) or of the frontal arc length (kJawArcShare) from the outline's end to the
  // midline.
  auto put = [&](int k, double spoke) {
    const int i = std::clamp(static_cast<int>(std::lround(spoke)), 0, m - 1);
    const Vec3 q = raw[static_cast<size_t>(i)];
    lm68[static_cast<size_t>(k)] = jawVertex(q, i);
  };
  // The spoke at the share g of the smoothed outline's frontal (x, y) arc length from spoke a to b.
  auto spokeAtArc = [&](int a, int b, double g) {
    const int d = b > a ? 1 : -1;
    std::vector<double> L(1, 0.0);
    for (int i = a + d; i != b + d; i += d)
      L.push_back(L.back() + (smooth[static_cast<size_t>(i)] - smooth[static_cast<size_t>(i - d)]).head<2>().norm());
    const double want = g * L.back();
    size_t j = 0;
    while (j + 2 < L.size() && L[j + 1] <= want) ++j;
    const double t = L[j + 1] > L[j] ? std::clamp((want - L[j]) / (L[j + 1] - L[j]), 0.0, 1.0) : 0.0;
    return a + d * (static_cast<double>(j) + t);
  };
  for (int k = 0; k <= 8; ++k) {
    const double f = kJawAngleShare[static_cast<size_t>(k)], g = kJawArcShare[static_cast<size_t>(k)];
    put(k, byAngle ? first + f * (mid - first) : spokeAtArc(first, mid, g));
    put(16 - k, byAngle ? lastI - f * (lastI - mid) : spokeAtArc(lastI, mid, g));
  }
  return true;
}

}  // namespace

AutoLandmarks findLandmarks(const TriMesh& mesh, const AutoLandmarkOptions& options) {
  const std::string& file = mesh.sourcePath;
  auto notAHead = [&](const std::string& why) { return InputError("not a head: " + why, file); };
  if (mesh.triangleCount() == 0) throw notAHead("the mesh has no triangles");
  AutoLandmarks out;

  // Pieces: the skin is the largest by area; eyeballs, teeth and the like are left out.
  int pieces = 0;
  const std::vector<int> label = pieceLabels(mesh, pieces);
  std::vector<double> area(pieces, 0.0);
  for (int t = 0; t < mesh.triangleCount(); ++t)
    area[label[mesh.F(t, 0)]] += triangleArea(mesh.V.row(mesh.F(t, 0)), mesh.V.row(mesh.F(t, 1)),
                                             mesh.V.row(mesh.F(t, 2)));
  const int skin = static_cast<int>(std::max_element(area.begin(), area.end()) - area.begin());
  for (int p = 0; p < pieces; ++p)
    if (p != skin && area[p] > 0.5 * area[skin])
      throw notAHead(fmt::format("the mesh has {} pieces of similar size (the two largest hold {:.0f}% and "
                                 "{:.0f}% of its area): give one head per file",
                                 pieces, 100.0 * area[skin] / (area[skin] + area[p]),
                                 100.0 * area[p] / (area[skin] + area[p])));
  out.otherPieces = pieces - 1;

  Target tg;
  std::vector<int> skinTris;
  for (int t = 0; t < mesh.triangleCount(); ++t)
    if (label[mesh.F(t, 0)] == skin) skinTris.push_back(t);
  tg.F.resize(static_cast<long>(skinTris.size()), 3);
  for (size_t i = 0; i < skinTris.size(); ++i) tg.F.row(static_cast<long>(i)) = mesh.F.row(skinTris[i]);
  for (int v = 0; v < mesh.vertexCount(); ++v)
    if (label[v] == skin) tg.skinIds.push_back(v);
  out.skinVertices = static_cast<int>(tg.skinIds.size());
  MatX3 P(static_cast<long>(tg.skinIds.size()), 3);
  for (size_t i = 0; i < tg.skinIds.size(); ++i) P.row(static_cast<long>(i)) = mesh.V.row(tg.skinIds[i]);

  // Flat: a head is about as deep as it is wide.
  const auto [E, sd] = principalAxes(P);
  if (sd(2) < 0.1 * sd(0))
    throw notAHead(fmt::format("the mesh is flat (its thinnest principal extent is {:.1f}% of its widest; "
                               "a head is about as deep as it is wide)",
                               100.0 * sd(2) / std::max(sd(0), 1e-300)));

  // Units: a head's bounding-box diagonal is 20–80 cm (a face mask ~26 cm, a bust ~60 cm).
  const double diag = (P.colwise().maxCoeff() - P.colwise().minCoeff()).norm();
  LengthUnit unit = LengthUnit::cm;
  double bestLog = 1e300;
  for (const LengthUnit u : {LengthUnit::cm, LengthUnit::m, LengthUnit::mm}) {
    const double l = std::abs(std::log(diag * centimetresPer(u) / 35.0));
    if (l < bestLog) {
      bestLog = l;
      unit = u;
    }
  }
  const double dcm = diag * centimetresPer(unit);
  if (!(dcm >= 10.0 && dcm <= 150.0))
    throw notAHead(fmt::format("its size fits no unit (bounding-box diagonal {:.4g}: a head's is 20-80 cm)", diag));
  if (options.unit && *options.unit != unit)
    throw InputError(fmt::format("head scale: the mesh read in {} has a bounding-box diagonal of {:.3g} cm, "
                                 "a head's is 20-80 cm (in {} it would be {:.3g} cm): probably --units {}",
                                 lengthUnitName(*options.unit), diag * centimetresPer(*options.unit),
                                 lengthUnitName(unit), dcm, lengthUnitName(unit)),
                     file);
  out.unit = unit;
  out.unitInferred = !options.unit.has_value();
  const double cmPer = centimetresPer(unit);

  tg.V = mesh.V * cmPer;
  tg.N = vertexNormals(tg.V, tg.F);
  tg.boundary.assign(mesh.vertexCount(), 0);
  const auto loops = boundaryLoops(tg.F, mesh.vertexCount());
  for (const auto& l : loops)
    for (int v : l) tg.boundary[v] = 1;
  const SurfaceLocator locator(tg.V, tg.F, tg.N);
  tg.loc = &locator;
  const MatX3 Pcm = P * cmPer;

  // Template and its coarse sample: MediaPipe's 468 original vertices (ids 0–467 at every level).
  const Template tp = makeTemplate(options.templateLevels, options.templateHead);
  const int coarseN = 468;
  if (tp.V.rows() < coarseN)
    throw InputError(fmt::format("the template head has {} vertices; it needs at least {}", tp.V.rows(), coarseN),
                     tp.head.mesh.sourcePath);
  // The built-in template's first 468 vertices are MediaPipe's, spread evenly over the face; of
  // another template, 468 at an even stride through its vertex order.
  MatX3 Xc(coarseN, 3), Nc(coarseN, 3);
  for (int i = 0; i < coarseN; ++i) {
    const long v = options.templateHead ? static_cast<long>(i) * tp.V.rows() / coarseN : i;
    Xc.row(i) = tp.V.row(v);
    Nc.row(i) = tp.N.row(v);
  }
  const Vec3 noseT = tp.V.row(tp.head.landmarks.vertex("nose_tip")).transpose();

  // Candidate orientations: the 24 axis-aligned ones (meshes come Y-up or Z-up, facing an axis)
  // and the 24 that map the template's principal axes onto the mesh's.
  const auto [Et, sdt] = principalAxes(tp.V);
  (void)sdt;
  std::vector<Mat3> candidates;
  for (const Mat3& S : axisRotations()) candidates.push_back(S);
  for (const Mat3& S : axisRotations()) candidates.push_back(E * S * Et.transpose());
  // Every candidate: 6 steps on every third of the 468 points; the best four: 15 more on all 468;
  // the best of those: to convergence on every template vertex.
  const double cap = 1.0;  // cm
  MatX3 Xs(coarseN / 3, 3), Ns(coarseN / 3, 3);
  for (int i = 0; i < coarseN / 3; ++i) {
    Xs.row(i) = Xc.row(3 * i);
    Ns.row(i) = Nc.row(3 * i);
  }
  std::vector<std::pair<double, int>> ranked;
  std::vector<Similarity> placed(candidates.size());
  // How far below the top the nose may lie: 2.5 times the template's nose-to-top height (ICT's crown
  // lies 1.6 times the built-in mask's above its nose), so that a neck, shoulders or a chest below
  // the face cannot hold the most forward point.
  const double noseBelowTopMax = 2.5 * (tp.V.col(1).maxCoeff() - noseT.y());
  for (size_t c = 0; c < candidates.size(); ++c) {
    const Mat3& R = candidates[c];
    // Nose tip on the mesh's most forward point along the candidate's facing direction, among the
    // points near enough the top along its up direction.
    Eigen::Index imax = 0;
    const VecX forward = Pcm * R.col(2);
    if (options.noseSeedNearTheTop) {
      const VecX up = Pcm * R.col(1);
      const double top = up.maxCoeff();
      double best = -1e300;
      for (Eigen::Index i = 0; i < forward.size(); ++i)
        if (up(i) >= top - noseBelowTopMax && forward(i) > best) {
          best = forward(i);
          imax = i;
        }
    } else {
      forward.maxCoeff(&imax);
    }
    placed[c].R = R;
    placed[c].t = Pcm.row(imax).transpose() - R * noseT;
    ranked.emplace_back(similarityIcp(tg, Xs, Ns, placed[c], 6, 0.8, cap, 0.6, 1.6), static_cast<int>(c));
  }
  std::sort(ranked.begin(), ranked.end());
  Similarity best;
  double bestScore = 1e300;
  for (size_t r = 0; r < std::min<size_t>(4, ranked.size()); ++r) {
    Similarity T = placed[static_cast<size_t>(ranked[r].second)];
    const double score = similarityIcp(tg, Xc, Nc, T, 15, 0.8, cap, 0.6, 1.6);
    if (score < bestScore - 1e-12) {
      bestScore = score;
      best = T;
    }
  }
  const double fineScore = similarityIcp(tg, tp.V, tp.N, best, 60, 0.9, cap, 0.6, 1.6);
  out.similarityScale = best.s;
  out.placementRmsMm = 10.0 * std::sqrt(fineScore);

  MatX3 start(tp.V.rows(), 3);
  for (int i = 0; i < tp.V.rows(); ++i) start.row(i) = best.apply(tp.V.row(i).transpose()).transpose();
  // A face fits: with the nose in place, most template points lie within 1 cm of the skin.
  // ICT 3.8 mm, the built-in head 2.1 mm, a sphere of radius 9 cm 6.3 mm: 8 mm leaves real heads
  // room; the nose test below catches the smooth shapes that pass.
  if (fineScore > 0.64)
    throw notAHead(fmt::format("no face fits it (the built-in face, best placed, lies {:.1f} mm from the "
                               "surface in root mean square; a head's is under 8 mm)",
                               10.0 * std::sqrt(fineScore)));

  std::vector<double> residual;
  std::vector<char> valid;
  const MatX3 bent = nonRigidIcp(tg, tp, start, options.stiffness, residual, valid);
  double meanRes = 0.0;
  for (double r : residual) meanRes += r;
  out.fitMeanDistanceCm = meanRes / std::max<size_t>(1, residual.size());

  // Labels move by closest point: each template landmark to the skin vertex nearest its bent position.
  const Landmarks& tl = tp.head.landmarks;
  auto transfer = [&](int tv) { return labelVertex(tg, bent.row(tv).transpose()); };
  std::vector<int> lm68(68);
  for (int k = 0; k < 68; ++k) lm68[k] = transfer(tl.multipie68[static_cast<size_t>(k)]);
  std::vector<double> snapCm(68, 0.0);
  const MatX3& V = tg.V;
  auto at = [&](int v) { return Vec3(V.row(v).transpose()); };

  // Openings: eye corners and lid points onto the eye loops, inner lip points onto the mouth loop.
  auto snapOpening = [&](int cornerA, int cornerB, const std::vector<int>& others) {
    const std::vector<int>* loop = openingBetween(loops, V, at(lm68[cornerA]), at(lm68[cornerB]));
    if (!loop) return false;
    const Vec3 dir = (at(lm68[cornerA]) - at(lm68[cornerB])).normalized();
    const int a = extremeAlong(*loop, V, dir), b = extremeAlong(*loop, V, -dir);
    snapCm[cornerA] = (at(a) - at(lm68[cornerA])).norm();
    snapCm[cornerB] = (at(b) - at(lm68[cornerB])).norm();
    lm68[cornerA] = a;
    lm68[cornerB] = b;
    for (int k : others) {
      const int v = nearestOf(*loop, V, at(lm68[k]));
      snapCm[k] = (at(v) - at(lm68[k])).norm();
      lm68[k] = v;
    }
    return true;
  };
  const std::vector<int> lmFit = lm68;
  const bool rightEye = snapOpening(36, 39, {37, 38, 40, 41});
  const bool leftEye = snapOpening(45, 42, {43, 44, 46, 47});
  out.eyesOpen = rightEye && leftEye;
  out.mouthOpen = snapOpening(60, 64, {61, 62, 63, 65, 66, 67});
  if (!options.snapToOpenings) {
    lm68 = lmFit;
    std::fill(snapCm.begin(), snapCm.end(), 0.0);
  }

  // The outer eye corners onto the ends of the eye openings (where the mesh has them): the loop's
  // vertex farthest along the fitted inner-to-outer corner direction.
  if (options.outerEyeCornersOnOpenings)
    for (const auto& [outer, inner] : {std::pair{36, 39}, std::pair{45, 42}})
      if (const std::vector<int>* loop = openingBetween(loops, V, at(lmFit[outer]), at(lmFit[inner])))
        lm68[outer] = extremeAlong(*loop, V, (at(lmFit[outer]) - at(lmFit[inner])).normalized());

  // Lids and brows at the template's own positions in the eye frame of the found corners: on a
  // smooth brow, or a lid over an opening, the fit slides, while where these points lie in a
  // frontal view relative to the eye and mouth corners varies little between faces. Each point
  // keeps its fitted depth and goes to the skin vertex nearest (x, y, depth) in that frame.
  std::vector<char> fromEyeFrame(68, 0);
  if (options.lidsAndBrowsFromEyeFrame) {
    const auto tAt = [&](int k) { return Vec3(tp.V.row(tl.multipie68[static_cast<size_t>(k)]).transpose()); };
    const EyeFrame tf = eyeFrame(tAt(36), tAt(45), tAt(48), tAt(54), true);
    const EyeFrame f = eyeFrame(at(lm68[36]), at(lm68[45]), at(lm68[48]), at(lm68[54]), true);
    if (tf.ok && f.ok)
      for (int k : {17, 18, 19, 20, 21, 22, 23, 24, 25, 26, 37, 38, 40, 41, 43, 44, 46, 47}) {
        const Vec3 q = tf.to(tAt(k)), p = f.to(at(lm68[k]));
        lm68[k] = labelVertex(tg, f.from(Vec3(q.x(), q.y(), p.z())));
        fromEyeFrame[static_cast<size_t>(k)] = 1;
      }
  }
  // The nose bridge's inner points (28, 29) at a third and two thirds of the way from the nasion
  // (27) to the tip (30), as on the mean 68-point face (OpenFace's template, see kJawAngleShare:
  // its 27-30 are 0.078, 0.078, 0.079 apart in height). On a smooth ridge the fit slides along it
  // (decimated ICT: 28 and 29 on one vertex); the line between 27 and 30 lies just under the ridge,
  // so its closest surface point is on the ridge.
  if (options.noseBridgeAtThirds) {
    const Vec3 nasion = at(lm68[27]), tip = at(lm68[30]);
    lm68[28] = labelVertex(tg, nasion + (tip - nasion) / 3.0);
    lm68[29] = labelVertex(tg, nasion + 2.0 * (tip - nasion) / 3.0);
  }
  // The outline's across direction from the two eye openings' centres (search version 6): the outer
  // corner is one loop vertex, and where a remeshing drops the corner's vertex the next one along
  // the lid is taken (decimated ICT's 45: 2.9 mm off, 2.6 mm high), which turned the frame 1.6° and
  // slid the spokes along the outline; the loops' centres barely move.
  std::optional<std::pair<Vec3, Vec3>> eyeCentres;
  if (options.jawFrameFromEyeOpenings) {
    const std::vector<int>* right = openingBetween(loops, V, at(lmFit[36]), at(lmFit[39]));
    const std::vector<int>* left = openingBetween(loops, V, at(lmFit[45]), at(lmFit[42]));
    if (right && left && right != left) eyeCentres = std::pair{loopCentre(*right, V), loopCentre(*left, V)};
  }
  const bool jawOnOutline = options.jawOnOutline && frontalJawLine(tg, lm68, options.jawByAngle, options.jawFrameFromMirrorPairs,
                                                                   options.jawOnRim, eyeCentres, options.jawVertexOnSilhouette);

  // The brows (17-26) seen from the front: across, at the mean 68-point face's positions in the eye
  // frame (kMeanFaceBrowX); up, at the template's; in depth, on the skin a frontal view sees there
  // (the frontmost skin point along the frame's z). The template's brows sit up to 3 mm from the
  // mean face's across (its inner ends farther apart), and the fitted depth, kept before, lies in
  // front of the skin where the brow's end turns back (ICT's point 17: 3.9 mm). The mean face's
  // heights are not taken: in photographs they move with the head's pitch (the brows stand ~2 cm
  // in front of the eye corners), its widths do not. After the jaw line, whose outline search
  // starts beyond the points already found.
  //
  // The inner eye corners (39, 42) likewise: across at the mean face's positions (kMeanFaceInnerEyeX),
  // at their fitted height, in depth on the skin seen from the front. The fit leaves them ~1 mm
  // towards the nose on ICT (its caruncle region is smooth), and the opening's end lies 2.9 mm
  // lateral of them; the rig's eyeWide follows them (docs/heads.md, "End to end").
  if (options.innerEyeCornersSeenFromTheFront) {
    const EyeFrame f = eyeFrame(at(lm68[36]), at(lm68[45]), at(lm68[48]), at(lm68[54]), true);
    if (f.ok)
      for (int k : {39, 42}) {
        const double x = k == 39 ? -kMeanFaceInnerEyeX : kMeanFaceInnerEyeX;
        if (const std::optional<Vec3> hit = frontmostAlong(tg, f.from(Vec3(x, f.to(at(lm68[k])).y(), 0.0)), f.ez))
          lm68[static_cast<size_t>(k)] = labelVertex(tg, *hit);
      }
  }
  if (options.browsSeenFromTheFront && fromEyeFrame[17]) {
    const auto tAt = [&](int k) { return Vec3(tp.V.row(tl.multipie68[static_cast<size_t>(k)]).transpose()); };
    const EyeFrame tf = eyeFrame(tAt(36), tAt(45), tAt(48), tAt(54), true);
    const EyeFrame f = eyeFrame(at(lm68[36]), at(lm68[45]), at(lm68[48]), at(lm68[54]), true);
    for (int k = 17; k <= 26; ++k) {
      const auto side = static_cast<size_t>(k <= 21 ? k - 17 : 26 - k);
      const double x = k <= 21 ? -kMeanFaceBrowX[side] : kMeanFaceBrowX[side];
      const double y = tf.to(tAt(k)).y();
      const std::optional<Vec3> hit = frontmostAlong(tg, f.from(Vec3(x, y, 0.0)), f.ez);
      lm68[static_cast<size_t>(k)] = labelVertex(tg, hit ? *hit : f.from(Vec3(x, y, f.to(at(lm68[k])).z())));
    }
  }

  // Confidence: the share of the template's vertices within 1.5 cm of the landmark that found a
  // compatible skin point, times exp(−(d/2 mm)²) for the bent landmark's distance d to the skin and
  // exp(−(s/5 mm)²) for the distance s it was snapped by.
  auto confidence = [&](int tv, double snap) {
    int near = 0, ok = 0;
    for (int i = 0; i < bent.rows(); ++i)
      if ((bent.row(i) - bent.row(tv)).squaredNorm() < 1.5 * 1.5) {
        ++near;
        ok += valid[i];
      }
    const double share = near ? static_cast<double>(ok) / near : 0.0;
    return share * std::exp(-std::pow(residual[tv] / 0.2, 2)) * std::exp(-std::pow(snap / 0.5, 2));
  };
  out.confidence68.resize(68);
  for (int k = 0; k < 68; ++k) out.confidence68[k] = confidence(tl.multipie68[static_cast<size_t>(k)], snapCm[k]);
  // A lid point placed from the eye frame is as certain as its eye's corners (its template vertex
  // lies over the opening, where the fit finds no skin).
  for (int k : {37, 38, 40, 41, 43, 44, 46, 47})
    if (fromEyeFrame[static_cast<size_t>(k)])
      out.confidence68[k] = k < 42 ? std::min(out.confidence68[36], out.confidence68[39])
                                   : std::min(out.confidence68[42], out.confidence68[45]);
  // The jaw line is the least certain part (see the warning below): its confidence at most 0.45
  // (drawn yellow), before the named points on it (chin_menton) take theirs.
  for (int k = 0; k <= 16; ++k) out.confidence68[k] = std::min(out.confidence68[k], jawOnOutline ? 0.45 : 0.3);

  // Named points: a template name on one of its Multi-PIE vertices takes that point's result.
  out.landmarks.multipie68 = lm68;
  for (const auto& [name, tv] : tl.named) {
    const auto it = std::find(tl.multipie68.begin(), tl.multipie68.end(), tv);
    if (it != tl.multipie68.end()) {
      const auto k = static_cast<size_t>(it - tl.multipie68.begin());
      out.landmarks.named[name] = lm68[k];
      out.namedConfidence[name] = out.confidence68[k];
    } else {
      out.landmarks.named[name] = transfer(tv);
      out.namedConfidence[name] = confidence(tv, 0.0);
    }
  }
  out.landmarks.sourcePath = mesh.sourcePath.empty() ? "<automatic landmarks>" : mesh.sourcePath + " (automatic landmarks)";
  out.frame = faceFrame(mesh.V, out.landmarks);
  // A nose: the tip stands 0.44–0.45 eye widths in front of the outer eye corners on ICT and the
  // built-in head; a smooth shape the face was bent onto has none.
  const double nose = out.frame.toFrame(Vec3(mesh.V.row(out.landmarks.vertex("nose_tip")).transpose())).z();
  if (nose < 0.25)
    throw notAHead(fmt::format("no nose (the tip found stands {:.2f} eye widths in front of the outer eye corners; "
                               "a face's nose 0.4-0.5)",
                               nose));

  if (!out.eyesOpen)
    out.warnings.push_back(std::string(rightEye || leftEye ? "one eye has" : "the eyes have") +
                           " no opening: no lids, so blinks do nothing; the eye corners come from the fit alone");
  if (!out.mouthOpen)
    out.warnings.push_back("the mouth has no opening: no lip contact, and the jaw stretches the skin; "
                           "the inner lip points come from the fit alone");
  // The jaw line: on the frontal outline it lies a mean 4.3 mm (max 6.9 mm; search version 4) from
  // ICT's given points, on the template's rim (the fallback when no outline is found) 15 mm
  // (docs/heads.md). Either way it is the least certain part: said, and its confidence capped above.
  out.warnings.push_back(jawOnOutline
                             ? "the jaw line (Multi-PIE points 0-16) is placed on the face's frontal outline (4 mm "
                               "from the given points on ICT, mean): check it before rig, drive or pose, which build "
                               "the jaw from it"
                             : "the jaw line (Multi-PIE points 0-16) is approximate (no frontal outline was found; the "
                               "template's rim, 15 mm from the given points on ICT): check it before rig, drive or "
                               "pose, which build the jaw from it");
  for (int k = 17; k < 68; ++k)
    if (out.confidence68[k] < 0.5)
      out.warnings.push_back(fmt::format("Multi-PIE point {} (vertex {}) is uncertain (confidence {:.2f}): check it",
                                         k, lm68[k], out.confidence68[k]));
  return out;
}

int multipieMirror(int k) {
  if (k < 0 || k >= 68) throw CheckError("multipieMirror: no Multi-PIE point " + std::to_string(k));
  if (k <= 16) return 16 - k;
  if (k <= 26) return 43 - k;                     // brows 17–21 ↔ 26–22
  if (k <= 30) return k;                          // nose bridge
  if (k <= 35) return 66 - k;                     // nose base 31–35
  static const std::array<int, 12> eyes = {45, 44, 43, 42, 47, 46, 39, 38, 37, 36, 41, 40};
  if (k <= 47) return eyes[static_cast<size_t>(k - 36)];
  if (k <= 54) return 102 - k;                    // outer lips 48–54 (51 on the midline)
  if (k <= 59) return 114 - k;                    // outer lips 55–59 (57 on the midline)
  if (k <= 64) return 124 - k;                    // inner lips 60–64 (62 on the midline)
  return 132 - k;                                 // inner lips 65–67 (66 on the midline)
}

std::vector<std::string> checkGivenLandmarks(const TriMesh& mesh, const Landmarks& given, const AutoLandmarks& found) {
  std::vector<std::string> warnings;
  if (given.multipie68.size() != 68 || found.landmarks.multipie68.size() != 68) return warnings;
  const double mm = 10.0 * centimetresPer(found.unit);
  auto dist = [&](int a, int b) { return mm * (mesh.V.row(a) - mesh.V.row(b)).norm(); };
  // Means over the points off the jaw line (17–67): the automatic jaw points follow the built-in
  // head's rim, 1–3 cm from a frontal jaw line, whichever file is right.
  std::vector<double> asGiven(68, 0.0);
  double m0 = 0.0, m1 = 0.0, mm2 = 0.0;
  for (int k = 0; k < 68; ++k) {
    const int auto_ = found.landmarks.multipie68[static_cast<size_t>(k)];
    const int g = given.multipie68[static_cast<size_t>(k)];
    asGiven[static_cast<size_t>(k)] = dist(g, auto_);
    if (k < 17) continue;
    m0 += asGiven[static_cast<size_t>(k)] / 51.0;
    m1 += (g >= 1 ? dist(g - 1, auto_) : 1e6) / 51.0;
    mm2 += dist(given.multipie68[static_cast<size_t>(multipieMirror(k))], auto_) / 51.0;
  }
  if (m1 < 5.0 && m1 < 0.6 * m0)
    throw InputError(fmt::format("the landmark ids look 1-based (an OBJ's numbering): as given Multi-PIE points 17-67 "
                                 "lie a mean {:.1f} mm from the automatic landmarks, with every id less 1 {:.1f} mm; "
                                 "subtract 1 from every id (vertex ids are 0-based)",
                                 m0, m1),
                     given.sourcePath);
  if (mm2 < 5.0 && mm2 < 0.6 * m0)
    throw InputError(fmt::format("left and right look swapped: as given Multi-PIE points 17-67 lie a mean {:.1f} "
                                 "mm from the automatic landmarks, with each side's labels swapped {:.1f} mm; 'right' and "
                                 "'left' are the subject's (Multi-PIE point 36, right_eye_outer, is on the subject's "
                                 "right, image left)",
                                 m0, mm2),
                     given.sourcePath);
  std::string far;
  int count = 0;
  for (int k = 17; k < 68; ++k)
    if (asGiven[static_cast<size_t>(k)] > 15.0) {
      far += fmt::format("{}{} ({:.1f} mm)", count ? ", " : "", k, asGiven[static_cast<size_t>(k)]);
      ++count;
    }
  if (count)
    warnings.push_back(fmt::format("{}: {} Multi-PIE point(s) lie more than 1.5 cm from the automatic landmarks: {} "
                                   "(check them: myoshell landmarks --picture)",
                                   given.sourcePath.empty() ? "landmarks" : given.sourcePath, count, far));
  return warnings;
}

}  // namespace myo
