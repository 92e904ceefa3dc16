// Internal to the io layer: the pieces every animation exporter shares.
#pragma once

#include "myoshell/io/animation_export.h"

namespace myo::detail {

// Checks that frames has at least one frame and every frame matches rest's n×3 shape (CheckError).
void checkFrames(const AnimationFrames& frames);

}  // namespace myo::detail
