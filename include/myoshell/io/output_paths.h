// Output paths checked before any work, so that a command which would fail at its first write
// fails at once instead, having computed nothing and written nothing (the CLI's commands and the
// Python module's writers). Each fault is an InputError naming the option and the path.
#pragma once

#include <string>

namespace myo {

// A file to write (atomically: a temporary file beside it, then renamed): not a folder, not a
// name ending in '/', not an existing device or other non-regular file; its folder exists, is a
// folder and can be written. `what` names the file in the messages ("JSON file"). "" passes (no
// output asked for).
void checkOutputFile(const std::string& path, const std::string& option, const std::string& what);

// A folder to write into, made when missing: not an existing file; an existing folder must be
// writable, and a missing one creatable (its nearest existing parent a writable folder).
void checkOutputFolder(const std::string& path, const std::string& option);

}  // namespace myo
