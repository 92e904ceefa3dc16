// Reading a whole file into memory: the one reader under every parser that takes a file
// (OBJ, landmarks, vertex sets, scenes, muscle libraries, PC2, the basis cache, viewer scripts).
#pragma once

#include <optional>
#include <string>

namespace myo {

// The bytes of the file at `path`. Throws InputError naming `path`:
// "cannot open: is a directory" for a folder; when the file cannot be opened, `cannotOpen` if given,
// else "cannot open (<strerror>)"; "cannot read" when reading fails part way.
std::string readWholeFile(const std::string& path, const std::string& cannotOpen = "");

// The same without throwing: nothing when the file is missing, a folder, or unreadable.
std::optional<std::string> tryReadWholeFile(const std::string& path);

}  // namespace myo
