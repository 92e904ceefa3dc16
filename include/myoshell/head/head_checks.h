// Checks that a head loaded from files is what the face model assumes: a mesh in centimetres with
// landmarks that belong to it (docs/heads.md, "Checks on load"). Pure functions over data: the io
// head loader calls them; the library itself keeps accepting a head in any unit (the face frame
// makes placement unit-invariant, and face_frame_test needs a head in metres).
#pragma once

#include <string>
#include <string_view>

#include "myoshell/core/types.h"
#include "myoshell/head/head.h"
#include "myoshell/head/landmarks.h"
#include "myoshell/mesh/tri_mesh.h"

namespace myo {

// "cm", "m" or "mm" → the unit; anything else throws InputError("unknown length unit 'X' (use m,
// mm or cm)", file) — `file` names where the text came from (an argument, a scene file).
LengthUnit parseLengthUnit(std::string_view text, const std::string& file = {});
const char* lengthUnitName(LengthUnit unit);
// Centimetres per unit: m → 100, mm → 0.1, cm → 1.
double centimetresPer(LengthUnit unit);

// Scales a mesh given in `unit` to cm in place (V ← V · centimetresPer(unit)); cm leaves it as is.
void rescaleToCentimetres(TriMesh& mesh, LengthUnit unit);
// The head's skin and skull (when present) to cm. Landmarks and pins are vertex ids: unchanged.
void rescaleToCentimetres(Head& head, LengthUnit unit);

// Plausible outer-canthus distance of a head in cm, |left_eye_outer − right_eye_outer|: adult
// faces measure 8–10 cm (the default head 8.9 cm, ICT 8.9 cm); the range leaves room for children
// and stylised heads while refusing a head in m (≈ 0.09) or mm (≈ 90).
inline constexpr double kMinOuterCanthusCm = 5.0;
inline constexpr double kMaxOuterCanthusCm = 15.0;

// Throws InputError (file: mesh.sourcePath) when the outer-canthus distance of V (n×3, cm expected)
// lies outside [kMinOuterCanthusCm, kMaxOuterCanthusCm]. The message gives the measured distance,
// what it would be in cm if the file were in m or mm, and proposes `--units m|mm|cm` (scene key
// `head.units`). `unitGiven` is the unit the mesh was converted from, named in the message.
void checkHeadScale(const TriMesh& mesh, const Landmarks& landmarks, LengthUnit unitGiven = LengthUnit::cm);

// The largest angle allowed between the face frame's z and the area-weighted mean normal of the
// face region (triangles within kFaceRegionRadius of the eye corners, nose tip and mouth). It is
// 9.8° on the default head, 11.1° on ICT (the chin–eye line leans back from the face); inward-facing
// triangles give ~180°, the default head's landmarks on ICT's mesh 149°. 45° halves the right angle
// between "the face looks along z" and "the face looks sideways", with 4× the margin of real heads.
inline constexpr double kMaxFrameNormalAngleDeg = 45.0;
// Radius of the face region around each landmark, in face-frame units (outer-canthus distances).
inline constexpr double kFaceRegionRadius = 0.3;

// Throws InputError (file: landmarks.sourcePath) naming the first landmark that does not fit the
// mesh (`mesh` n×3 / m×3 triangles; any unit — the checks are in face-frame coordinates, so they are
// invariant to position, rotation and scale):
// - off the surface: a landmark vertex on no triangle, or on another connected piece of the mesh
//   than the face (the piece holding nose_tip);
// - in the face frame (x subject's left, y up, z out of the face; face_frame.h): the eyes' inner
//   corners between the outer ones and on their sides; mouth corners, brows on the matching side;
//   brows above the eyes; the nose tip below the eyes, above the upper lip and in front of the eye
//   corners and mouth corners; the mouth corners and lip midpoints below the nose tip; the upper lip
//   above the lower lip; the chin below the lower lip;
// - the frame's z within kMaxFrameNormalAngleDeg of the face region's mean normal.
// Requires landmarks.requireAll() to have passed. Scale is not checked here (checkHeadScale).
void checkLandmarksFitMesh(const TriMesh& mesh, const Landmarks& landmarks);

// Both checks, as loaders apply them to a head already converted to cm: landmarks first (so the
// landmarks of another mesh are named as such, not taken for a unit problem), then the scale.
void checkLoadedHead(const Head& head, LengthUnit unitGiven = LengthUnit::cm);

// Measurements behind the checks, for reports and tests.
struct HeadFitMeasures {
  double outerCanthusDistance = 0.0;  // |left_eye_outer − right_eye_outer|, mesh units
  double frameNormalAngleDeg = 0.0;   // angle between the frame's z and the face region's mean normal
  int faceRegionTriangles = 0;        // triangles in the face region
};
HeadFitMeasures measureHeadFit(const TriMesh& mesh, const Landmarks& landmarks);

}  // namespace myo
