// Lips that touch rather than pass through (docs/mouth_contact.md; issue 17): the lips against
// teeth proxies, the upper lip against the lower, by a per-vertex projection when a shape is placed.
//
// Teeth proxies. The dental arches with their alveolar bone, as one elliptic cylinder about the
// face frame's y (the midplane's vertical): in face-frame coordinates (x, z) the arch is the inside
// of the ellipse (x/a)² + ((z − z_c)/b)² < k², its front (the incisors' labial face) lipThickness
// behind the stomion, a the arch's half-width, b its depth (incisors to the last molars). The upper
// proxy reaches from the occlusal plane (the stomion's height) up by upperHeight and stays with the
// skull; the lower reaches down by lowerHeight and rides with the mandible (the jaw's motion at
// weight 1, jaw.h). k ≤ 1 shrinks both so that no rest vertex lies inside (the rest is contact-free).
// A vertex inside is pushed out along the ray from the arch's axis (in the lower proxy's case in the
// mandible's frame): not the closest point of the ellipse, but near it over the front where the
// lips touch (the ellipse is 1.6 times deeper than wide).
//
// Lip on lip. The lips are the skin within lipRegion of the stomion and inside the inner mouth
// corners, split by the jaw's weight map (the lower lip follows the mandible, w ≥ 0.9; the upper lip
// w ≤ 0.1; the commissure between is one tissue and gets no pair). Pairs, fixed at rest: where the
// lips touch, each lower-lip vertex within pairReach of the upper lip with its nearest upper-lip
// vertex; where they are parted, each lower-lip vertex of the mouth opening's edge (its boundary
// loop) with the upper edge's vertex nearest across x. A pair's separation along the face frame's y
// may not fall below min(its rest value, 0): a pair that would cross is pushed apart along y, each
// vertex half the way (a one-sided constraint: the lips may part freely, they may not pass through
// each other).
#pragma once

#include <utility>
#include <vector>

#include "myoshell/anatomy/contact_report.h"
#include "myoshell/core/types.h"
#include "myoshell/head/face_frame.h"
#include "myoshell/head/jaw.h"
#include "myoshell/head/landmarks.h"
#include "myoshell/mesh/tri_mesh.h"

namespace myo {

// Face-frame units (fractions of the outer-canthal distance, 8.9 cm on ICT); anatomical
// estimates, not fitted (docs/mouth_contact.md lists their sources).
struct MouthContactSettings {
  double lipThickness = 0.07;  // stomion to the incisors' labial face, ≈ 6 mm
  double archHalfWidth = 0.28; // ≈ 2.5 cm: half the width across the second molars
  double archDepth = 0.45;     // ≈ 4 cm: incisors to the last molars
  double upperHeight = 0.25;   // ≈ 2.2 cm: the upper crowns and the maxilla's alveolar process
  double lowerHeight = 0.25;   // the lower crowns and the mandible's alveolar part
  double reach = 0.5;          // vertices within this of the stomion are tested against the teeth,
  double clearance = 0.2;      // ≈ 1.8 cm: those within this of the proxies at rest
  double lipRegion = 0.35;     // the lips: within this of the stomion
  double pairReach = 0.04;     // ≈ 3.6 mm: a lower-lip vertex this near the upper lip gets a pair
};

struct MouthContact {
  FaceFrame frame;                 // the head's face frame (cm: scale applied to a, b, heights)
  double a = 0.0, b = 0.0;         // cm, the arch ellipse's semi-axes (after the rest shrink k)
  double zCentre = 0.0;            // cm, frame z of the ellipse's centre
  double yOcclusal = 0.0;          // cm, frame y of the occlusal plane (the stomion's)
  double upperTop = 0.0, lowerBottom = 0.0;  // cm, frame y bounds of the proxies
  double shrink = 1.0;             // k: 1, or less when the rest mesh lies inside the arch
  std::vector<int> vertices;       // tested against the teeth
  std::vector<std::pair<int, int>> lipPairs;  // (upper-lip vertex, lower-lip vertex)
  std::vector<double> lipBounds;   // per pair: the least separation along y allowed, cm
};

// The mouth of a head with the 68 landmarks (InputError otherwise) and its jaw's weight map.
MouthContact mouthContact(const TriMesh& skin, const Landmarks& landmarks, const JawRig& jaw,
                          const MouthContactSettings& settings = {});

// Projects `positions` (n×3: the placed skin, the jaw in `pose`) out of the teeth proxies and the
// lips out of each other (pairs first, then the teeth). At rest it moves nothing.
// `project` false (contact off): moves nothing; the report's before and after are the deepest violation.
ContactReport applyMouthContact(const MouthContact& mouth, const JawRig& jaw, const JawPose& pose, MatX3& positions,
                                bool project = true);

// The depth (cm, ≥ 0) of position p inside the teeth proxies, the lower one moved by `mandible`
// (jawMotion at weight 1), as the projection measures it (along the ray from the arch's axis, or with
// the jaw open the height over the occlusal face where that is nearer) but faded to 0 over the last
// tenth of a proxy's height before its outer cap, so the penalty is continuous; and, when inside and
// `gradient` is given, ∂depth/∂p (head space; about unit length over the front).
double teethPenetration(const MouthContact& mouth, const RigidMotion& mandible, const Vec3& p, Vec3* gradient);
// Lip pair k's violation in `positions`: its least allowed separation along the frame's y minus the
// separation (cm; > 0 when the lips cross). Its gradient is −y at the upper vertex, +y at the lower.
double lipPairViolation(const MouthContact& mouth, size_t pair, const MatX3& positions);
// The arch's outward direction at p (head space, unit): from the arch's axis, across y.
Vec3 archOutward(const MouthContact& mouth, const Vec3& p);

// The deepest violation of the mouth's constraints in `positions` (cm; 0 when none).
double mouthPenetration(const MouthContact& mouth, const JawRig& jaw, const JawPose& pose, const MatX3& positions);

}  // namespace myo
