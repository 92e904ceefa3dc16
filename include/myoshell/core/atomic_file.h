// Writing a whole file so that no reader ever sees half of it: the bytes go to a temporary file
// beside the target, which is renamed into place only once complete.
#pragma once

#include <string>

namespace myo {

// Writes `bytes` to `path` through "<path>.tmp". Throws InputError("<what>", path) when the file
// cannot be written or renamed (a missing folder, a folder at `path`, no permission); nothing is
// left behind then.
void writeFileAtomically(const std::string& path, const std::string& bytes, const std::string& what = "cannot write file");

}  // namespace myo
