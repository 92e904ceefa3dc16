#include "myoshell/anatomy/eyelids.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "myoshell/core/check.h"
#include "myoshell/core/curves.h"
#include "myoshell/core/errors.h"
#include "myoshell/core/portable_math.h"
#include "myoshell/head/face_frame.h"
#include "myoshell/mesh/subdivision.h"
#include "myoshell/mesh/surface_paths.h"

namespace myo {

namespace {

// The 68-point indices of one eye: the corners, the two upper and the two lower mid-lid points,
// each mid pair ordered from the inner corner out (so upper[k] lies above lower[k]).
struct EyeLandmarks {
  int inner, outer;
  std::array<int, 2> upper, lower;
};
constexpr std::array<EyeLandmarks, 2> kEyes = {{{39, 36, {38, 37}, {40, 41}},   // the subject's right
                                                {42, 45, {43, 44}, {47, 46}}}};  // the subject's left

void requireLandmarks(const Landmarks& landmarks) {
  if (landmarks.multipie68.size() != 68)
    throw InputError("the eyelids need the 68-point landmarks (eyes 36–47); " +
                     (landmarks.sourcePath.empty() ? std::string("these landmarks") : landmarks.sourcePath) +
                     " has none");
}

Vec3 landmark(const MatX3& V, const Landmarks& l, int k) {
  return V.row(l.multipie68[static_cast<size_t>(k)]).transpose();
}

// Whether a boundary loop of the mesh lies inside one eye's landmark box (face-frame units, a
// little margin above and below the lids).
bool eyeIsOpen(const TriMesh& skin, const Landmarks& l, const FaceFrame& frame, const EyeLandmarks& e,
               const std::vector<std::vector<int>>& loops) {
  const double x0 = frame.toFrame(landmark(skin.V, l, e.inner)).x(), x1 = frame.toFrame(landmark(skin.V, l, e.outer)).x();
  double yLow = std::numeric_limits<double>::infinity(), yHigh = -yLow;
  for (int k : {e.upper[0], e.upper[1], e.lower[0], e.lower[1], e.inner, e.outer}) {
    const double y = frame.toFrame(landmark(skin.V, l, k)).y();
    yLow = std::min(yLow, y);
    yHigh = std::max(yHigh, y);
  }
  const double margin = 0.05;
  for (const std::vector<int>& loop : loops) {
    Vec3 mean = Vec3::Zero();
    for (int v : loop) mean += skin.V.row(v).transpose();
    const Vec3 q = frame.toFrame(Vec3(mean / static_cast<double>(loop.size())));
    if (q.x() > std::min(x0, x1) && q.x() < std::max(x0, x1) && q.y() > yLow - margin && q.y() < yHigh + margin)
      return true;
  }
  return false;
}

// The eye's local coordinates of p about centre c: (x along the axis, elevation φ = atan2(y, z)).
struct EyeFrame {
  Vec3 centre, x, y, z;
  double along(const Vec3& p) const { return (p - centre).dot(x); }
  double elevation(const Vec3& p) const { return std::atan2((p - centre).dot(y), (p - centre).dot(z)); }
  double fromAxis(const Vec3& p) const { return planarLength((p - centre).dot(y), (p - centre).dot(z)); }
};

// A margin path through the landmarks from..via..to, joined shortest edge paths (no repeats).
std::vector<int> marginPath(const TriMesh& skin, const std::vector<int>& stops) {
  std::vector<int> path{stops.front()};
  for (size_t k = 1; k < stops.size(); ++k) {
    const std::vector<int> leg = shortestEdgePath(skin, stops[k - 1], stops[k]);
    if (leg.empty()) throw InputError("the eyelids: the lid landmarks are not connected along the skin");
    path.insert(path.end(), leg.begin() + 1, leg.end());
  }
  return path;
}

// Distance (cm) from p to the polyline through the path's vertices.
double distanceToPath(const MatX3& V, const std::vector<int>& path, const Vec3& p) {
  double best = (p - V.row(path.front()).transpose()).norm();
  for (size_t k = 1; k < path.size(); ++k) {
    const Vec3 a = V.row(path[k - 1]).transpose(), b = V.row(path[k]).transpose();
    const Vec3 ab = b - a;
    const double len2 = ab.squaredNorm();
    const double t = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
    best = std::min(best, (p - (a + t * ab)).norm());
  }
  return best;
}

// A margin over x: its elevation φ(x) and its distance from the axis ρ(x), from the path's
// vertices sorted by x (into `curve`, reusing its storage).
void marginCurve(const MatX3& V, const std::vector<int>& path, const EyeFrame& f, LidMarginCurve& curve) {
  curve.byX.assign(path.begin(), path.end());
  std::sort(curve.byX.begin(), curve.byX.end(), [&](int a, int b) {
    return f.along(V.row(a).transpose()) < f.along(V.row(b).transpose());
  });
  curve.elevation.clear();
  curve.distance.clear();
  for (int v : curve.byX) {
    const Vec3 p = V.row(v).transpose();
    curve.elevation.emplace_back(f.along(p), f.elevation(p));
    curve.distance.emplace_back(f.along(p), f.fromAxis(p));
  }
}

EyeFrame eyeFrame(const EyeLids& lids) {
  return {lids.centre, lids.axis, lids.up, lids.axis.cross(lids.up)};
}

// The palpebral fissure of positions P: both margins over x, and the canthi's x range.
void fissure(const MatX3& P, const EyeLids& lids, const EyeFrame& f, LidFissure& r) {
  marginCurve(P, lids.upperMargin, f, r.upper);
  marginCurve(P, lids.lowerMargin, f, r.lower);
  const double inner = f.along(P.row(lids.upperMargin.front()).transpose());
  const double outer = f.along(P.row(lids.upperMargin.back()).transpose());
  r.xLow = std::min(inner, outer);
  r.xHigh = std::max(inner, outer);
}

// The centre behind the mid-lid landmarks' mean m, along −z, at the depth t where their mean
// distance to it is the radius R (bisection: the mean distance grows with t).
Vec3 eyeballCentre(const std::vector<Vec3>& midLid, const Vec3& z, double radius) {
  Vec3 m = Vec3::Zero();
  for (const Vec3& p : midLid) m += p;
  m /= static_cast<double>(midLid.size());
  auto meanDistance = [&](double t) {
    double sum = 0.0;
    for (const Vec3& p : midLid) sum += (p - (m - t * z)).norm();
    return sum / static_cast<double>(midLid.size());
  };
  double lo = 0.0, hi = 2.0 * radius;
  if (meanDistance(lo) >= radius) return m;  // the lids spread wider than the eyeball: centre at their mean
  for (int it = 0; it < 80; ++it) {
    const double mid = 0.5 * (lo + hi);
    (meanDistance(mid) < radius ? lo : hi) = mid;
  }
  return m - 0.5 * (lo + hi) * z;
}

EyeLids buildEye(const TriMesh& skin, const Landmarks& l, const FaceFrame& frame, int eye, const LidSettings& s) {
  const EyeLandmarks& e = kEyes[static_cast<size_t>(eye)];
  const MatX3& V = skin.V;
  EyeLids lids;
  lids.side = eye == 0 ? "right" : "left";
  lids.axis = frame.axes.col(0);
  lids.up = frame.axes.col(1);
  lids.radius = s.eyeballRadius * frame.scale;
  std::vector<Vec3> midLid;
  for (int k : {e.upper[0], e.upper[1], e.lower[0], e.lower[1]}) midLid.push_back(landmark(V, l, k));
  lids.centre = eyeballCentre(midLid, frame.axes.col(2), lids.radius);
  for (int k = 0; k < 2; ++k)
    lids.gapPairs[static_cast<size_t>(k)] = {l.multipie68[static_cast<size_t>(e.upper[static_cast<size_t>(k)])],
                                             l.multipie68[static_cast<size_t>(e.lower[static_cast<size_t>(k)])]};
  auto id = [&](int k) { return l.multipie68[static_cast<size_t>(k)]; };
  lids.upperMargin = marginPath(skin, {id(e.inner), id(e.upper[0]), id(e.upper[1]), id(e.outer)});
  lids.lowerMargin = marginPath(skin, {id(e.inner), id(e.lower[0]), id(e.lower[1]), id(e.outer)});

  const EyeFrame f = eyeFrame(lids);
  LidFissure rest;
  fissure(V, lids, f, rest);
  const double tu = s.upperTarsus * frame.scale, fu = s.upperFalloff * frame.scale;
  const double tl = s.lowerTarsus * frame.scale, fl = s.lowerFalloff * frame.scale;
  const double reach = std::max(tu + fu, tl + fl);
  const double orbit = s.orbitReach * lids.radius;
  lids.contactRadius = lids.radius;
  lids.lowerShare = s.lowerShare;
  lids.nasalTurn = s.nasalSlide * frame.scale / lids.radius;
  lids.upperGazeFollow = s.upperGazeFollow;
  lids.lowerGazeFollow = s.lowerGazeFollow;
  lids.sideGazeFollow = s.sideGazeFollow;
  for (Eigen::Index i = 0; i < V.rows(); ++i) {
    const Vec3 p = V.row(i).transpose();
    const double fromCentre = (p - lids.centre).norm();
    if (fromCentre < orbit) {
      lids.orbitVertices.push_back(static_cast<int>(i));
      lids.contactRadius = std::min(lids.contactRadius, fromCentre - kRestContactClearance * frame.scale);  // the rest stays clear
    }
    const double x = f.along(p);
    if (x <= rest.xLow || x >= rest.xHigh) continue;  // beyond the canthi the lids do not move
    const double dUp = distanceToPath(V, lids.upperMargin, p), dLow = distanceToPath(V, lids.lowerMargin, p);
    if (std::min(dUp, dLow) >= reach) continue;
    const double phiUp = interpolateLinear(rest.upper.elevation, x), phiLow = interpolateLinear(rest.lower.elevation, x);
    const bool isUpper = f.elevation(p) >= 0.5 * (phiUp + phiLow);
    const double w = isUpper ? 1.0 - smoothStep((dUp - tu) / fu) : 1.0 - smoothStep((dLow - tl) / fl);
    if (w == 0.0) continue;
    lids.lidVertices.push_back(static_cast<int>(i));
    lids.lidWeights.push_back(isUpper ? w : -w);
    lids.raiseAngle.push_back(isUpper ? -s.raiseFraction * std::max(0.0, phiUp - phiLow) * w : 0.0);
  }
  return lids;
}

}  // namespace

std::string lidCloserName(int eye) { return eye == 0 ? "orbicularis_oculi_palpebral_right" : "orbicularis_oculi_palpebral_left"; }
std::string lidRaiserName(int eye) {
  return eye == 0 ? "levator_palpebrae_superioris_right" : "levator_palpebrae_superioris_left";
}

bool LidDrivers::drives(int muscle) const {
  return muscle >= 0 && (muscle == closers[0] || muscle == closers[1] || muscle == raisers[0] || muscle == raisers[1]);
}

LidPose LidDrivers::pose(const VecX& activations) const {
  LidPose p;
  for (size_t eye = 0; eye < 2; ++eye) {
    if (closers[eye] >= 0) p.close[eye] = activations(closers[eye]);
    if (raisers[eye] >= 0) p.raise[eye] = activations(raisers[eye]);
  }
  return p;
}

LidDrivers lidDrivers(const std::vector<std::string>& names) {
  LidDrivers d;
  for (size_t m = 0; m < names.size(); ++m)
    for (int eye = 0; eye < 2; ++eye) {
      if (names[m] == lidCloserName(eye)) d.closers[static_cast<size_t>(eye)] = static_cast<int>(m);
      if (names[m] == lidRaiserName(eye)) d.raisers[static_cast<size_t>(eye)] = static_cast<int>(m);
    }
  return d;
}

bool hasOpenEyes(const TriMesh& skin, const Landmarks& landmarks) {
  if (landmarks.multipie68.size() != 68) return false;
  const FaceFrame frame = faceFrame(skin.V, landmarks);
  const auto loops = boundaryLoops(skin.F, skin.vertexCount());
  return eyeIsOpen(skin, landmarks, frame, kEyes[0], loops) && eyeIsOpen(skin, landmarks, frame, kEyes[1], loops);
}

LidRig lidRig(const TriMesh& skin, const Landmarks& landmarks, const LidSettings& settings) {
  requireLandmarks(landmarks);
  if (!hasOpenEyes(skin, landmarks))
    throw InputError("the eyelids need open eyes (an opening in the mesh between each eye's corner landmarks); "
                     "this head's eyes are closed",
                     landmarks.sourcePath);
  const FaceFrame frame = faceFrame(skin.V, landmarks);
  LidRig rig;
  for (int eye = 0; eye < 2; ++eye) rig.eyes[static_cast<size_t>(eye)] = buildEye(skin, landmarks, frame, eye, settings);
  return rig;
}

EyeClosure measureClosure(const EyeLids& eye, const LidPose& pose, size_t e, const MatX3& positions,
                          LidFissure& fissureNow) {
  EyeClosure k;
  k.close = pose.close[e];
  k.raise = pose.raise[e];
  k.gazePitch = pose.gaze.pitchDeg[e] * M_PI / 180.0;
  k.gazeYaw = pose.gaze.yawDeg[e] * M_PI / 180.0;
  k.gazing = k.gazePitch != 0.0 || k.gazeYaw != 0.0;
  k.moves = k.close != 0.0 || k.raise != 0.0 || k.gazing;
  if (!k.moves) return k;
  // The fissure closed is the one the skin has now (the residual included), so at c = 1 the
  // margins meet whatever the physics did to them.
  const EyeFrame f = eyeFrame(eye);
  fissure(positions, eye, f, fissureNow);
  // The nasal slide turns about the vertical axis through the centre, towards the inner canthus,
  // fading with the fissure's height Δ(x)/Δmax to nothing at the canthi, which the canthal tendons
  // hold (a full slide up to the canthi tore the skin there into a crack).
  k.towardsNose = f.along(positions.row(eye.upperMargin.front()).transpose()) < 0.0 ? -1.0 : 1.0;
  for (size_t e = 0; e < fissureNow.upper.elevation.size(); ++e) {
    const auto& [x, phi] = fissureNow.upper.elevation[e];
    const double gap = phi - interpolateLinear(fissureNow.lower.elevation, x);
    if (gap > k.gapMax) k.gapMax = gap, k.gapTop = e;
  }
  return k;
}

namespace {

// turnLidVertex with the fissure's three readings given: Δ(x) (gap), the margins' ρ step at x and
// Δmax, and whether x lies between the canthi.
Vec3 turnByReadings(const EyeLids& eye, const EyeClosure& k, size_t j, const Vec3& p, bool inside, double gap, double step,
                    double gapMax, Mat3* turn) {
  const double c = k.close, r = k.raise, gazePitch = k.gazePitch, gazeYaw = k.gazeYaw;
  Vec3 d = p - eye.centre;
  const double x = d.dot(eye.axis);
  const double w = eye.lidWeights[j];  // + upper lid, − lower lid
  double alpha = 0.0, kappa = 0.0;     // the turn (radians) and the change of ρ (cm) at c = 1
  double slide = 0.0;                  // Δ(x)/Δmax: the share of the nasal slide and of the gaze's turn
  if ((c != 0.0 || k.gazing) && inside && gapMax > 0.0) slide = std::min(1.0, gap / gapMax);
  if (c != 0.0 && inside) {
    const double share = w > 0.0 ? 1.0 - eye.lowerShare : eye.lowerShare;
    // The gaze turns the upper margin by κ_u·φ_g·s and the lower by κ_l·φ_g·s (below), so it
    // leaves a fissure Δ + (κ_u − κ_l)·φ_g·s: the closure closes that one, and at c = 1 the
    // margins meet wherever the eye looks (closing the rest fissure, they crossed in down-gaze
    // and stayed apart in up-gaze).
    const double narrowing = (eye.upperGazeFollow - eye.lowerGazeFollow) * gazePitch * slide;
    const double closed = gazePitch != 0.0 ? std::max(0.0, gap + narrowing) : gap;
    alpha = share * closed * w;
    kappa = share * step * w;
  }
  // The lids follow the gaze: up-gaze raises them (θ + lowers a point).
  const double follow = w > 0.0 ? eye.upperGazeFollow : eye.lowerGazeFollow;
  const double theta = c * alpha + r * (1.0 - c) * eye.raiseAngle[j] - follow * gazePitch * std::abs(w) * slide;
  const Vec3 across = d - x * eye.axis;  // the part the distance ρ from the axis measures
  const double rho = across.norm();
  if (rho > 0.0) d += (c * kappa / rho) * across;
  Mat3 R = Eigen::AngleAxisd(theta, eye.axis).toRotationMatrix();
  // Turns about `up`: the nasal slide and the gaze's yaw (+ towards the subject's left, +x).
  const double yaw = (c != 0.0 ? k.towardsNose * c * eye.nasalTurn : 0.0) + eye.sideGazeFollow * gazeYaw;
  if (yaw != 0.0) R = Eigen::AngleAxisd(yaw * std::abs(w) * slide, eye.up).toRotationMatrix() * R;
  if (turn) *turn = R;
  return eye.centre + R * d;
}

// A reading of a margin curve (interpolateLinear) at x and its partial derivatives: by x, and by
// its entries' x and value (entry indices i0, i1; one entry outside the curve's range).
struct CurveReading {
  double value = 0.0, byX = 0.0;
  size_t i0 = 0, i1 = 0;
  double byX0 = 0.0, byX1 = 0.0, byY0 = 0.0, byY1 = 0.0;
};
CurveReading readCurve(const std::vector<std::pair<double, double>>& xy, double x) {
  CurveReading c;
  if (x <= xy.front().first || x >= xy.back().first) {
    c.i0 = c.i1 = x <= xy.front().first ? 0 : xy.size() - 1;
    c.value = xy[c.i0].second;
    c.byY0 = 1.0;
    return c;
  }
  const auto upper = std::upper_bound(xy.begin(), xy.end(), x,
                                      [](double value, const std::pair<double, double>& p) { return value < p.first; });
  c.i1 = static_cast<size_t>(upper - xy.begin());
  c.i0 = c.i1 - 1;
  const auto& [x0, y0] = xy[c.i0];
  const auto& [x1, y1] = xy[c.i1];
  const double span = x1 - x0;
  const double t = span > 0.0 ? (x - x0) / span : 0.0;
  c.value = (1.0 - t) * y0 + t * y1;
  c.byY0 = 1.0 - t;
  c.byY1 = t;
  if (span > 0.0) {
    const double slope = (y1 - y0) / span;
    c.byX = slope;
    c.byX0 = slope * (x - x1) / span;
    c.byX1 = -slope * (x - x0) / span;
  }
  return c;
}

}  // namespace

Vec3 turnLidVertex(const EyeLids& eye, const EyeClosure& k, const LidFissure& now, size_t j, const Vec3& p, Mat3* turn) {
  const double x = (p - eye.centre).dot(eye.axis);
  const bool inside = x > now.xLow && x < now.xHigh;
  double gap = 0.0, step = 0.0;
  if ((k.close != 0.0 || k.gazing) && inside)
    gap = std::max(0.0, interpolateLinear(now.upper.elevation, x) - interpolateLinear(now.lower.elevation, x));
  if (k.close != 0.0 && inside) step = interpolateLinear(now.lower.distance, x) - interpolateLinear(now.upper.distance, x);
  return turnByReadings(eye, k, j, p, inside, gap, step, k.gapMax, turn);
}

void turnLidVertexGradient(const EyeLids& eye, const EyeClosure& k, const LidFissure& now, size_t j, const Vec3& p,
                           const Vec3& g, std::vector<std::pair<int, Vec3>>& out) {
  out.clear();
  const EyeFrame f = eyeFrame(eye);
  const double x = f.along(p);
  const bool inside = x > now.xLow && x < now.xHigh;
  const bool readsGap = (k.close != 0.0 || k.gazing) && inside, readsStep = k.close != 0.0 && inside;
  // The readings and their partials (the canthi's x and the slide's sign only switch: no derivative).
  CurveReading up, low, upRho, lowRho;
  double gap = 0.0, step = 0.0;
  if (readsGap) {
    up = readCurve(now.upper.elevation, x);
    low = readCurve(now.lower.elevation, x);
    gap = std::max(0.0, up.value - low.value);
  }
  if (readsStep) {
    upRho = readCurve(now.upper.distance, x);
    lowRho = readCurve(now.lower.distance, x);
    step = lowRho.value - upRho.value;
  }
  // ∂(g·x')/∂(p, Δ, step, Δmax) by forward differences of the turn with those readings given (no
  // fissure measured; the step is ~10⁻⁷ of the readings, the error as small against the test's 10⁻⁵).
  auto turned = [&](const Vec3& pp, double dGap, double dStep, double dMax) {
    return g.dot(turnByReadings(eye, k, j, pp, inside, gap + dGap, step + dStep, k.gapMax + dMax, nullptr));
  };
  const double base = turned(p, 0, 0, 0);
  const double h = 1e-7 * std::max(1.0, (p - eye.centre).norm());
  Vec3 byP;
  for (int a = 0; a < 3; ++a) {
    Vec3 e = Vec3::Zero();
    e(a) = h;
    byP(a) = (turned(p + e, 0, 0, 0) - base) / h;
  }
  const double hs = 1e-7;
  const double byGap = gap > 0.0 ? (turned(p, hs, 0, 0) - base) / hs : 0.0;
  const double byStep = readsStep ? (turned(p, 0, hs, 0) - base) / hs : 0.0;
  const double byMax = readsGap && k.gapMax > 0.0 ? (turned(p, 0, 0, hs) - base) / hs : 0.0;
  // The entries' partials by their vertex's place: x = a·d, φ = atan2(d·y, d·z), ρ = |(d·y, d·z)|.
  auto add = [&](int v, const Vec3& grad) {
    if (grad.squaredNorm() == 0.0) return;
    for (auto& [u, sum] : out)
      if (u == v) {
        sum += grad;
        return;
      }
    out.emplace_back(v, grad);
  };
  // Entry e of a margin curve read through its vertex: with y = ρ sin φ, z = ρ cos φ,
  // ∂x/∂p = a, ∂φ/∂p = (cos φ · y − sin φ · z)/ρ and ∂ρ/∂p = sin φ · y + cos φ · z (the frame's axes).
  auto entry = [&](const LidMarginCurve& curve, size_t e, double byXe, double byPhi, double byRho) {
    const double phi = curve.elevation[e].second, rho = curve.distance[e].second;
    const double sn = std::sin(phi), cs = std::cos(phi);
    Vec3 grad = byXe * f.x;
    if (byPhi != 0.0 && rho > 0.0) grad += (byPhi / rho) * (cs * f.y - sn * f.z);
    if (byRho != 0.0) grad += byRho * (sn * f.y + cs * f.z);
    add(curve.byX[e], grad);
  };
  // Δ = φ_u(x) − φ_l(x) and step = ρ_l(x) − ρ_u(x) through their entries and the vertex's own x.
  double ownX = 0.0;
  if (gap > 0.0) {
    ownX += byGap * (up.byX - low.byX);
    entry(now.upper, up.i0, byGap * up.byX0, byGap * up.byY0, 0.0);
    entry(now.upper, up.i1, byGap * up.byX1, byGap * up.byY1, 0.0);
    entry(now.lower, low.i0, -byGap * low.byX0, -byGap * low.byY0, 0.0);
    entry(now.lower, low.i1, -byGap * low.byX1, -byGap * low.byY1, 0.0);
  }
  if (byStep != 0.0) {
    ownX += byStep * (lowRho.byX - upRho.byX);
    entry(now.lower, lowRho.i0, byStep * lowRho.byX0, 0.0, byStep * lowRho.byY0);
    entry(now.lower, lowRho.i1, byStep * lowRho.byX1, 0.0, byStep * lowRho.byY1);
    entry(now.upper, upRho.i0, -byStep * upRho.byX0, 0.0, -byStep * upRho.byY0);
    entry(now.upper, upRho.i1, -byStep * upRho.byX1, 0.0, -byStep * upRho.byY1);
  }
  // Δmax = φ_u,top − φ_l(x_top), top the upper entry measureClosure found it at.
  if (byMax != 0.0) {
    const size_t top = k.gapTop;
    const CurveReading lowAtTop = readCurve(now.lower.elevation, now.upper.elevation[top].first);
    entry(now.upper, top, -byMax * lowAtTop.byX, byMax, 0.0);
    entry(now.lower, lowAtTop.i0, -byMax * lowAtTop.byX0, -byMax * lowAtTop.byY0, 0.0);
    entry(now.lower, lowAtTop.i1, -byMax * lowAtTop.byX1, -byMax * lowAtTop.byY1, 0.0);
  }
  // The vertex's own row last: its direct turn and its x's reading of the curves (a vertex can also
  // be a margin entry above; add() sums).
  add(eye.lidVertices[j], byP + ownX * f.x);
}

void turnLids(const LidRig& rig, const LidPose& pose, MatX3& positions, std::array<std::vector<Mat3>, 2>* turns,
              LidFissure* scratch) {
  LidFissure local;
  LidFissure& now = scratch ? *scratch : local;
  for (size_t e = 0; e < 2; ++e) {
    const EyeLids& eye = rig.eyes[e];
    if (turns) (*turns)[e].assign(eye.lidVertices.size(), Mat3::Identity());
    const EyeClosure closure = measureClosure(eye, pose, e, positions, now);
    if (!closure.moves) continue;
    for (size_t k = 0; k < eye.lidVertices.size(); ++k) {
      const int i = eye.lidVertices[k];
      positions.row(i) = turnLidVertex(eye, closure, now, k, positions.row(i).transpose(),
                                       turns ? &(*turns)[e][k] : nullptr).transpose();
    }
  }
}

ContactReport applyLids(const LidRig& rig, const LidPose& pose, MatX3& positions, bool project) {
  turnLids(rig, pose, positions);
  ContactReport contact;
  for (size_t e = 0; e < 2; ++e) {
    const EyeLids& eye = rig.eyes[e];
    for (int i : eye.orbitVertices) {
      const Vec3 d = positions.row(i).transpose() - eye.centre;
      const double dist = d.norm();
      if (dist >= eye.contactRadius || dist == 0.0) continue;
      const double depth = eye.contactRadius - dist;
      contact.maxPenetrationBefore = std::max(contact.maxPenetrationBefore, depth);
      if (!project) {
        contact.maxPenetrationAfter = std::max(contact.maxPenetrationAfter, depth);
        continue;
      }
      positions.row(i) = (eye.centre + (eye.contactRadius / dist) * d).transpose();
      contact.maxPenetrationAfter =
          std::max(contact.maxPenetrationAfter, eye.contactRadius - (positions.row(i).transpose() - eye.centre).norm());
      ++contact.projected;
    }
  }
  return contact;
}

double lidGap(const LidRig& rig, int eye, const MatX3& positions) {
  MYO_CHECK(eye == 0 || eye == 1, "eye " << eye);
  double sum = 0.0;
  for (const auto& [up, low] : rig.eyes[static_cast<size_t>(eye)].gapPairs)
    sum += (positions.row(up) - positions.row(low)).norm();
  return 0.5 * sum;
}

}  // namespace myo
