#include "myoshell/muscles/muscle.h"

#include <cmath>
#include <numbers>
#include <optional>
#include <vector>

#include "myoshell/core/check.h"
#include "myoshell/core/errors.h"
#include "myoshell/mesh/closest_point.h"
#include "myoshell/mesh/edge_table.h"
#include "myoshell/mesh/geometry.h"
#include "myoshell/mesh/ray_cast.h"

#include <algorithm>
#include <string>
#include <utility>

namespace myo {

int Muscle::insertionCentre(int k) const {
  return (def.stations - 1) * def.ringNodes + k;
}

namespace {

// Closest points on the head's skin: through the caller's locator when given (the same points,
// found faster), else by brute force.
struct SkinQuery {
  const Head& head;
  const MatX3& normals;  // the skin's vertex normals
  const SurfaceLocator* locator;
  std::vector<char> rimVertex;  // per skin vertex: on a boundary edge (a hole's rim, a mask's edge)
  SurfacePoint operator()(const Vec3& p) const {
    return locator ? locator->closest(p) : closestSurfacePoint(head.mesh.V, head.mesh.F, normals, p);
  }
  // Whether a closest point lies on the rim: every vertex that carries it is a rim vertex.
  bool onRim(const SurfacePoint& c) const {
    for (int k = 0; k < 3; ++k)
      if (c.barycentric(k) > 1e-9 && !rimVertex[static_cast<size_t>(head.mesh.F(c.triangle, k))]) return false;
    return true;
  }
};

std::vector<char> rimVertices(const TriMesh& mesh) {
  std::vector<char> rim(static_cast<size_t>(mesh.vertexCount()), 0);
  for (const Edge& e : buildEdgeTable(mesh.F, mesh.vertexCount()).edges)
    if (e.isBoundary()) rim[static_cast<size_t>(e.v[0])] = rim[static_cast<size_t>(e.v[1])] = 1;
  return rim;
}

// A landmark's vertex moved by a face-frame offset (not projected onto the skin); InputError naming
// the muscle when the head has no such landmark.
Vec3 landmarkMoved(const std::string& landmark, const Vec3& offset, const Head& head, const FaceFrame& frame,
                   const std::string& muscle) {
  if (!head.landmarks.has(landmark))
    throw InputError("muscle '" + muscle + "': the head has no landmark '" + landmark + "'", head.landmarks.sourcePath);
  return Vec3(head.mesh.V.row(head.landmarks.vertex(landmark))) + frame.scale * frame.directionFromFrame(offset);
}

// The anchor's point on the skin: the landmark moved by the frame offset, then projected. Where
// the closest skin is a hole's rim, the anchor lies behind skin that turns away from it (ICT's
// upper lid over its eye opening: both levator palpebrae anchors fell on the opening's rim, a
// 0.05 cm muscle), so it takes the skin in front of it along the face's depth axis, when a ray from
// in front meets skin there; a mask's outer edge beyond which nothing lies keeps the rim point.
// A ring's path points keep their closest points (rimTakesFront false): the palpebral ring's
// upper arc, moved into the lid, left the contact settle unconverged (docs/muscles.md).
SurfacePoint anchorOnSkin(const MuscleAnchor& anchor, const Head& head, const FaceFrame& frame,
                          const SkinQuery& onSkin, const std::string& muscle, bool rimTakesFront = true) {
  const Vec3 moved = landmarkMoved(anchor.landmark, anchor.offset, head, frame, muscle);
  const SurfacePoint closest = onSkin(moved);
  if (!rimTakesFront || !onSkin.onRim(closest)) return closest;
  const Vec3 out = frame.directionFromFrame(Vec3::UnitZ());
  const std::optional<SurfacePoint> front =
      firstRayHit(head.mesh.V, head.mesh.F, onSkin.normals, moved + 2.0 * frame.scale * out, -out);
  return front ? *front : closest;
}

}  // namespace

namespace {

Muscle importMuscle(const MuscleDef& def) {
  Muscle muscle;
  muscle.def = def;
  MYO_CHECK(def.shell, "muscle '" << def.name << "': its OBJ " << def.obj
                                   << " was not read (io/muscle_library_file.h: readMuscleShells)");
  muscle.mesh = *def.shell;
  const int n = muscle.mesh.vertexCount();
  auto check = [&](const std::vector<int>& ids, const char* what) {
    for (int v : ids)
      if (v < 0 || v >= n)
        throw InputError("muscle '" + def.name + "': " + what + " vertex " + std::to_string(v) + " is outside [0, " +
                         std::to_string(n) + ")", def.obj);
  };
  check(def.originNodes, "origin");
  check(def.centralNodes, "central");
  check(def.insertionNodes, "insertion");
  muscle.originNodes = def.originNodes;
  muscle.centralNodes = def.centralNodes;
  auto centroid = [&](const std::vector<int>& ids) {
    Vec3 c = Vec3::Zero();
    for (int v : ids) c += muscle.mesh.V.row(v).transpose();
    return Vec3(c / static_cast<double>(ids.size()));
  };
  muscle.originPoint = centroid(muscle.originNodes);
  muscle.insertionNodes = def.insertionNodes;
  if (muscle.insertionNodes.empty()) {
    // The quarter of the central nodes farthest from the origin.
    std::vector<int> byDistance = muscle.centralNodes;
    std::sort(byDistance.begin(), byDistance.end(), [&](int a, int b) {
      return (Vec3(muscle.mesh.V.row(a)) - muscle.originPoint).norm() > (Vec3(muscle.mesh.V.row(b)) - muscle.originPoint).norm();
    });
    byDistance.resize(std::max<size_t>(1, byDistance.size() / 4));
    muscle.insertionNodes = byDistance;
  }
  muscle.insertionPoint = centroid(muscle.insertionNodes);
  muscle.restLength = (muscle.insertionPoint - muscle.originPoint).norm();
  if (muscle.restLength <= 0.0) throw InputError("muscle '" + def.name + "': insertion and origin coincide", def.obj);
  muscle.contractDirection.resize(static_cast<Eigen::Index>(muscle.centralNodes.size()), 3);
  for (size_t c = 0; c < muscle.centralNodes.size(); ++c) {
    const Vec3 d = muscle.originPoint - Vec3(muscle.mesh.V.row(muscle.centralNodes[c]));
    muscle.contractDirection.row(static_cast<Eigen::Index>(c)) = (d.norm() > 0 ? d.normalized() : Vec3::Zero()).transpose();
  }
  return muscle;
}

// The centre line of a ring muscle: S stations at equal arc length along the polyline through its
// path's skin points (closed: around the loop, station 0 not repeated), each re-projected onto the
// skin and pushed under it at the depth interpolated between the path's anchors.
void ringCentreLine(const MuscleDef& def, const Head& head, const FaceFrame& frame, const SkinQuery& onSkin,
                    std::vector<Vec3>& centre, std::vector<Vec3>& normal) {
  std::vector<Vec3> points;
  std::vector<double> depths;
  for (const MuscleAnchor& a : def.ring.path) {
    points.push_back(anchorOnSkin(a, head, frame, onSkin, def.name, false).point);
    depths.push_back(frame.scale * a.depth);
  }
  if (def.ring.closed) {
    points.push_back(points.front());
    depths.push_back(depths.front());
  }
  std::vector<double> arc(points.size(), 0.0);
  for (size_t k = 1; k < points.size(); ++k) arc[k] = arc[k - 1] + (points[k] - points[k - 1]).norm();
  if (!(arc.back() > 1e-3 * frame.scale)) throw InputError("muscle '" + def.name + "': its ring path has no length on this head");
  const int S = def.stations;
  const int intervals = def.ring.closed ? S : S - 1;
  size_t seg = 0;
  for (int s = 0; s < S; ++s) {
    const double target = arc.back() * s / intervals;
    while (seg + 2 < points.size() && arc[seg + 1] < target) ++seg;
    const double len = arc[seg + 1] - arc[seg];
    const double w = len > 0 ? std::clamp((target - arc[seg]) / len, 0.0, 1.0) : 0.0;
    const SurfacePoint p = onSkin((1 - w) * points[seg] + w * points[seg + 1]);
    normal[static_cast<size_t>(s)] = p.normal;
    centre[static_cast<size_t>(s)] = p.point - ((1 - w) * depths[seg] + w * depths[seg + 1]) * p.normal;
  }
}

// A landmark's mirror twin by name: the side's token swapped (mouth_corner_left ↔
// mouth_corner_right, left_eye_inner ↔ right_eye_inner); a midline landmark is its own twin.
std::string mirroredLandmark(const std::string& name) {
  for (const auto& [from, to] : {std::pair<std::string, std::string>{"left", "right"}, {"right", "left"}}) {
    const size_t at = name.find(from);
    if (at != std::string::npos) return name.substr(0, at) + to + name.substr(at + from.size());
  }
  return name;
}

bool mirrorAnchors(const MuscleAnchor& a, const MuscleAnchor& b) {
  return mirroredLandmark(a.landmark) == b.landmark && a.offset.x() == -b.offset.x() &&
         a.offset.y() == b.offset.y() && a.offset.z() == b.offset.z() && a.depth == b.depth;
}

// Whether a ring is a midline muscle whose definition is its own mirror image: open, its path read
// backwards the mirror of itself anchor by anchor, its two anchors each other's mirror and its
// centre halfway (the mouth's two parts).
bool midlineMirrorRing(const MuscleDef& def) {
  if (def.side != "center" || def.ring.closed || def.ring.centre != 0.5) return false;
  const auto& path = def.ring.path;
  for (size_t k = 0; k < path.size(); ++k)
    if (!mirrorAnchors(path[k], path[path.size() - 1 - k])) return false;
  return mirrorAnchors(def.ring.anchors[0], def.ring.anchors[1]);
}

// The reflection through the face's midplane (the frame's y–z plane through its origin).
Vec3 mirrorPoint(const FaceFrame& frame, const Vec3& p) {
  const Vec3 x = frame.axes.col(0);
  return p - 2.0 * (p - frame.origin).dot(x) * x;
}
Vec3 mirrorDirection(const FaceFrame& frame, const Vec3& d) {
  const Vec3 x = frame.axes.col(0);
  return d - 2.0 * d.dot(x) * x;
}

// A midline ring placed symmetric by construction (docs/muscles.md, "A midline ring is its own
// mirror"): each station and its twin from the other end (s and S − 1 − s) are placed on each side
// independently, so on a head that is not exactly symmetric a point near a rim can land on either
// side of a closest-point tie; each pair is replaced by the mean of the one and the other's mirror
// image through the face's midplane, and its mirror. Neither side is chosen: the rule is the same on
// every head, and on an exactly symmetric head it changes nothing.
void symmetrizeStations(const FaceFrame& frame, std::vector<Vec3>& centre, std::vector<Vec3>& normal) {
  const size_t S = centre.size();
  for (size_t s = 0; s < (S + 1) / 2; ++s) {
    const size_t twin = S - 1 - s;
    const Vec3 c = 0.5 * (centre[s] + mirrorPoint(frame, centre[twin]));
    const Vec3 n = (normal[s] + mirrorDirection(frame, normal[twin])).normalized();
    centre[s] = c;
    normal[s] = n;
    centre[twin] = mirrorPoint(frame, c);
    normal[twin] = mirrorDirection(frame, n);
  }
}

}  // namespace

Muscle buildMuscle(const MuscleDef& def, const Head& head, TubeOrientation orientation, const SurfaceLocator* skin) {
  def.validate();
  if (def.imported()) return importMuscle(def);
  Muscle muscle;
  muscle.def = def;
  const FaceFrame frame = head.frame();
  if (skin)
    MYO_CHECK(skin->vertices().rows() == head.mesh.V.rows() && skin->triangles().rows() == head.mesh.F.rows(),
              "muscle '" << def.name << "': the skin locator is not over this head's mesh");
  const MatX3 normals = skin ? skin->vertexNormals() : vertexNormals(head.mesh.V, head.mesh.F);
  const SkinQuery onSkin{head, normals, skin, rimVertices(head.mesh)};
  const int S = def.stations, R = def.ringNodes;
  std::vector<Vec3> centre(S), normal(S);
  const bool loop = def.isRing() && def.ring.closed;
  if (def.isRing()) {
    ringCentreLine(def, head, frame, onSkin, centre, normal);
    Vec3 c = Vec3::Zero();
    for (int k = 0; k < 2; ++k) {
      const MuscleAnchor& a = def.ring.anchors[static_cast<size_t>(k)];
      const SurfacePoint p = anchorOnSkin(a, head, frame, onSkin, def.name, false);
      c += (k == 0 ? 1.0 - def.ring.centre : def.ring.centre) * (p.point - frame.scale * a.depth * p.normal);
      muscle.hoopEnds[static_cast<size_t>(k)] = p.point;
    }
    const bool symmetric = midlineMirrorRing(def);
    if (def.ring.hoop) {  // the arch's centre of curvature: `radius` behind its front (inside the head)
      const MuscleDef::Ring::Hoop& hoop = *def.ring.hoop;
      const Vec3 front = landmarkMoved(hoop.landmark, hoop.offset, head, frame, def.name);
      muscle.hoopCentre = front - frame.scale * hoop.radius * frame.directionFromFrame(Vec3::UnitZ());
      if (symmetric) muscle.hoopCentre = 0.5 * (muscle.hoopCentre + mirrorPoint(frame, muscle.hoopCentre));
    }
    if (symmetric) {
      symmetrizeStations(frame, centre, normal);
      c = 0.5 * (c + mirrorPoint(frame, c));  // the centre on the midplane
      const Vec3 end = 0.5 * (muscle.hoopEnds[0] + mirrorPoint(frame, muscle.hoopEnds[1]));
      muscle.hoopEnds = {end, mirrorPoint(frame, end)};
    }
    muscle.ringCentre = c;
  } else {
    const SurfacePoint o = anchorOnSkin(def.origin, head, frame, onSkin, def.name);
    const SurfacePoint i = anchorOnSkin(def.insertion, head, frame, onSkin, def.name);
    if (def.pushes) muscle.pushPoint = anchorOnSkin(*def.pushes, head, frame, onSkin, def.name).point;
    if (def.continuesInto) {
      const SurfacePoint c = anchorOnSkin(*def.continuesInto, head, frame, onSkin, def.name);
      muscle.continuePoint = c.point - frame.scale * def.continuesInto->depth * c.normal;
    }
    if ((o.point - i.point).norm() < 1e-3 * frame.scale)
      throw InputError("muscle '" + def.name + "': origin and insertion coincide on this head");

    // Centre line: stations between the two skin points, each re-projected onto the skin so the
    // muscle follows the face's curvature, then pushed under it along the normal (thesis Fig. 10).
    // With a skull, the origin sits on the bone: its depth is the skin-to-skull distance under the
    // origin's skin point (never less than the definition's own depth).
    double originDepth = frame.scale * def.origin.depth;
    if (head.hasSkull()) {
      const MatX3 skullNormals = vertexNormals(head.skull.V, head.skull.F);
      const SurfacePoint bone = closestSurfacePoint(head.skull.V, head.skull.F, skullNormals, o.point);
      originDepth = std::max(originDepth, bone.distance);
    }
    for (int s = 0; s < S; ++s) {
      const double t = static_cast<double>(s) / (S - 1);
      const SurfacePoint p = onSkin((1 - t) * o.point + t * i.point);
      const double depth = (1 - t) * originDepth + t * frame.scale * def.insertion.depth;
      normal[s] = p.normal;
      centre[s] = p.point - depth * p.normal;
    }
  }
  // A loop's neighbours wrap around; an open line's ends use one-sided differences.
  auto station = [&](int s) { return loop ? (s + S) % S : std::clamp(s, 0, S - 1); };
  std::vector<Vec3> tangent(S);
  for (int s = 0; s < S; ++s) tangent[s] = (centre[station(s + 1)] - centre[station(s - 1)]).normalized();

  // Rings: a flat ellipse (width across, thickness along the skin normal); node k at angle
  // π/2 + 2π(k−1)/R, so nodes 1 and 1 + R/2 are the top and bottom middle (the central nodes).
  TriMesh& mesh = muscle.mesh;
  mesh.V.resize(S * R, 3);
  const double halfWidth = 0.5 * def.width * frame.scale, halfThick = 0.5 * def.thickness * frame.scale;
  // A right muscle's `across` is flipped (after `up` is made from it): reflection turns n × t into
  // −(its mirror), so the flip makes node k of the right tube the mirror of node k of the left one.
  const bool flip = orientation == TubeOrientation::MirrorRightSide && def.side == "right";
  for (int s = 0; s < S; ++s) {
    Vec3 across = normal[s].cross(tangent[s]).normalized();
    const Vec3 up = tangent[s].cross(across).normalized();  // the normal made orthogonal to the axis
    if (flip) across = -across;
    for (int k = 0; k < R; ++k) {
      const double angle = std::numbers::pi / 2 + 2 * std::numbers::pi * (k - 1) / R;
      mesh.V.row(s * R + k) = centre[s] + halfWidth * std::cos(angle) * across + halfThick * std::sin(angle) * up;
    }
  }
  // Triangles: two per quad of the tube, fans closing both ends; 2·S·R − 4 in all. A loop joins
  // its last ring to its first instead (a torus, 2·S·R triangles, no ends).
  // A midline ring's second half splits its quads along the other diagonal, the mirror image of the
  // first half's split (docs/muscles.md, "A midline ring is its own mirror"): the same diagonal on
  // both halves is the other one in the mirror, and where the lips' skin lies within a millimetre of
  // the band (the mouth's corners) the closest points and the coupling's 1/δ differed by 4×.
  const bool mirrorSplit = def.isRing() && !loop && midlineMirrorRing(def);
  std::vector<Eigen::Vector3i> tris;
  for (int s = 0; s + 1 < S || (loop && s < S); ++s)
    for (int k = 0; k < R; ++k) {
      const int next = (s + 1) % S;
      const int a = s * R + k, b = s * R + (k + 1) % R, c = next * R + k, d = next * R + (k + 1) % R;
      if (mirrorSplit && 2 * s > S - 2) {  // the quad's mirror lies between stations S − 2 − s and S − 1 − s
        tris.emplace_back(a, b, c);
        tris.emplace_back(b, d, c);
      } else {
        tris.emplace_back(a, b, d);
        tris.emplace_back(a, d, c);
      }
    }
  if (!loop) {
    for (int k = 1; k + 1 < R; ++k) tris.emplace_back(0, k + 1, k);
    const int last = (S - 1) * R;
    for (int k = 1; k + 1 < R; ++k) tris.emplace_back(last, last + k, last + k + 1);
  }
  mesh.F.resize(static_cast<Eigen::Index>(tris.size()), 3);
  for (size_t t = 0; t < tris.size(); ++t) mesh.F.row(static_cast<Eigen::Index>(t)) = tris[t].transpose();
  // Orient outwards: the enclosed volume must be positive.
  double volume = 0.0;
  for (Eigen::Index t = 0; t < mesh.F.rows(); ++t)
    volume += Vec3(mesh.V.row(mesh.F(t, 0))).dot(Vec3(mesh.V.row(mesh.F(t, 1))).cross(Vec3(mesh.V.row(mesh.F(t, 2)))));
  if (volume < 0) mesh.F.col(1).swap(mesh.F.col(2));
  mesh.sourcePath = "<muscle " + def.name + ">";
  muscle.restLength = 0.0;
  for (int s = 0; s + 1 < S || (loop && s < S); ++s) muscle.restLength += (centre[station(s + 1)] - centre[s]).norm();
  muscle.originPoint = centre.front();
  muscle.insertionPoint = centre.back();
  // A ring has no origin, central or insertion nodes: its contraction about its centre is its
  // shape (muscle_coupling.cpp), and only the anatomical model plays it.
  if (def.isRing()) return muscle;

  for (int k = 0; k < R; ++k) muscle.originNodes.push_back(k);
  muscle.contractDirection.resize(2 * (S - 1), 3);
  int row = 0;
  for (int s = 1; s < S; ++s)
    for (int k : {1, 1 + R / 2}) {
      muscle.centralNodes.push_back(s * R + k);
      muscle.contractDirection.row(row++) = -tangent[s].transpose();
    }
  for (int k = 0; k < R; ++k) muscle.insertionNodes.push_back((S - 1) * R + k);
  return muscle;
}

}  // namespace myo
