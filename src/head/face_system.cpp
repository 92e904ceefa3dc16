#include "myoshell/head/face_system.h"

#include "myoshell/core/check.h"

namespace myo {

const char* toString(FaceModelKind kind) { return kind == FaceModelKind::Thesis ? "thesis" : "anatomical"; }

DefaultHeadOptions defaultHeadOptions(FaceModelKind kind) {
  DefaultHeadOptions o;
  o.openEyes = kind == FaceModelKind::Anatomical;
  return o;
}

std::unique_ptr<FaceStepper> makeStepper(std::shared_ptr<const FaceSystem> face) {
  MYO_CHECK(face != nullptr, "makeStepper: no face");
  const FaceSystem& f = *face;
  return f.makeStepper(std::move(face));
}

}  // namespace myo
