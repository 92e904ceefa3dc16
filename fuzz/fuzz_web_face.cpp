// Fuzzes the web page's face data reader (io/web_face_file.h, `face.myoweb`; docs/web.md). The file
// ends in a checksum of everything before it, which a mutation almost always breaks: the target
// reads the bytes as given (the checksum must refuse them, never crash) and then with the checksum
// made right, so the mutations reach the parser. A file that reads has a basis whose sizes agree
// (Φ 3f×d, λ d, masses f, Ψ zero, free vertices in range), takes with a positive duration and fps,
// FACS weights in [0, 1], each AU once; written back and read again it gives the same bytes.
#include <cstring>

#include "fuzz_common.h"
#include "myoshell/core/errors.h"
#include "myoshell/io/web_face_file.h"

namespace {

void check(const myo::WebFace& w) {
  const myo::ModalBasis& b = w.basis;
  const auto f = static_cast<Eigen::Index>(b.freeVertices.size());
  FUZZ_EXPECT(b.Phi.rows() == 3 * f && b.Phi.cols() == b.lambda.size(), "Φ is 3f×d");
  FUZZ_EXPECT(b.Psi.rows() == b.Phi.rows() && b.Psi.cols() == b.Phi.cols() && (b.Psi.size() == 0 || b.Psi.isZero()),
              "Ψ zero, the size of Φ");
  FUZZ_EXPECT(b.freeMass.size() == f, "a mass per free vertex");
  FUZZ_EXPECT(f <= b.fullVertexCount, "no more free vertices than vertices");
  for (const int v : b.freeVertices) FUZZ_EXPECT(v >= 0 && v < b.fullVertexCount, "free vertices in range");
  for (const myo::SceneDesc& t : w.takes) {
    FUZZ_EXPECT(t.duration > 0.0 && t.fps > 0.0, "a take lasts and has frames");
    for (const auto& [muscle, track] : t.activations)
      for (size_t k = 1; k < track.keys().size(); ++k)
        FUZZ_EXPECT(track.keys()[k].time > track.keys()[k - 1].time, "keys in order");
  }
  for (const myo::FacsEntry& e : w.facs.entries) {
    FUZZ_EXPECT(e.au >= 1 && e.au <= 999, "AU number in range");
    FUZZ_EXPECT(w.facs.find(e.au) == &e, "each AU once");
    for (const auto& [muscle, weight] : e.muscles) FUZZ_EXPECT(weight >= 0.0 && weight <= 1.0, "weight in [0, 1]");
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::string bytes = myo::fuzz::text(data, size);
  for (int pass = 0; pass < 2; ++pass) {
    if (pass == 1) {  // the checksum made right
      if (bytes.size() < 16) return 0;
      const std::uint64_t sum = myo::fnv1a64(bytes.data(), bytes.size() - 8);
      std::memcpy(bytes.data() + bytes.size() - 8, &sum, 8);
    }
    myo::WebFace w;
    try {
      w = myo::readWebFace(bytes, "fuzz.myoweb");
    } catch (const myo::InputError&) {
      continue;
    }
    check(w);
    std::string again;
    try {
      again = myo::webFaceBytes(w.muscles, w.basisKey, w.basis, w.takes, w.facs);
    } catch (const myo::InputError&) {
      continue;  // the writer refuses what it would not write (an imported muscle cannot be read)
    }
    FUZZ_EXPECT(again == bytes, "written back, the same bytes");
  }
  return 0;
}
