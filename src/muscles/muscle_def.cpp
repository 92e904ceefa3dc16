#include "myoshell/muscles/muscle_def.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "myoshell/core/check.h"
#include "myoshell/core/errors.h"

namespace myo {

const char* toString(MuscleKind kind) { return kind == MuscleKind::Ring ? "ring" : "linear"; }

void MuscleDef::validate() const {
  auto bad = [&](const std::string& what) { throw InputError("muscle '" + name + "': " + what); };
  if (name.empty()) throw InputError("a muscle has an empty name");
  if (side != "right" && side != "left" && side != "center")
    bad("side must be \"right\", \"left\" or \"center\" (got \"" + side + "\")");
  if (imported()) {
    if (originNodes.size() < 3) bad("an imported muscle needs at least 3 origin_nodes");
    if (centralNodes.empty()) bad("an imported muscle needs central_nodes");
  }
  if (isRing()) {
    if (imported()) bad("a ring muscle is generated from its path, not imported");
    if (ring.path.size() < 3) bad("a ring needs a path of at least 3 anchors");
    if (!(ring.shortening > 0.0 && ring.shortening < 1.0)) bad("ring shortening must lie in (0, 1)");
    if (!(ring.protrusion >= 0.0) || !std::isfinite(ring.protrusion)) bad("ring protrusion must be ≥ 0");
    if (!(ring.centre >= 0.0 && ring.centre <= 1.0)) bad("ring centre must lie in [0, 1]");
    if (ring.hoop) {
      if (ring.closed) bad("a hoop is for an open ring (a band held at its two ends)");
      if (ring.hoop->landmark.empty()) bad("the hoop has no landmark");
      if (!ring.hoop->offset.allFinite()) bad("the hoop's offset is not finite");
      if (!(ring.hoop->radius > 0.0) || !std::isfinite(ring.hoop->radius)) bad("the hoop's radius must be > 0");
    }
  }
  if (pushes && (isRing() || imported())) bad("pushes is for generated linear muscles");
  std::vector<const MuscleAnchor*> anchors = {&origin, &insertion};
  if (pushes) anchors.push_back(&*pushes);
  if (continuesInto && (isRing() || imported())) bad("continues_into is for generated linear muscles");
  if (continuesInto) anchors.push_back(&*continuesInto);
  if (isRing()) {
    anchors.clear();
    for (const MuscleAnchor& a : ring.path) anchors.push_back(&a);
    for (const MuscleAnchor& a : ring.anchors) anchors.push_back(&a);
  }
  for (const MuscleAnchor* a : anchors) {
    if (imported()) break;
    if (a->landmark.empty()) bad("an anchor has no landmark");
    if (!a->offset.allFinite()) bad("an anchor offset is not finite");
    if (!(a->depth > 0.0) || !std::isfinite(a->depth)) bad("anchor depth must be > 0");
  }
  if (!(width > 0.0) || !std::isfinite(width)) bad("width must be > 0");
  if (!(thickness > 0.0) || !std::isfinite(thickness)) bad("thickness must be > 0");
  if (stations < 3) bad("stations must be ≥ 3 (got " + std::to_string(stations) + ")");
  if (ringNodes < 4 || ringNodes % 2 != 0)
    bad("ring_nodes must be even and ≥ 4 (got " + std::to_string(ringNodes) + ")");
  if (!(contraction > 0.0 && contraction < 1.0)) bad("contraction must lie in (0, 1)");
  if (!std::isfinite(springStiffness)) bad("spring_stiffness is not finite");
  if (roiAlpha > 0.0 && roiAlpha <= 1.0) bad("roi_alpha must be > 1 (thesis eq. 19)");
  if (coupling) coupling->validate("muscle '" + name + "': coupling");
}

}  // namespace myo
