#include "myoshell/core/text_lines.h"

#include "myoshell/core/errors.h"

namespace myo {

std::vector<std::string_view> splitLines(std::string_view all, const std::string& name) {
  std::vector<std::string_view> lines;
  size_t start = 0;
  while (start <= all.size()) {
    size_t end = all.find_first_of("\r\n", start);
    if (end == std::string_view::npos) end = all.size();
    if (end - start > kMaxLineBytes)
      throw InputError("line " + std::to_string(lines.size() + 1) + " is longer than 16 MiB", name,
                       static_cast<int>(lines.size() + 1));
    lines.push_back(all.substr(start, end - start));
    if (end == all.size()) break;
    start = end + (all[end] == '\r' && end + 1 < all.size() && all[end + 1] == '\n' ? 2 : 1);
  }
  return lines;
}

}  // namespace myo
