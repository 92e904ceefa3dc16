#include "myoshell/muscles/muscle_mirror.h"

#include <utility>

namespace myo {

std::string mirroredMuscleName(const std::string& name) {
  for (const auto& [from, to] : {std::pair<std::string, std::string>{"_left", "_right"}, {"_right", "_left"}})
    if (name.size() > from.size() && name.ends_with(from)) return name.substr(0, name.size() - from.size()) + to;
  return name;
}

}  // namespace myo
