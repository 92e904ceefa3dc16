// Muscles as data: where a muscle sits on a head (in the head's face frame, so placement does not
// depend on the head's position, orientation or units), its shape and how hard it pulls.
// The thesis's eight muscles ship in assets/muscles/thesis_muscles.json (docs/muscles.md).
#pragma once

#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "myoshell/core/types.h"
#include "myoshell/head/face_model_kind.h"
#include "myoshell/mesh/tri_mesh.h"
#include "myoshell/muscles/coupling_profile.h"

namespace YAML {
class Node;
}

namespace myo {

class DocReader;
}

namespace myo {

// A point of a muscle: a landmark of the head, moved by an offset in face-frame units (fractions
// of the outer inter-ocular distance, axes x = subject's left, y = up, z = out of the face), then
// put onto the skin and pushed `depth` (face-frame units) under it along the skin normal.
struct MuscleAnchor {
  std::string landmark;          // a name Landmarks::vertex resolves ("mouth_corner_right", …)
  Vec3 offset = Vec3::Zero();    // face-frame units
  double depth = 0.04;           // face-frame units under the skin (> 0)
};

// A linear muscle pulls its insertion towards its origin (the thesis's kind). A ring muscle is a
// sphincter (orbicularis oris, orbicularis oculi): a band along `path` whose activation is a
// tension along its fibres that draws the ring towards its centre (docs/muscles.md, "Ring
// muscles"). Only the anatomical model plays ring muscles.
enum class MuscleKind { Linear, Ring };
const char* toString(MuscleKind kind);

struct MuscleDef {
  std::string name;              // unique, e.g. "zygomaticus_major_right"
  MuscleKind kind = MuscleKind::Linear;
  std::string side;              // "right", "left" or "center" (the subject's side)
  std::string facs;              // FACS action unit(s) it drives, e.g. "AU12" (documentation only)
  MuscleAnchor origin;           // fixed end, on the skull side: its station ring is pinned
  MuscleAnchor insertion;        // moving end, into the skin
  double width = 0.10;           // face-frame units across the muscle
  double thickness = 0.02;       // face-frame units, the flat ring's height
  int stations = 6;              // rings along the muscle (≥ 3): 6 gives the thesis's 36 nodes
  int ringNodes = 6;             // nodes per ring (≥ 4, even): 6 × 6 = 36 nodes, 68 triangles
  // The insertion's displacement along the muscle at activation a = 1, as a fraction of the rest
  // length; the maximum force is calibrated to reach it (static, linear response of the stretch mode).
  double contraction = 0.15;
  // Stiffness of the subcutaneous springs of this muscle (thesis eq. 14), dyn; ≤ 0 = model default.
  double springStiffness = 0.0;
  // ROI factor α of thesis eq. 19 (> 1); ≤ 0 = model default.
  double roiAlpha = 0.0;
  // Anatomical model: this muscle's coupling profile along its length (key `coupling`; fields not
  // written keep CouplingProfile's defaults); none = the model's profile (MuscleCouplingSettings).
  // The thesis model does not read it.
  std::optional<CouplingProfile> coupling;
  // Anatomical model, linear muscles (key `thickens`): the muscle is bound to the dermis along its
  // belly, so the column of skin and muscle over its deep face keeps its volume as it shortens and
  // bunches out of the face (the frontalis, whose skin, dense connective layer and aponeurosis move
  // as one over the loose areolar layer: docs/muscles.md, "The compressed forehead thickens"). Its
  // origin is the galea, which slides with them: it contracts about the forehead's line of
  // convergence, not its origin (docs/muscles.md, "The galea slides").
  bool thickens = false;
  // Anatomical model, linear muscles (key `pushes`, an anchor): the soft tissue the muscle squeezes
  // flows past its origin, which holds only the muscle's deep end on the bone, and carries the skin
  // ahead of the origin, up to this anchor, along with the insertion (the mentalis: the chin's pad
  // pushes the lower lip up; docs/muscles.md, "The chin's pad pushes the lower lip").
  std::optional<MuscleAnchor> pushes;
  // Anatomical model, linear muscles (key `continues_into`, an anchor): the fibres continue past the
  // insertion into a muscle in series whose far end is fixed at this anchor (the medial frontalis
  // into the procerus, fixed on the nasal bone). Pulled at one end and held at the other, the
  // continuation stretches evenly and draws the skin over it along: each skin vertex over the
  // segment from the insertion to the anchor, within the muscle's width, moves with the insertion
  // ring's mean motion times (1 − s), s its place along the segment (docs/muscles.md, "The medial
  // frontalis draws the nose's root").
  std::optional<MuscleAnchor> continuesInto;

