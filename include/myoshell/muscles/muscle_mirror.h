// A muscle's mirror twin, by name: libraries name a pair `<muscle>_left` and `<muscle>_right` (the
// subject's sides) and a midline muscle without a side (procerus, orbicularis_oris_upper). The
// shipped libraries name every pair so (tests/face/face_muscles_test.cpp); fit-rig fits a left/right
// pair of shapes through the twins (fit/activation_fit.h, fitMirroredActivations).
#pragma once

#include <string>

namespace myo {

// The twin's name: the side's suffix swapped (zygomaticus_major_left ↔ zygomaticus_major_right); a
// name without one is its own twin.
std::string mirroredMuscleName(const std::string& name);

}  // namespace myo
