// Internal to the io layer: the pieces every animation exporter shares.
#pragma once

#include <filesystem>
#include <string_view>

#include "myoshell/io/animation_export.h"

namespace myo::detail {

// Writes bytes to path through "<path>.tmp" renamed into place. Throws InputError naming the file
// when it cannot be written; on failure neither the temporary nor the final file is left behind.
void writeFileAtomically(const std::filesystem::path& path, std::string_view bytes);

// Checks that frames has at least one frame and every frame matches rest's n×3 shape (CheckError).
void checkFrames(const AnimationFrames& frames);

}  // namespace myo::detail