  // Ring muscles (kind Ring; key `ring`): the band's course through `path` (≥ 3 anchors, in order,
  // each placed as origin and insertion are), closed into a loop or open (an arc whose ends are the
  // first and last anchors); the two `anchors` whose midpoint (under the skin) is the ring's
  // centre — the modioli for the mouth, the medial palpebral ligament and the lateral raphe for the
  // eye; `shortening` (the fibres' shortening at a = 1, a fraction of their length: the ring's
  // contraction about its centre) and `protrusion` (forward motion out of the face per unit of
  // inward motion, from the lip's incompressibility: docs/muscles.md).
  struct Ring {
    std::vector<MuscleAnchor> path;
    bool closed = false;
    std::array<MuscleAnchor, 2> anchors;
    double shortening = 0.3;
    double protrusion = 0.0;
    // Where the contraction's fixed point lies between the two anchors (0 the first, 1 the second;
    // key `centre`): 0.5 for a band fixed at both ends (the lips' modioli), 0 for a loop fixed to
    // bone at its first anchor only (the eye's orbicularis at the medial palpebral ligament).
    double centre = 0.5;
    // Whether the contraction runs along the skin's tangent plane (key `along_skin`): a band sliding
    // over a curved bed (the orbital part over the rim and the cheek) rather than in the face's
    // plane (the lips, with their protrusion; the palpebral part, whose lids turn about the globe).
    bool alongSkin = false;
    // Whether the ring runs in a lip that keeps its volume (key `lip_body`): shortened along its
    // fibres, the lip grows in height about its own axis instead of being squeezed across
    // (docs/muscles.md, "The lip's body"; the mouth's parts).
    bool lipBody = false;
    // The band presses the lip onto the dental arch (key `hoop`: the lower lip's marginal part,
    // docs/muscles.md, "The marginal part rolls the lower lip in"): instead of drawing in about the
    // anchors' centre in the face's plane, the band is a string held at its two ends and loaded by
    // its tension round the arch, deflected towards the arch's centre of curvature in the face's
    // x–z plane by σ of its distance there, times 4ξ(1 − ξ) (ξ its place along the ring, 0 and 1
    // the ends): nothing at the ends, all at the middle. The arch's front is `front` (a landmark's
    // vertex plus a face-frame offset, not projected: it lies inside the head), its radius of
    // curvature there `radius` (face-frame units); the centre lies `radius` behind the front.
    struct Hoop {
      std::string landmark;
      Vec3 offset = Vec3::Zero();
      double radius = 0.0;
    };
    std::optional<Hoop> hoop;
  };
  Ring ring;
  bool isRing() const { return kind == MuscleKind::Ring; }

  // Imported muscle (instead of a generated one): an OBJ of the closed muscle shell in the head's
  // space (cm), with its node sets as vertex ids of that OBJ. origin/insertion anchors, width,
  // thickness, stations and ring_nodes are then not used.
  std::string obj;                  // path (resolved against the file that defined the muscle)
  std::vector<int> originNodes;     // pinned to the skull (≥ 3, not collinear)
  std::vector<int> centralNodes;    // where the activation force acts
  std::vector<int> insertionNodes;  // the moving end used for calibration; empty = the quarter of
                                    // the central nodes farthest from the origin
  // The OBJ's mesh, read by io (io/muscle_library_file.h: readMuscleShells); buildMuscle needs it.
  std::shared_ptr<const TriMesh> shell;
  bool imported() const { return !obj.empty(); }

  // Throws InputError naming the muscle and the field for impossible values.
  void validate() const;
};

// Parses a muscle library (JSON or YAML): {"muscles": [{...}, ...]} with the keys of MuscleDef in
// snake_case (name, side, facs, origin {landmark, offset, depth}, insertion {…}, width, thickness,
// stations, ring_nodes, contraction, spring_stiffness, roi_alpha, coupling {insertion_modulus,
// belly_modulus, origin_end, belly_start, insertion_start}, note). Errors (InputError) name
// `name:line:col`, the key path and the fault; unknown keys are errors.
// Imported muscles' OBJs are not read here (def.shell stays empty; io reads them).
std::vector<MuscleDef> parseMuscleDefs(const std::string& jsonText, const std::string& name = "<string>");
// The same over a document already loaded (io reads library files with it).
std::vector<MuscleDef> readMuscleLibrary(const YAML::Node& root, const std::string& name);
// One muscle definition from a mapping being read (scene files reuse this for their own muscles).
MuscleDef readMuscleDef(DocReader& reader);

// The thesis's eight muscles (zygomaticus major, corrugator supercilii, depressor labii inferioris,
// depressor anguli oris; right and left), from the library embedded at build time.
const std::vector<MuscleDef>& thesisMuscleDefs();
const std::string& thesisMuscleJson();

// The whole face's muscles (assets/muscles/face_muscles.json, embedded): 17 pairs and 3 midline
// muscles, the thesis's eight among them, linear and ring (docs/muscles.md).
const std::vector<MuscleDef>& faceMuscleDefs();

// The thesis's eight as the whole face places them: faceMuscleDefs()'s entries under the thesis's
// names, in the thesis's order. Its zygomaticus major arises from the zygomatic bone and its
// depressor anguli from the mandible's lower border, where the thesis's placement leaves them short
// or in front of the chin (docs/anatomical_model.md, "The anatomical model's eight").
const std::vector<MuscleDef>& anatomicalEightDefs();

// The anatomical model's built-in library: the eight above, then the mouth's sphincter
// (orbicularis_oris_upper, _lower of the whole face), which is the lips' own body: without it the
// lips are bare skin that a pulled corner drags sideways (docs/anatomical_model.md, "The lips").
const std::vector<MuscleDef>& anatomicalBuiltinDefs();

// A built-in library by its scene name for a model: "builtin" (the thesis's eight as the thesis
// places them under model: thesis; anatomicalBuiltinDefs() under model: anatomical) or "face" (the
// whole face); nullptr for any other name (a library file's path).
const std::vector<MuscleDef>* builtinMuscleLibrary(const std::string& name, FaceModelKind model);

// The library every command, the viewer, Python and a scene without muscles.library use: the whole
// face under the anatomical model; the thesis's eight under model: thesis (its figures stay
// byte-identical to the thesis's).
inline const char* defaultMuscleLibrary(FaceModelKind model = FaceModelKind::Anatomical) {
  return model == FaceModelKind::Thesis ? "builtin" : "face";
}

}  // namespace myo
