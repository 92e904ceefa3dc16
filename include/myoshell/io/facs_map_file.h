// FACS map files (action units → muscles; the face layer parses the text: fit/facs_map.h).
#pragma once

#include <string>
#include <vector>

#include "myoshell/fit/facs_map.h"

namespace myo {

// Reads a FACS map file, its muscles checked against `knownMuscles` when not empty (parseFacsMap's
// format and errors; InputError "cannot open" when unreadable).
FacsMap readFacsMapFile(const std::string& path, const std::vector<std::string>& knownMuscles = {});

}  // namespace myo
