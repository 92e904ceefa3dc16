// Heads and landmarks from files (the face layer receives them as data: face/head.h, landmarks.h).
#pragma once

#include <string>

#include "myoshell/face/head.h"
#include "myoshell/face/landmarks.h"

namespace myo {

// Any OBJ head: readObj(objPath), readLandmarks(landmarkPath) with requireAll(), the mesh scaled
// from `unit` to cm (rescaleToCentimetres), the checks of face/head_checks.h (checkLoadedHead:
// landmarks that fit the mesh, then a plausible scale), and pins from pinPath (a vertex-set file,
// e.g. ICT's rigid_vertices.json) or, when pinPath is empty, defaultGravityPins. The head's name is
// the OBJ file's stem. Errors are InputError naming the file and the fault (docs/heads.md,
// "Checks on load"). The face layer itself accepts a head in any unit; only files are checked.
Head loadHead(const std::string& objPath, const std::string& landmarkPath, const std::string& pinPath = "",
              LengthUnit unit = LengthUnit::cm);

// Reads a landmark file (parseLandmarks; InputError "cannot open landmark file" when it cannot be read).
Landmarks readLandmarks(const std::string& path, int vertexCount);

}  // namespace myo
