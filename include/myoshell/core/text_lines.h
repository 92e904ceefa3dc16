// Splitting a text file into lines, as every line-based reader does (OBJ, performances).
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace myo {

// The longest line a reader accepts: longer is a broken or hostile file, not a face.
constexpr size_t kMaxLineBytes = size_t{16} << 20;

// The lines of `text`, ending at "\n", "\r\n" or a lone "\r" (classic Mac files; tinyobjloader splits
// them the same way). After a final line break comes one empty line. Views into `text`. A line longer
// than kMaxLineBytes is an InputError naming `name` and the line.
std::vector<std::string_view> splitLines(std::string_view text, const std::string& name);

}  // namespace myo
