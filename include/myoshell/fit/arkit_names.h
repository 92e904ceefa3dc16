// ARKit blendshape names and their ICT-FaceKit spellings, from one alias table in data
// (assets/retarget/arkit_names.json; docs/rigs.md, "Names"). ARKit writes mouthSmileLeft and
// browInnerUp; ICT writes mouthSmile_L and browInnerUp_L + browInnerUp_R. ARKit's browInnerUp and
// cheekPuff are each two ICT shapes whose activations add.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace myo {

// The 52 ARKit names, in the order of Apple's documentation (eyes, jaw, mouth, brows, cheeks,
// nose, tongue).
const std::vector<std::string>& arkitNames();

// The ARKit name for any spelling (ARKit's own, or ICT's; an ICT half such as browInnerUp_L gives
// the ARKit name it is part of), or nothing for an unknown name. Exact, case-sensitive.
std::optional<std::string> findArkitName(const std::string& spelling);

// The same, throwing InputError for an unknown name: "unknown blendshape name 'X' (did you mean
// a, b?)" with the close matches, or "(use one of the 52 ARKit names: …)" when none is close.
std::string canonicalArkitName(const std::string& spelling);

// The ARKit name of a shape's mirror image, the same motion on the subject's other side, for any
// spelling (canonicalArkitName's errors): mouthSmileLeft ↔ mouthSmileRight, and mouthLeft ↔
// mouthRight, jawLeft ↔ jawRight, which move the whole mouth or jaw towards one side; nothing for a
// shape of both sides or the midline (jawOpen, browInnerUp). fit-rig fits each pair together.
std::optional<std::string> mirroredArkitName(const std::string& spelling);

// What FACS says of an ARKit shape (the aus and side columns of the table): the action units whose
// motion it shows (none for mouthClose, mouthLeft, mouthRight) and, for a sided shape, the
// subject's side ("left", "right"; "" for a shape of both sides or the midline).
struct ArkitFacs {
  std::vector<int> aus;
  std::string side;
};
// For any spelling (canonicalArkitName's errors).
const ArkitFacs& arkitFacs(const std::string& spelling);

// The ICT names that compose an ARKit name (one, or two for browInnerUp and cheekPuff); the ARKit
// name is checked (canonicalArkitName) first, so any spelling is accepted.
const std::vector<std::string>& ictNamesOf(const std::string& spelling);

}  // namespace myo
