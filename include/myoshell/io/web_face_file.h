// The web page's face data (docs/web.md): what the browser needs, besides the built-in head it
// builds itself, to build the anatomical face exactly as the native build does without yaml-cpp
// and without an eigen-solve: the muscle definitions (parsed natively from the library) and the
// released skin basis the face steps in, under its cache key; and the takes it can play (scenes'
// keyframed timelines, parsed natively) for the page's ScenePlayer; and the FACS map (parsed
// natively from assets/facs/au_map.json) the page's action-unit sliders drive muscles through.
//
// File, little-endian:
//   magic "MYOWEBF1" (8) | u32 format version | u32 muscle count | muscles | basis | u32 take count |
//   takes | u32 AU count | FACS entries | u64 FNV-1a 64 checksum of everything before it
//   muscle: its MuscleDef fields in declaration order (strings as u32 length + bytes, doubles f64,
//           ints i32, an optional coupling as u8 present + 5 f64, a ring's path as u32 count +
//           anchors); imported muscles (an OBJ shell) are refused by the writer
//   basis:  key (2×u64) | u32 fullVertexCount | u32 free count f | u32 modes d | freeVertices (f×i32)
//           | lambda (d×f64) | freeMass (f×f64) | Φ (3f·d f32, column-major)
//   take:   name | duration f64 (s) | fps f64 | u32 track count | tracks (muscle name | track) |
//           jaw open, forward, lateral (a track each); track: u32 key count | keys (t f64, value f64,
//           interpolation u8: 0 step, 1 linear, 2 smooth)
//   FACS entry: au i32 | name | openface u8 | u32 muscle count | (muscle name, weight f64)… | needs |
//           jaw open, forward, lateral f64 | gaze pitch, yaw f64 | mouth pressure f64 (fit/facs_map.h)
// A take carries what the page's ScenePlayer plays (activations and the jaw over time); the writer
// refuses a scene with anything else on its timeline (gravity, head pose, gaze, drags), so a take
// plays in the page exactly as `myoshell run` plays its scene.
// Φ is stored in float32 (half the bytes; its round-off, 6e-8 relative, is far below the test's
// 1e-3 cm); Ψ is not stored: the page steps linear modes only (AnatomicalSettings::warping off),
// and the reader gives Ψ = 0 so the basis fits the skin; readWebFace's callers refuse warping.
// The writer lives beside the reader so the two cannot drift; the reader alone goes to WebAssembly.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "myoshell/anim/scene.h"
#include "myoshell/fit/facs_map.h"
#include "myoshell/muscles/muscle_def.h"
#include "myoshell/reduce/basis_cache.h"

namespace myo {

struct WebFace {
  std::vector<MuscleDef> muscles;
  BasisKey basisKey;   // the released basis's key as the native build computed it
  ModalBasis basis;    // Φ from float32, Ψ zero (3f×d)
  // The takes (name, duration, fps, activation and jaw tracks; every other field the default).
  std::vector<SceneDesc> takes;
  FacsMap facs;  // its entries (no notes)
};

// The file's bytes. InputError naming an imported muscle, or a take (by its name) whose timeline
// holds more than activations and the jaw.
std::string webFaceBytes(const std::vector<MuscleDef>& muscles, const BasisKey& key, const ModalBasis& basis,
                         const std::vector<SceneDesc>& takes = {}, const FacsMap& facs = {});
void writeWebFaceFile(const std::string& path, const std::vector<MuscleDef>& muscles, const BasisKey& key,
                      const ModalBasis& basis, const std::vector<SceneDesc>& takes = {}, const FacsMap& facs = {});
// InputError naming `name` and what is wrong (magic, version, truncation, checksum, sizes).
WebFace readWebFace(std::string_view bytes, const std::string& name);

// Serves the one basis a WebFace holds: load(key) returns it for its key; any other key is an
// InputError naming both keys (the browser built another face than the native build did; the
// page never computes a basis). store() keeps nothing.
class WebFaceBasisCache : public BasisCache {
 public:
  WebFaceBasisCache(BasisKey key, ModalBasis basis) : key_(key), basis_(std::move(basis)) {}
  std::optional<ModalBasis> load(const BasisKey& key) override;
  void store(const BasisKey&, const ModalBasis&) override {}

 private:
  BasisKey key_;
  ModalBasis basis_;
};

}  // namespace myo
