// What a contact projection did to one set of positions (eyelids.h, mouth_contact.h).
#pragma once

#include <algorithm>

namespace myo {

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
