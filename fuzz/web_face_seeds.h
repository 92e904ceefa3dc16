// The fuzz_web_face seeds the writer makes (fuzz/write_web_face_seeds.cpp writes them into
// fuzz/corpus/fuzz_web_face/current_NAME.myoweb): each reaches one part of the format at its
// current version, so a replay exercises the parser, not only the version check. A format change
// makes the test WebFaceFile.TheFuzzSeedsAreAtTheCurrentFormat fail until they are written again.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "myoshell/io/web_face_file.h"

namespace myo::fuzz {

struct WebFaceSeed {
  std::string name;  // the file is current_<name>.myoweb
  std::vector<MuscleDef> muscles;
  std::vector<SceneDesc> takes;
  FacsMap facs;
};

// A 4-vertex, 3-mode basis with fixed values (small: libFuzzer mutates files of a few KB).
inline ModalBasis webFaceSeedBasis() {
  ModalBasis b;
  b.fullVertexCount = 4;
  b.freeVertices = {0, 1, 2, 3};
  b.lambda = VecX::LinSpaced(3, 10.0, 30.0);
  b.freeMass = VecX::Constant(4, 0.25);
  b.Phi = MatX(12, 3);
  for (Eigen::Index i = 0; i < b.Phi.size(); ++i) b.Phi.data()[i] = 0.01 * static_cast<double>(i % 7) - 0.03;
  b.Psi = MatX::Zero(12, 3);
  return b;
}

inline BasisKey webFaceSeedKey() {
  BasisKey k;
  k.words = {0x0123456789abcdefULL, 0xfedcba9876543210ULL};
  return k;
}

// One seed per feature of the whole face's muscles the format carries (a thickening muscle, a
// ring with the lip's body, a pushing muscle, a continuing one, a ring
// with a hoop), a take, a FACS map, all together.
inline std::vector<WebFaceSeed> webFaceSeeds() {
  const std::vector<MuscleDef>& face = faceMuscleDefs();
  const auto first = [&](const std::function<bool(const MuscleDef&)>& has) {
    for (const MuscleDef& m : face)
      if (has(m)) return m;
    throw InputError("fuzz seeds: the whole face has no muscle of a kind a seed needs");
  };
  const MuscleDef thickens = first([](const MuscleDef& m) { return m.thickens && !m.continuesInto; });
  const MuscleDef lipBody = first([](const MuscleDef& m) { return m.ring.lipBody; });
  const MuscleDef pushes = first([](const MuscleDef& m) { return m.pushes.has_value(); });
  const MuscleDef continues = first([](const MuscleDef& m) { return m.continuesInto.has_value(); });
  const MuscleDef hoop = first([](const MuscleDef& m) { return m.ring.hoop.has_value(); });
  SceneDesc take;
  take.name = "smile";
  take.duration = 1.5;
  take.fps = 24.0;
  take.activations[thickens.name] = ScalarTrack({{0.0, 0.0, Interpolation::Smooth}, {0.5, 0.75, Interpolation::Step}, {1.0, 0.25}});
  take.jawOpen = ScalarTrack({{0.2, 0.0}, {0.9, 12.5, Interpolation::Smooth}});
  FacsMap facs;
  for (const FacsEntry& e : builtinFacsMap().entries)
    if (facs.entries.size() < 4) facs.entries.push_back(e);
  return {
      {"thickens", {thickens}, {}, {}},
      {"lip_body", {lipBody}, {}, {}},
      {"pushes", {pushes}, {}, {}},
      {"continues_into", {continues}, {}, {}},
      {"hoop", {hoop}, {}, {}},
      {"take", {thickens}, {take}, {}},
      {"facs", {thickens}, {}, facs},
      {"all", {thickens, lipBody, pushes, continues, hoop}, {take}, facs},
  };
}

}  // namespace myo::fuzz
