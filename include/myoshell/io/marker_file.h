// Marker files (`myoshell fit MARKERS.json`; the face layer parses the text: fit/marker_target.h).
#pragma once

#include <string>

#include "myoshell/fit/marker_target.h"

namespace myo {

// Reads a marker file for a head of `vertexCount` vertices (parseMarkerTarget's format and errors;
// InputError "cannot open" when unreadable).
MarkerTarget readMarkerFile(const std::string& path, int vertexCount);

}  // namespace myo
