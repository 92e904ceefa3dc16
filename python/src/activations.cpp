#include "activations.h"

#include <fmt/core.h>

#include "myoshell/core/errors.h"

namespace myo::python {

int muscleIndexByName(const FaceSystem& face, const std::string& name) {
  for (int m = 0; m < face.muscleCount(); ++m)
    if (face.muscleName(m) == name) return m;
  std::string names;
  for (int m = 0; m < face.muscleCount(); ++m) names += (names.empty() ? "" : ", ") + face.muscleName(m);
  throw InputError("unknown muscle '" + name + "' (the anatomical model's muscles: " + names + ")");
}

void checkActivation(const std::string& name, double value) {
  if (!(value >= 0.0 && value <= 1.0))
    throw InputError(fmt::format("{}={}: an activation must lie in [0, 1] under the anatomical model", name, value));
}

VecX activationVector(const FaceSystem& face, const NamedValues& values) {
  VecX a = VecX::Zero(face.muscleCount());
  for (const auto& [name, value] : values) {
    const int m = muscleIndexByName(face, name);
    checkActivation(name, value);
    a(m) = value;
  }
  return a;
}

}  // namespace myo::python
