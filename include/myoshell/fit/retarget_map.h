// Retargeting maps (docs/fitting.md, "Retargeting maps"): for each ARKit blendshape name, the
// muscle activations (and jaw values, once the model has a jaw) whose settled face makes that shape.
// `myoshell fit-rig` writes one by fitting every shape of a rig; `myoshell rig` reads one and
// simulates every entry on any head. Maps are keyed by muscle names, so they transfer between heads.
//
//   {"format": "myoshell-retarget-map", "version": 1,
//    "rig": "ict_arkit_rig.glb", "head": "ict", "model": "anatomical", "library": "face", "note": "…",
//    "shapes": [
//      {"name": "mouthSmileLeft", "source": "fitted", "activations": {"zygomaticus_major_L": 0.93}, "jaw": {},
//       "fit": {"cosine": 0.81, "magnitude_ratio": 0.9, "rms_mm": 1.2, "max_mm": 4.1}},
//      {"name": "browDownLeft", "source": "derived", "activations": {"corrugator_supercilii_left": 1}, "jaw": {}},
//      {"name": "eyeLookUpLeft", "source": "derived", "activations": {}, "jaw": {}, "gaze": {"left_pitch": 25}},
//      {"name": "mouthClose", "corrective_of": "jawOpen", "activations": {…}},
//      {"name": "eyeLookInLeft", "reachable": false, "reason": "eye rotation: …"}, …]}
//
// Names may be written in ARKit's or ICT's spelling (fit/arkit_names.h) and are stored in ARKit's.
// An activation lies in [0, 1]; a corrective's (`corrective_of`: the shape it is added to, ARKit's
// mouthClose on jawOpen) is the difference from its base's and lies in [−1, 1]. An unreachable shape
// (one muscles cannot make: eye rotation, air) has a reason and no activations. `fit` holds the
// figures the fit reached (optional; informative only). `source` says where a reachable shape's
// values come from: "fitted" to an artist's shape by fit-rig, or "derived" from the shape's FACS
// action units through the FACS map (fit/facs_route.h) where the rig had no such shape; absent, a
// shape is "fitted". `library` names the muscle library the map's activations are for ("builtin",
// "face" or a library file's name; absent in maps written before it was recorded).
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace YAML {
class Node;
}

namespace myo {

struct RetargetFitFigures {
  double cosine = 0.0;
  double magnitudeRatio = 0.0;
  double rmsMm = 0.0;
  double maxMm = 0.0;
};

// Name → value pairs in the file's order (muscle activations, jaw values).
using NamedValues = std::vector<std::pair<std::string, double>>;

enum class RetargetSource { Fitted, Derived };
const char* toString(RetargetSource source);  // "fitted", "derived"

struct RetargetShape {
  std::string name;                 // ARKit spelling
  bool reachable = true;
  std::string reason;               // why not, when unreachable
  std::string correctiveOf;         // ARKit name of the base shape, or ""
  NamedValues activations;          // muscle → activation (a corrective's: the difference)
  NamedValues jaw;                  // jaw degree of freedom → value
  std::optional<RetargetFitFigures> fit;
  RetargetSource source = RetargetSource::Fitted;  // reachable shapes: fitted to a rig's shape or derived
  // The eyes' turn, degrees in [−45, 45]: "left_pitch", "left_yaw", "right_pitch", "right_yaw"
  // (anatomy/eyelids.h, EyeGaze; + up, + the subject's left). The lids follow it.
  NamedValues gaze;
  // Air held in the mouth, kPa in [0, 10] (anatomy/mouth_pressure.h: cheekPuff), 0 for none.
  double mouthPressureKpa = 0.0;
};

struct RetargetMap {
  std::string rig;                  // the rig it was fitted on (informative)
  std::string head;                 // the head it was fitted on (informative)
  std::string model = "anatomical";
  std::string library;              // the muscle library it is for ("" when the file does not say)
  std::string note;
  std::vector<RetargetShape> shapes;  // each ARKit name at most once

  // The entry for a name in any spelling, or nullptr.
  const RetargetShape* find(const std::string& anySpelling) const;
  // Every muscle name the map uses, sorted, each once.
  std::vector<std::string> muscleNames() const;
  // The activations that make `shape` on its own: its own, plus its base's for a corrective.
  NamedValues totalActivations(const RetargetShape& shape) const;
};

// Parses a map. When `knownMuscles` is not empty, every activation must name one of them. Errors
// (InputError) name `name:line:col`, the key path and the fault: a wrong format or version, an unknown
// or repeated shape name (in either spelling; the close names are suggested), an activation outside
// its range or of an unknown muscle, a non-finite jaw value, an unreachable shape without a reason or
// with activations, a corrective of a shape the map does not make, a `source` other than "fitted" or
// "derived" (or on an unreachable shape, or "derived" on a corrective), an unknown key.
RetargetMap parseRetargetMap(const std::string& text, const std::string& name = "<string>",
                             const std::vector<std::string>& knownMuscles = {});
RetargetMap readRetargetMap(const YAML::Node& root, const std::string& name,
                            const std::vector<std::string>& knownMuscles = {});

// The map as JSON text (parseRetargetMap reads it back to the same map; numbers keep 17 digits).
std::string serialiseRetargetMap(const RetargetMap& map);

// The ARKit shapes that muscles cannot make, with the reason (assets/retarget/unreachable.json):
// ARKit name → reason, in ARKit order.
const std::vector<std::pair<std::string, std::string>>& unreachableArkitShapes();
// The shipped map (assets/retarget/arkit_ict_face.json, embedded): ICT's ARKit rig fitted with the
// whole face's muscles (`fit-rig --library face`), checked against faceMuscleDefs()'s names. The
// default map of performance input (anim/performance_map.h).
const RetargetMap& builtinRetargetMap();
// The shipped map of a built-in library, embedded: "face" → builtinRetargetMap(), "builtin" →
// assets/retarget/arkit_ict.json (ICT's rig fitted with the built-in ten); nullptr for any other
// name (a library file has no shipped map).
const RetargetMap* shippedRetargetMap(const std::string& library);

// The reason for an unreachable name (any spelling), or nothing.
std::optional<std::string> unreachableReason(const std::string& anySpelling);

}  // namespace myo
