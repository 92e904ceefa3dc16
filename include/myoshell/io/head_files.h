// Heads and landmarks from files (the face layer receives them as data: head/head.h, landmarks.h).
#pragma once

#include <string>

#include "myoshell/head/head.h"
#include "myoshell/head/landmarks.h"

namespace myo {

// Any OBJ head: readObj(objPath), readLandmarks(landmarkPath) with requireAll(), the mesh scaled
// from `unit` to cm (rescaleToCentimetres), the checks of head/head_checks.h (checkLoadedHead:
// landmarks that fit the mesh, then a plausible scale), and pins from pinPath (a vertex-set file,
// e.g. ICT's rigid_vertices.json) or, when pinPath is empty, defaultGravityPins. The head's name is
// the OBJ file's stem. Errors are InputError naming the file and the fault (docs/heads.md,
// "Checks on load"). The face layer itself accepts a head in any unit; only files are checked.
Head loadHead(const std::string& objPath, const std::string& landmarkPath, const std::string& pinPath = "",
              LengthUnit unit = LengthUnit::cm);

// The files of a head as the command line names it (`myoshell head`, `myoshell pose`).
struct HeadFiles {
  std::string obj;         // the head's OBJ; empty for the built-in head
  std::string landmarks;   // its landmark file (empty for the built-in head)
  std::string pins;        // a vertex-set file of gravity pins, or empty (the rim rule)
  LengthUnit unit = LengthUnit::cm;  // the unit the OBJ is written in
  bool builtIn() const { return obj.empty(); }
};

// Resolves a head argument: "default" (the built-in head), an OBJ file, or a folder laid out like
// ../shared/data/ict (head_skin.obj, landmarks_multipie68.json, and rigid_vertices.json when present;
// a landmark or pin file given explicitly wins over the folder's). `units` is the --units text.
// Checks only what can be checked without reading the head (loadHead reads and checks it); the
// InputErrors name the option: "--units: unknown length unit 'X' (use m, mm or cm)", "--landmarks,
// --pins and --units apply to an OBJ head, not the default head", "OBJ: no such head: give
// 'default', an OBJ file or a folder with head_skin.obj", "OBJ: an OBJ head needs --landmarks FILE
// (layout of docs/heads.md); `myoshell landmarks OBJ` finds them automatically". The command line
// and Python's load_head never meet the last: they give an OBJ without landmarks its automatic file
// first (findLandmarkFile, io/auto_landmark_file.h).
HeadFiles resolveHeadArgument(const std::string& head, const std::string& landmarks, const std::string& pins,
                              const std::string& units);

// Reads a landmark file (parseLandmarks; InputError "cannot open landmark file" when it cannot be read).
Landmarks readLandmarks(const std::string& path, int vertexCount);

}  // namespace myo
