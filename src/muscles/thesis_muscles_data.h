// The muscle library embedded at build time (cmake/EmbedText.cmake).
#pragma once

namespace myo::detail {
extern const char kThesisMusclesJson[];  // assets/muscles/thesis_muscles.json, NUL-terminated
}  // namespace myo::detail
