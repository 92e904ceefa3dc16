// How firmly a muscle is tied to the skin along its length (muscle_coupling.h): the shear modulus
// G(t) of the tissue between muscle and skin at position t ∈ [0, 1] along the muscle (0 the origin,
// 1 the insertion): none at the origin, weak along the belly, strong at the insertion
// (docs/anatomical_model.md, "Values and sources"). One profile per muscle, as data in the muscle
// library (MuscleDef::coupling, key `coupling`; docs/muscles.md), or the model's default.
#pragma once

#include <string>

namespace myo {

struct CouplingProfile {
  double insertionModulus = 3.0e5;  // G at the insertion, dyn/cm² (30 kPa: muscle/dense tissue)
  double bellyModulus = 1.0e4;      // G along the belly, dyn/cm² (1 kPa: subcutaneous fat)
  double originEnd = 0.15;          // t below which there is no coupling (the origin)
  double bellyStart = 0.30;         // G ramps 0 → belly over [originEnd, bellyStart]
  // G ramps belly → insertion over [insertionStart, 1]: the last 15 % of the muscle, about 1 cm of a
  // 6–7 cm zygomaticus, the modiolus's size (docs/anatomical_model.md, "The insertion zone").
  double insertionStart = 0.85;
  // G at position t ∈ [0, 1] along the muscle (smooth ramps), dyn/cm².
  double modulus(double t) const;
  // InputError "OWNER: FIELD …" naming the field by its library key (insertion_modulus, …).
  void validate(const std::string& owner = "muscle coupling") const;
  bool operator==(const CouplingProfile&) const = default;
};

}  // namespace myo
