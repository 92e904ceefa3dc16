// Fuzzes the glTF rig reader (io/rig_file.h) on the same bytes read as .glb and as .gltf. A rig
// that reads is consistent: one shape per name, every shape n×3 and finite, triangle and weld
// indices in range. Side-car buffers point into a folder that does not exist, so the target
// never reads the machine's files.
#include "fuzz_common.h"
#include "myoshell/core/errors.h"
#include "myoshell/io/rig_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string bytes = myo::fuzz::text(data, size);
  for (const char* path : {"/nonexistent-myo-fuzz/rig.glb", "/nonexistent-myo-fuzz/rig.gltf"}) {
    myo::RigFile rig;
    try {
      rig = myo::parseRig(bytes, path);
    } catch (const myo::InputError&) {
      continue;
    }
    const Eigen::Index n = rig.base.V.rows();
    FUZZ_EXPECT(n > 0 && rig.base.V.allFinite(), "finite base");
    FUZZ_EXPECT(rig.names.size() == rig.targets.size() && !rig.names.empty(), "one shape per name");
    for (const myo::MatX3& t : rig.targets) FUZZ_EXPECT(t.rows() == n && t.allFinite(), "shape n×3, finite");
    FUZZ_EXPECT(rig.base.F.rows() > 0, "triangles");
    FUZZ_EXPECT(rig.base.F.minCoeff() >= 0 && rig.base.F.maxCoeff() < n, "triangle index in range");
    for (int w : rig.weldedIndex) FUZZ_EXPECT(w >= 0 && w < n, "weld index in range");
    for (const std::string& name : rig.names) FUZZ_EXPECT(rig.find(name) >= 0, "names found");
  }
  return 0;
}
