// What a contact projection did to one set of positions (eyelids.h, mouth_contact.h).
#pragma once

#include <algorithm>

namespace myo {

// Where the rest mesh already touches a contact (an orbit vertex on the eyeball's sphere, a lip
// vertex on the teeth, the lips closed), the constraint is set this far inside the rest (face-frame
// units: ≈ 9 µm on ICT), so the rest lies strictly clear of it. A constraint active exactly at rest
// let the time step's penalty switch on and off at every step: a face at rest kept buzzing by a few
// µm instead of falling still (docs/mouth_contact.md, "Penalty forces").
constexpr double kRestContactClearance = 1e-4;

struct ContactReport {
  double maxPenetrationBefore = 0.0;  // cm: the deepest violation before projection
  double maxPenetrationAfter = 0.0;   // cm: after it (0 up to round-off)
  int projected = 0;                  // vertices moved
  void add(const ContactReport& o) {
    maxPenetrationBefore = std::max(maxPenetrationBefore, o.maxPenetrationBefore);
    maxPenetrationAfter = std::max(maxPenetrationAfter, o.maxPenetrationAfter);
    projected += o.projected;
  }
};

}  // namespace myo
