// The page's face, built the one way both sides build it: the native data writer
// (web/face_data_main.cpp) and the page's WebAssembly (web/wasm/myoshell_web.cpp). The built-in head
// as the anatomical model loads it, these muscles, the anatomical model's default settings, gravity
// on, no drags: what `myoshell pose` builds for the built-in head (the writer checks the keys agree).
#pragma once

#include <memory>
#include <vector>

#include "myoshell/anatomy/anatomical_face.h"
#include "myoshell/head/face_system.h"

namespace myo::web {

inline std::shared_ptr<const AnatomicalFace> buildWebFace(const std::vector<MuscleDef>& muscles, BasisCache* cache) {
  const Head head = loadDefaultHead(defaultHeadOptions(FaceModelKind::Anatomical));
  return std::make_shared<const AnatomicalFace>(head, muscles, AnatomicalSettings{}, std::vector<DragDef>{},
                                                /*gravity=*/true, cache);
}

}  // namespace myo::web
