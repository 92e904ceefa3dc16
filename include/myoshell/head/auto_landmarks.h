// Automatic landmarks: the 68 Multi-PIE points and the named points of any head mesh, in any
// orientation, position and unit, without a picture, a network or a learned model (docs/heads.md,
// "Automatic landmarks"). The built-in head is the labelled template: it is placed on the mesh by
// a similarity ICP from 48 candidate orientations, bent onto it by non-rigid ICP (Amberg, Romdhani
// & Vetter 2007, "Optimal Step Nonrigid ICP Algorithms for Surface Registration"), and its labels
// move to the mesh's nearest vertices; the outer eye corners go to the ends of the eye openings
// where the mesh has them, the lids and brows to the template's positions in the frame of the found
// eye corners, and the jaw line onto the face's frontal outline.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "myoshell/head/face_frame.h"
#include "myoshell/head/head.h"
#include "myoshell/head/landmarks.h"
#include "myoshell/mesh/tri_mesh.h"

namespace myo {

struct AutoLandmarkOptions {
  // The mesh's length unit; empty: inferred from its size (a head's bounding-box diagonal is
  // 20–80 cm, so m, cm and mm lie a factor 10 apart). A unit given that contradicts the size is an
  // InputError proposing the one that fits.
  std::optional<LengthUnit> unit;
  // Loop levels of the built-in head used as the template (1: 1,790 vertices). Level 2 (6,990)
  // gave the same landmarks on ICT within 0.3 mm at 4× the time.
  int templateLevels = 1;
  // Each candidate orientation's start puts the template's nose tip on the skin's most forward
  // vertex along the candidate's facing direction among those within 2.5 times the template's
  // nose-to-top height of the skin's top along its up direction (a head's nose lies 1.6 times the
  // built-in mask's below the crown on ICT), not over the whole skin. Off: the whole skin, where a
  // head with shoulders or a flared neck has its most forward point on the chest and the placement
  // settles on a wrong face (ICT with its neck flared 2.5 times over 12 cm: 139 mm mean error;
  // on, 2.27 mm, ICT's own). Search version 8; docs/heads.md, "Method", step 4.
  bool noseSeedNearTheTop = true;
  // Another labelled head as the template instead of the built-in one (templateLevels then
  // unused): in cm, +y up, facing +z like the built-in head, one piece, at least 468 vertices,
  // every name the built-in file has. For measuring (the built-in head found with a remeshed copy
  // of itself, docs/heads.md); not owned, must outlive the call.
  const Head* templateHead = nullptr;
  // Move the eye corners and lid points onto the eye openings' boundary loops, the inner lip
  // points onto the mouth's (when the mesh has them). Off: ICT's given points lie on the visible
  // lid and lip lines, not on its loops (which turn into the sockets); on ICT snapping raised the
  // inner lip errors from 1.1–2.5 mm to 3.4–7.0 mm.
  bool snapToOpenings = false;
  // The outer eye corners (Multi-PIE 36, 45) moved to the ends of the eye openings, where the mesh
  // has them. The inner corners stay where the fit puts them: on ICT the inner canthus lies 2.9 mm
  // medial of its opening's end (snapping them raised their error from 1.4 to 3.2 mm).
  bool outerEyeCornersOnOpenings = true;
  // The lid points (37, 38, 40, 41, 43, 44, 46, 47) and the brows (17-26) placed at the template's
  // own positions in the frontal eye frame of the found eye and mouth corners, at their fitted
  // depth (docs/heads.md, "Method").
  bool lidsAndBrowsFromEyeFrame = true;
  // The jaw line (Multi-PIE 0-16) placed on the head's frontal outline (frontalJawLine in
  // auto_landmarks.cpp) instead of the template's jaw labels, which are its rim.
  bool jawOnOutline = true;
  // The outline's frame (its spokes' directions and the midline) turned so that its x axis is the
  // mean right-to-left direction of every mirror pair found off the jaw line (Multi-PIE 17–67),
  // not the outer eye corners' alone. Off: decimated ICT 3.09 / 10.58 → 2.82 / 10.12 mm, but three of
  // ICT's posed copies 6.95 → 8.22 mm at most (docs/heads.md, "Method", step 9).
  bool jawFrameFromMirrorPairs = false;
  // The outline's frame turned so that its x axis runs between the centres of the two eye openings
  // (their boundary loops' length-weighted centroids), where the mesh has both, rather than between
  // the outer eye corners' vertices (origin and unit kept). A remeshing that drops a corner's vertex
  // moves the corner to the next vertex along the lid, but barely moves the loop's centre: decimated
  // ICT 3.09 / 10.58 → 2.73 / 8.69 mm; ICT, its posed copies, Loop once and the built-in heads
  // unchanged (search version 6; docs/heads.md, "Method", step 9).
  bool jawFrameFromEyeOpenings = true;
  // On a mask (a mesh with an open boundary round the face), where the outline march runs off the
  // front-facing surface with the boundary within 0.1 eye widths, the point goes onto the boundary:
  // the visible outline of a mask is its rim (search version 5).
  bool jawOnRim = true;
  // A jaw point's vertex: of the skin vertices within twice the nearest one's distance from its
  // outline point (at most 0.1 eye widths), the nearest on the mesh's outline seen from the front
  // (its silhouette along the spoke's view, or its open boundary) and not behind the point; else
  // the nearest. Off: the nearest vertex (decimated ICT's jaw point 6, 2.7 mm inside the outline:
  // 8.7 mm from ICT's point; on, 0.0 mm). Search version 7; docs/heads.md, "Method", step 9.
  bool jawVertexOnSilhouette = true;
  // Along that outline, the points at the mean 68-point face's angles (seen from the eye corners'
  // midpoint) rather than at its shares of the frontal arc length (nearly even steps). Off: ICT's
  // jaw 4.30 / 6.95 -> 4.35 / 6.95 mm, decimated ICT 3.79 / 6.95 -> 5.32 / 11.39, ICT after one
  // Loop step 4.85 / 7.30 -> 5.62 / 8.04 (docs/heads.md, "One jaw spacing for both heads").
  bool jawByAngle = true;
  // The brows (17-26) across the face at the mean 68-point face's positions in the eye frame, up
  // at the template's, in depth on the skin a frontal view sees there (docs/heads.md, "Method").
  bool browsSeenFromTheFront = true;
  // The inner eye corners (39, 42) across the face at the mean 68-point face's positions, at their
  // fitted height, in depth on the skin a frontal view sees there.
  bool innerEyeCornersSeenFromTheFront = true;
  // The nose bridge's points 28 and 29 at thirds between 27 and 30 (the mean 68-point face's
  // spacing) rather than where the fit leaves them. Off: ICT agrees with the mean face, but the
  // built-in head's own file puts them at 0.44 and 0.64 of the way (docs/heads.md, "Method").
  bool noseBridgeAtThirds = false;
  // The non-rigid ICP's stiffness schedule α (Amberg et al. 2007), decreasing.
  std::vector<double> stiffness = {50, 20, 10, 5, 2, 1};
};

struct AutoLandmarks {
  Landmarks landmarks;               // multipie68 and named, vertex ids of the input mesh
  std::vector<double> confidence68;  // per Multi-PIE point, in [0, 1]
  std::map<std::string, double> namedConfidence;
  FaceFrame frame;                   // faceFrame of the input mesh (its own units)
  LengthUnit unit = LengthUnit::cm;  // the mesh's unit
  bool unitInferred = true;          // false when options.unit gave it
  bool eyesOpen = false;             // both eyes have an opening (a boundary loop between the corners)
  bool mouthOpen = false;            // the mouth has an opening
  int skinVertices = 0;              // vertices of the skin (the largest piece by area)
  int otherPieces = 0;               // other connected pieces (eyeballs, teeth), left out
  double fitMeanDistanceCm = 0.0;    // mean template-to-skin distance after the non-rigid fit
  double similarityScale = 1.0;      // template size relative to the built-in head
  double placementRmsMm = 0.0;       // the best similarity placement's score, √(mean min(d, 1 cm)²), mm
  std::vector<std::string> warnings; // what the model cannot do with this head, uncertain points
};

// Finds the landmarks of `mesh` (any pose and unit; eyeballs, teeth and other pieces beside the
// skin are recognised as separate connected pieces and get no landmarks; vertex order untouched).
// Deterministic: the same mesh gives the same result bit for bit. Throws InputError (file:
// mesh.sourcePath) "not a head: REASON" for a mesh that is flat, has two pieces of similar size,
// has no size a head has in any unit, or on which no face fits.
AutoLandmarks findLandmarks(const TriMesh& mesh, const AutoLandmarkOptions& options = {});

// Multi-PIE point k's mirror partner (the subject's right ↔ left; points on the midline map to
// themselves): jaw k ↔ 16 − k, brows 17 ↔ 26, eyes 36 ↔ 45, lips 48 ↔ 54, …
int multipieMirror(int k);

// Checks a landmark file a user gave against the automatic landmarks of the same mesh (`found`,
// from findLandmarks(mesh)), for the common mistakes (issue 42):
// - ids that look 1-based (read off an OBJ's numbering): with every id less 1, Multi-PIE points
//   17–67 lie a mean under 0.6× their mean distance as given from the automatic ones, and under
//   5 mm → InputError (ICT's file shifted: 6.1 mm as given, 2.7 mm less 1; its file as it is:
//   2.7 mm, 15.5 mm less 1);
// - left and right swapped: the same with each point's label taken from its mirror partner;
// - otherwise a warning naming each point more than 1.5 cm from the automatic one, with its
//   distance. The jaw line (Multi-PIE 0–16) is left out of the warning: the automatic jaw points
//   sit on the built-in head's rim, up to 3 cm from a frontal jaw line (docs/heads.md).
// Needs the 68 points in `given` (returns no warnings without them). Lengths in the mesh's unit,
// reported in mm through `found.unit`.
std::vector<std::string> checkGivenLandmarks(const TriMesh& mesh, const Landmarks& given, const AutoLandmarks& found);

}  // namespace myo
