// Landmark files found automatically (head/auto_landmarks.h) for an OBJ head given without
// --landmarks, kept in the basis cache folder keyed on the OBJ's content, never beside the user's
// OBJ (docs/heads.md, "A head without a landmark file"). One path for the command line and scenes:
// `findLandmarkFile` resolves an OBJ without landmarks, `checkLandmarkFile` checks a given file
// against the automatic landmarks when they are already kept.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "myoshell/anim/scene.h"
#include "myoshell/head/auto_landmarks.h"
#include "myoshell/head/head_checks.h"

namespace myo {

// What findLandmarkFile found or reused.
struct FoundLandmarkFile {
  std::string obj;                   // the head's OBJ, as given
  std::string path;                  // the landmark file written (or reused) in the cache folder
  bool reused = false;               // read back from an earlier search (no search run)
  LengthUnit unit = LengthUnit::cm;  // the OBJ's unit: inferred by the search, or the one given
  bool unitInferred = true;          // false when a unit was given
  bool eyesOpen = false;             // both eyes have an opening (lids; blinks work)
  bool mouthOpen = false;            // the mouth has an opening (lip contact, a jaw that opens it)
  std::vector<std::string> warnings; // the search's warnings (eyes or mouth closed, the jaw line, uncertain points)
  double seconds = 0.0;              // the search's time (0 when reused)
};

// The folder automatic landmark files live in: `cacheDir`/landmarks, or, when no cache folder is
// known (cacheDir empty), the system's temporary folder's myoshell-landmarks.
std::filesystem::path landmarkFileFolder(const std::filesystem::path& cacheDir);

// The automatic landmark file of an OBJ's bytes in that folder: <128-bit content hash>.landmarks.json.
std::filesystem::path landmarkFilePath(const std::string& objBytes, const std::filesystem::path& cacheDir);

// The text of a landmark file holding `found`: today's layout (multipie68, named) with a confidence
// per point, and an "automatic" object (units, units_inferred, eyes, mouth, warnings) the landmark
// reader skips. `source` names the head in the file's "source" line.
std::string autoLandmarkFileText(const AutoLandmarks& found, const std::string& source);

// Keeps `found` (the search's result on the OBJ `obj`) in the cache folder for later commands;
// returns the file's path. InputError when it cannot be written.
std::string storeAutoLandmarks(const std::string& obj, const AutoLandmarks& found, const std::filesystem::path& cacheDir);

// The landmarks of the OBJ head `obj` without a landmark file: the file kept from an earlier search
// of the same bytes when there is one, else findLandmarks(readObj(obj), unit) written there (in
// landmarkFileFolder({}) when the cache folder cannot be written).
// `unit` empty: the unit is the search's (inferred from the size); given: checked by the search and
// by loadHead as for any OBJ. InputError from the OBJ reader or the search ("not a head: ...").
FoundLandmarkFile findLandmarkFile(const std::string& obj, const std::filesystem::path& cacheDir,
                                   std::optional<LengthUnit> unit = std::nullopt);

// The landmarks of a glTF rig's base mesh (`base`, read in cm from the file `glb`) without a
// landmark file, as findLandmarkFile does for an OBJ: kept in the cache folder keyed on the GLB's
// bytes, reused when kept, else findLandmarks(base) with the unit cm (a glTF file is in metres by
// specification, read in cm). InputError as findLandmarkFile.
FoundLandmarkFile findRigBaseLandmarkFile(const std::string& glb, const TriMesh& base, const std::filesystem::path& cacheDir);

// Checks a landmark file given for `obj` against the automatic landmarks of the same bytes when
// the cache folder already holds them (no search is run: docs/heads.md says why), by
// checkGivenLandmarks: ids that look 1-based and swapped sides throw InputError naming the
// mistake; points more than 1.5 cm off are returned as warnings, with the kept search's warnings
// on eyes and mouth. Nothing kept: no warnings.
std::vector<std::string> checkLandmarkFile(const std::string& obj, const std::string& landmarks,
                                           const std::filesystem::path& cacheDir);

// A scene's head: an OBJ without head.landmarks gets findLandmarkFile's file (head.landmarks) and,
// when the scene gives no head.units, its unit; returns what was found. An OBJ with landmarks is
// checked by checkLandmarkFile (the warnings go to `warnings`). Paths are resolved against the
// scene's folder. The built-in head: nothing.
std::optional<FoundLandmarkFile> completeSceneHead(SceneDesc& scene, const std::filesystem::path& cacheDir,
                                                   std::vector<std::string>* warnings = nullptr);

}  // namespace myo
