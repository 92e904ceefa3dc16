// Heads and landmarks from files (the face layer receives them as data: face/head.h, landmarks.h).
#pragma once

#include <string>

#include "myoshell/face/head.h"
#include "myoshell/face/landmarks.h"

namespace myo {

// Any OBJ head: readObj(objPath), readLandmarks(landmarkPath) with requireAll(), and pins from
// pinPath (a vertex-set file, e.g. ICT's rigid_vertices.json) or, when pinPath is empty,
// defaultGravityPins. The head's name is the OBJ file's stem. Errors are InputError naming the
// file and the fault.
Head loadHead(const std::string& objPath, const std::string& landmarkPath, const std::string& pinPath = "");

// Reads a landmark file (parseLandmarks; InputError "cannot open landmark file" when it cannot be read).
Landmarks readLandmarks(const std::string& path, int vertexCount);

}  // namespace myo
