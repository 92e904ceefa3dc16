// Activations by muscle name, checked as `myoshell pose --set NAME=VALUE` checks them, with the
// same messages (without the option's name): an unknown muscle lists the model's muscles; a value
// outside [0, 1] (or NaN) is refused.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "myoshell/core/types.h"
#include "myoshell/head/face_system.h"

namespace myo::python {

using NamedValues = std::vector<std::pair<std::string, double>>;

// The muscle's index in `face`; InputError "unknown muscle 'x' (the anatomical model's muscles: …)".
int muscleIndexByName(const FaceSystem& face, const std::string& name);
// InputError "NAME=VALUE: an activation must lie in [0, 1] under the anatomical model" outside [0, 1].
void checkActivation(const std::string& name, double value);
// One activation per muscle of `face` in its order: the named ones, every other 0.
VecX activationVector(const FaceSystem& face, const NamedValues& values);

}  // namespace myo::python
