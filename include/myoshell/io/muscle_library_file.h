// Muscle libraries and imported muscle shells from files (the face layer parses library text and
// builds muscles from data: muscles/muscle_def.h, muscle.h).
#pragma once

#include <string>
#include <vector>

#include "myoshell/muscles/muscle_def.h"

namespace myo {

// Reads a muscle library file (JSON or YAML; parseMuscleDefs's layout and errors; "cannot open
// file" when unreadable), then the OBJ of each imported muscle (readMuscleShells).
std::vector<MuscleDef> readMuscleDefs(const std::string& path);

// Reads the OBJ of every imported muscle (def.obj, strict readObj) into def.shell, unless already
// read. Errors are readObj's InputError naming the OBJ.
void readMuscleShells(std::vector<MuscleDef>& defs);

}  // namespace myo
