// The default head's data, embedded at build time by cmake/EmbedDefaultHead.cmake (generated
// default_head_data.cpp in the build tree): the verified MediaPipe binarypb slice and the
// landmark file assets/default_head/landmarks_multipie68.json.
#pragma once

#include <cstddef>
#include <cstdint>

namespace myo::detail {
extern const std::uint8_t kDefaultHeadBinarypb[];
extern const std::size_t kDefaultHeadBinarypbSize;
extern const char kDefaultHeadSha256[];
extern const std::uint8_t kDefaultHeadLandmarks[];
extern const std::size_t kDefaultHeadLandmarksSize;
}  // namespace myo::detail
