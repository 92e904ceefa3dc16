// Retargeting map files (`myoshell fit-rig --out`, `myoshell rig --map`; the face layer parses the
// text: fit/retarget_map.h).
#pragma once

#include <string>
#include <vector>

#include "myoshell/fit/retarget_map.h"

namespace myo {

// Reads a map (parseRetargetMap's format and errors; InputError "cannot open" when unreadable).
// When `knownMuscles` is not empty, every activation must name one of them.
RetargetMap readRetargetMapFile(const std::string& path, const std::vector<std::string>& knownMuscles = {});

// Writes the map through a temporary file renamed into place: a failure leaves no file.
void writeRetargetMapFile(const std::string& path, const RetargetMap& map);

}  // namespace myo
