#include "myoshell/anatomy/mouth_contact.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "myoshell/core/errors.h"
#include "myoshell/core/portable_math.h"
#include "myoshell/mesh/subdivision.h"

namespace myo {

namespace {

// Frame coordinates in cm (the frame's axes, no scale): where the arch is measured.
Vec3 local(const FaceFrame& f, const Vec3& p) { return f.axes.transpose() * (p - f.origin); }
Vec3 global(const FaceFrame& f, const Vec3& q) { return f.origin + f.axes * q; }

// The arch's ellipse-normalised radius of a local point (1 on the unshrunk ellipse).
double archRadius(const MouthContact& m, const Vec3& q) {
  const double x = q.x() / m.a, z = (q.z() - m.zCentre) / m.b;
  return std::sqrt(x * x + z * z);
}

// How far a local point lies outside the proxies at rest (cm; 0 inside): along the ray from the
// arch's axis and beyond their top or bottom.
double archClearance(const MouthContact& m, const Vec3& q) {
  const double s = archRadius(m, q);
  const Vec3 axis(0.0, q.y(), m.zCentre);
  const double radial = s > 1.0 ? (q - axis).norm() * (1.0 - 1.0 / s) : 0.0;
  const double vertical = std::max({0.0, q.y() - m.upperTop, m.lowerBottom - q.y()});
  return planarLength(radial, vertical);
}

enum class Proxy { None, Upper, Lower };
Proxy proxyAt(const MouthContact& m, const Vec3& q) {
  if (q.y() >= m.yOcclusal && q.y() <= m.upperTop) return Proxy::Upper;
  if (q.y() < m.yOcclusal && q.y() >= m.lowerBottom) return Proxy::Lower;
  return Proxy::None;
}

// Depth inside the arch of a local point (cm along the ray from the axis; ≤ 0 outside), and the
// point pushed out onto it.
double archDepth(const MouthContact& m, const Vec3& q, Vec3* out) {
  const double s = archRadius(m, q);
  if (s >= 1.0 || s == 0.0) return 0.0;
  const Vec3 axis(0.0, q.y(), m.zCentre);
  const Vec3 onArch = axis + (q - axis) / s;
  if (out) *out = onArch;
  return (onArch - q).norm();
}

// The lower proxy lives in the mandible's frame: x ↦ R x + d at weight 1 (jaw.h).
struct Mandible {
  RigidMotion motion;
  Vec3 toRest(const Vec3& p) const { return motion.R.transpose() * (p - motion.d); }
  Vec3 fromRest(const Vec3& p) const { return motion.apply(p); }
  bool atRest() const { return motion.R == Mat3::Identity() && motion.d.isZero(); }
};

// With the jaw open the proxies part: the upper one's bottom (the occlusal plane) and the lower
// one's top face the gap between the teeth, and the way out of a proxy is the nearer of its
// radial depth and its height over that face. Measured radially alone, a vertex inside the arch
// sliding through the face into the gap dropped its whole depth at once: no vertical force held it
// and the penalty's energy jumped there (the lower lip's marginal band at 1, the jaw at 10°: its
// Newton stalled; docs/mouth_contact.md, "The occlusal faces are a way out"). Where the proxies
// meet — the mandible at rest, or where the lower proxy's top does not lie below the face — the face
// is no way out and the depth is the radial one.
constexpr double kGapTolerance = 1e-6;  // cm: the faces meet within this (the turn's round-off)

// Whether the upper proxy's bottom is a way out at local point q's footprint (q in the head frame).
bool upperFaceOpen(const MouthContact& m, const Mandible& jaw, const Vec3& q) {
  if (jaw.atRest()) return false;
  const Vec3 e = local(m.frame, jaw.toRest(global(m.frame, Vec3(q.x(), m.yOcclusal, q.z()))));
  return e.y() > m.yOcclusal + kGapTolerance || archRadius(m, e) >= 1.0;  // above the lower's top, or beside it
}

// Whether the lower proxy's top is a way out at local point r's footprint (r in its rest frame).
bool lowerFaceOpen(const MouthContact& m, const Mandible& jaw, const Vec3& r) {
  if (jaw.atRest()) return false;
  const Vec3 e = local(m.frame, jaw.fromRest(global(m.frame, Vec3(r.x(), m.yOcclusal, r.z()))));
  return e.y() < m.yOcclusal - kGapTolerance || archRadius(m, e) >= 1.0;  // below the upper's face, or beside it
}

double lipViolation(const MouthContact& m, size_t k, const MatX3& P) {
  const auto [up, low] = m.lipPairs[k];
  const double separation = (P.row(up) - P.row(low)).dot(m.frame.axes.col(1).transpose());
  return m.lipBounds[k] - separation;
}

// The teeth's depth at vertex position p (cm) and, when inside, where it goes.
double teethDepth(const MouthContact& m, const Mandible& jaw, const Vec3& p, Vec3* out) {
  const Vec3 q = local(m.frame, p);
  if (proxyAt(m, q) == Proxy::Upper) {
    Vec3 pushed;
    double d = archDepth(m, q, &pushed);
    if (d > 0.0 && q.y() - m.yOcclusal < d && upperFaceOpen(m, jaw, q)) {  // out through the occlusal face
      d = q.y() - m.yOcclusal;
      pushed = Vec3(q.x(), m.yOcclusal, q.z());
    }
    if (d > 0.0 && out) *out = global(m.frame, pushed);
    return d;
  }
  const Vec3 r = local(m.frame, jaw.toRest(p));  // the lower proxy's rest frame
  if (proxyAt(m, r) != Proxy::Lower) return 0.0;
  Vec3 pushed;
  double d = archDepth(m, r, &pushed);
  if (d > 0.0 && m.yOcclusal - r.y() < d && lowerFaceOpen(m, jaw, r)) {
    d = m.yOcclusal - r.y();
    pushed = Vec3(r.x(), m.yOcclusal, r.z());
  }
  if (d > 0.0 && out) *out = jaw.fromRest(global(m.frame, pushed));
  return d;
}

}  // namespace

MouthContact mouthContact(const TriMesh& skin, const Landmarks& landmarks, const JawRig& jaw,
                          const MouthContactSettings& s) {
  if (landmarks.multipie68.size() != 68)
    throw InputError("the mouth's contact needs the 68-point landmarks (lips 48–67)", landmarks.sourcePath);
  const MatX3& V = skin.V;
  MouthContact m;
  m.frame = faceFrame(V, landmarks);
  const double unit = m.frame.scale;
  auto at = [&](int k) { return Vec3(V.row(landmarks.multipie68[static_cast<size_t>(k)]).transpose()); };
  const Vec3 stomion = 0.5 * (at(62) + at(66));
  const Vec3 qs = local(m.frame, stomion);
  m.a = s.archHalfWidth * unit;
  m.b = s.archDepth * unit;
  m.zCentre = qs.z() - s.lipThickness * unit - m.b;
  m.yOcclusal = qs.y();
  m.upperTop = m.yOcclusal + s.upperHeight * unit;
  m.lowerBottom = m.yOcclusal - s.lowerHeight * unit;

  // The tested vertices: near the stomion and within `clearance` of the proxies at rest (a vertex
  // farther out would need a residual that large to reach the teeth); and the shrink that leaves
  // every one of them outside at rest.
  for (Eigen::Index i = 0; i < V.rows(); ++i) {
    const Vec3 p = V.row(i).transpose();
    if ((p - stomion).norm() >= s.reach * unit) continue;
    const Vec3 q = local(m.frame, p);
    if (archClearance(m, q) > s.clearance * unit) continue;
    m.vertices.push_back(static_cast<int>(i));
    // Strictly clear: kRestContactClearance relative to the arch's half-width (contact_report.h).
    if (proxyAt(m, q) != Proxy::None)
      m.shrink = std::min(m.shrink, archRadius(m, q) * (1.0 - kRestContactClearance / s.archHalfWidth));
  }
  m.a *= m.shrink;  // about the ellipse's centre: its front recedes by (1 − k)·b
  m.b *= m.shrink;

  // Lip pairs: each lower-lip vertex near the upper lip, with its nearest upper-lip vertex.
  // Only where the lips part cleanly: inside the inner corners (landmarks 60, 64), the lower lip
  // following the mandible (w ≥ 0.9) and the upper lip not (w ≤ 0.1). At the commissure the lips
  // are one tissue that the corner's muscles move as one; no pair belongs there.
  const double cornerX = 0.5 * (std::abs(local(m.frame, at(60)).x()) + std::abs(local(m.frame, at(64)).x()));
  std::vector<int> upper, lower;
  for (int i : m.vertices) {
    const Vec3 p = V.row(i).transpose();
    if ((p - stomion).norm() >= s.lipRegion * unit || std::abs(local(m.frame, p).x()) >= cornerX) continue;
    if (jaw.weights(i) >= 0.9) lower.push_back(i);
    else if (jaw.weights(i) <= 0.1) upper.push_back(i);
  }
  const Vec3 y = m.frame.axes.col(1);
  auto pair = [&](int u, int l) {
    m.lipPairs.emplace_back(u, l);
    m.lipBounds.push_back(std::min(0.0, (V.row(u) - V.row(l)).dot(y.transpose())) - kRestContactClearance * unit);
  };
  // (1) Where the lips touch at rest: each lower-lip vertex within pairReach of the upper lip.
  for (int l : lower) {
    int best = -1;
    double bestDistance = s.pairReach * unit;
    for (int u : upper) {
      const double d = (V.row(u) - V.row(l)).norm();
      if (d < bestDistance) best = u, bestDistance = d;
    }
    if (best >= 0) pair(best, l);
  }
  // (2) Where they are parted at rest: the mouth opening's edge (the boundary loop through the
  // lips), each lower-edge vertex with the upper-edge vertex nearest across x. Parted lips may close
  // until they meet (bound 0), not cross.
  std::vector<bool> isUpper(static_cast<size_t>(V.rows()), false), isLower(static_cast<size_t>(V.rows()), false);
  for (int u : upper) isUpper[static_cast<size_t>(u)] = true;
  for (int l : lower) isLower[static_cast<size_t>(l)] = true;
  for (const std::vector<int>& loop : boundaryLoops(skin.F, skin.vertexCount())) {
    std::vector<int> upEdge, lowEdge;
    for (int v : loop) {
      if (isUpper[static_cast<size_t>(v)]) upEdge.push_back(v);
      if (isLower[static_cast<size_t>(v)]) lowEdge.push_back(v);
    }
    if (upEdge.empty() || lowEdge.empty()) continue;  // not the mouth
    for (int l : lowEdge) {
      const double x = local(m.frame, V.row(l).transpose()).x();
      int best = upEdge.front();
      for (int u : upEdge)
        if (std::abs(local(m.frame, V.row(u).transpose()).x() - x) <
            std::abs(local(m.frame, V.row(best).transpose()).x() - x))
          best = u;
      if (std::find(m.lipPairs.begin(), m.lipPairs.end(), std::pair<int, int>{best, l}) == m.lipPairs.end()) pair(best, l);
    }
  }
  return m;
}

double teethPenetration(const MouthContact& m, const RigidMotion& mandible, const Vec3& p, Vec3* gradient) {
  const Mandible jaw{mandible};
  // d = ρ (1/s − 1) in the arch's (x, z − z_c) plane: ρ the distance from the axis, s the
  // ellipse-normalised radius; ∇d = (1/s − 1) ∇ρ − (ρ/s²) ∇s, nothing along y.
  auto grad = [&](const Vec3& q) {
    const double x = q.x(), z = q.z() - m.zCentre;
    const double rho = planarLength(x, z), s = archRadius(m, q);
    const double dsx = x / (m.a * m.a * s), dsz = z / (m.b * m.b * s);
    return Vec3((1.0 / s - 1.0) * x / rho - rho / (s * s) * dsx, 0.0, (1.0 / s - 1.0) * z / rho - rho / (s * s) * dsz);
  };
  // The depth fades to 0 over the last tenth of a proxy's height before its outer cap (its top, the
  // lower one's bottom): w(t) = 3τ² − 2τ³, τ = t/β, t the distance inside the cap. Cut off at the
  // cap, a vertex inside the arch would drop its whole penalty crossing it, and the penalty's energy
  // would jump there: its Newton stalled on such a jump (the platysma, ICT; docs/mouth_contact.md).
  // Returns w·d with ∇(w·d) = w ∇d + d w'(t) ∇t, ∇t = ∓ the frame's y (in the lower proxy's frame).
  auto faded = [&](double d, double t, double height, const Vec3& radialGrad, const Vec3& capGrad) {
    const double beta = 0.1 * height, tau = std::clamp(t / beta, 0.0, 1.0);
    const double w = tau * tau * (3.0 - 2.0 * tau), dw = t < beta ? 6.0 * tau * (1.0 - tau) / beta : 0.0;
    if (gradient) *gradient = w * radialGrad + d * dw * capGrad;
    return w * d;
  };
  const Vec3 y = m.frame.axes.col(1);
  const Vec3 q = local(m.frame, p);
  if (proxyAt(m, q) == Proxy::Upper) {
    const double d = archDepth(m, q, nullptr);
    if (d <= 0.0) return 0.0;
    // Out through the occlusal face when it is open and nearer: the height t_o over it, ∇t_o = y.
    const double tFace = q.y() - m.yOcclusal;
    if (tFace < d && upperFaceOpen(m, jaw, q)) return faded(tFace, m.upperTop - q.y(), m.upperTop - m.yOcclusal, y, -y);
    return faded(d, m.upperTop - q.y(), m.upperTop - m.yOcclusal, m.frame.axes * grad(q), -y);
  }
  const Vec3 r = local(m.frame, jaw.toRest(p));
  if (proxyAt(m, r) != Proxy::Lower) return 0.0;
  const double d = archDepth(m, r, nullptr);
  if (d <= 0.0) return 0.0;
  // Out through its top when it is open and nearer: t_o = y_occ − r_y, ∇t_o = −R y.
  const double tFace = m.yOcclusal - r.y();
  if (tFace < d && lowerFaceOpen(m, jaw, r))
    return faded(tFace, r.y() - m.lowerBottom, m.yOcclusal - m.lowerBottom, Vec3(-(mandible.R * y)), mandible.R * y);
  return faded(d, r.y() - m.lowerBottom, m.yOcclusal - m.lowerBottom, mandible.R * (m.frame.axes * grad(r)),
               mandible.R * y);
}

double lipPairViolation(const MouthContact& m, size_t pair, const MatX3& positions) {
  return lipViolation(m, pair, positions);
}

Vec3 archOutward(const MouthContact& m, const Vec3& p) {
  const Vec3 q = local(m.frame, p);
  const Vec3 radial(q.x(), 0.0, q.z() - m.zCentre);
  const double r = radial.norm();
  return r > 0.0 ? Vec3(m.frame.axes * (radial / r)) : Vec3(m.frame.axes.col(2));
}

ContactReport applyMouthContact(const MouthContact& m, const JawRig& jaw, const JawPose& pose, MatX3& P, bool project) {
  if (!project) {
    ContactReport measured;
    measured.maxPenetrationBefore = measured.maxPenetrationAfter = mouthPenetration(m, jaw, pose, P);
    return measured;
  }
  ContactReport report;
  const Eigen::RowVector3d y = m.frame.axes.col(1).transpose();
  for (size_t k = 0; k < m.lipPairs.size(); ++k) {
    const double v = lipViolation(m, k, P);
    if (v <= 0.0) continue;
    report.maxPenetrationBefore = std::max(report.maxPenetrationBefore, v);
    P.row(m.lipPairs[k].first) += 0.5 * v * y;
    P.row(m.lipPairs[k].second) -= 0.5 * v * y;
    report.projected += 2;
  }
  const Mandible mandible{jawMotion(jaw, pose, 1.0)};
  for (int i : m.vertices) {
    Vec3 pushed;
    const double d = teethDepth(m, mandible, P.row(i).transpose(), &pushed);
    if (d <= 0.0) continue;
    report.maxPenetrationBefore = std::max(report.maxPenetrationBefore, d);
    P.row(i) = pushed.transpose();
    ++report.projected;
  }
  report.maxPenetrationAfter = mouthPenetration(m, jaw, pose, P);
  return report;
}

double mouthPenetration(const MouthContact& m, const JawRig& jaw, const JawPose& pose, const MatX3& P) {
  double worst = 0.0;
  for (size_t k = 0; k < m.lipPairs.size(); ++k) worst = std::max(worst, lipViolation(m, k, P));
  const Mandible mandible{jawMotion(jaw, pose, 1.0)};
  for (int i : m.vertices) worst = std::max(worst, teethDepth(m, mandible, P.row(i).transpose(), nullptr));
  return worst;
}

}  // namespace myo
