// The head a fitting command (`fit`, `fit-rig`, `rig`, `muscles`; Python's fit_rig and rig) works
// on: --head default|DIR|OBJ (with --landmarks and --units) as every command reads it, or, for a glTF rig without a head option, the rig's base
// mesh with the landmark file given (a glTF file carries no landmarks). With the anatomical model's
// settings and the muscles of --library.
#pragma once

#include <string>

#include "myoshell/io/rig_file.h"
#include "myoshell/io/scene_face.h"
#include "myoshell/muscles/muscle_def.h"

namespace myo {

struct FitHeadOptions {
  std::string head = "default";
  std::string landmarks;
  std::string units = "cm";
  std::string library = defaultMuscleLibrary();  // --library: "face" (the whole face's 40), "builtin" (the built-in ten) or a file
  bool headGiven = false;   // --head on the command line
  bool unitsGiven = false;  // --units on the command line
};

// The scene inputs on the head the options name, or on `rig`'s base when `rig` is given and no
// --head is (`what` prefixes the error when --landmarks is then missing). InputError as
// resolveHeadArgument and readLandmarks; for a rig's base without --landmarks, or with --units.
SceneInputs fitHeadInputs(const FitHeadOptions& options, const RigFile* rig, const std::string& what);

// The unit of the OBJ head the options name (cm for a rig's base).
LengthUnit fitHeadUnit(const FitHeadOptions& options, const RigFile* rig);

// True when the head is the rig's base (a rig given and no --head).
inline bool usesRigBase(const FitHeadOptions& options, const RigFile* rig) { return rig && !options.headGiven; }

// The name a map records for --library's value: "builtin", "face", or a library file's file name.
std::string muscleLibraryLabel(const std::string& library);

// --lambda: the sparsity weight, a number ≥ 0 (InputError otherwise).
double parseLambda(const std::string& text);

}  // namespace myo
