// Which face model a scene plays: the thesis's (docs/face_model.md) or the anatomical one
// (docs/anatomical_model.md). Its own header so that what only chooses by model (the built-in
// muscle library, muscle_def.h) need not see the whole FaceSystem seam (face_system.h).
#pragma once

namespace myo {

enum class FaceModelKind { Thesis, Anatomical };
const char* toString(FaceModelKind kind);  // "thesis", "anatomical"

}  // namespace myo
