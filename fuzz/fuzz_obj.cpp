// Fuzzes the OBJ reader: strict, lenient and "like a rest mesh" reads of the same bytes.
// Properties checked on top of "only InputError":
//   - a strict read that succeeds gives finite positions, at least one triangle, in-range indices;
//   - the lenient read reports no fault exactly when the strict read succeeds;
//   - a mesh read strictly reads back "like" itself with the same positions and triangles;
//   - corner UVs: 0 or 3 per triangle; read from the file alone, present exactly when UVs are.
#include <cmath>

#include "fuzz_common.h"
#include "myoshell/core/errors.h"
#include "myoshell/mesh/obj_reader.h"

namespace {

// readOnly: the mesh comes from this file alone (not read "like" a rest), so its corner UVs are known.
void checkMesh(const myo::TriMesh& m, bool readOnly) {
  FUZZ_EXPECT(m.F.rows() == static_cast<Eigen::Index>(m.sourcePolygon.size()), "one source polygon per triangle");
  for (Eigen::Index t = 0; t < m.F.rows(); ++t)
    for (int k = 0; k < 3; ++k) FUZZ_EXPECT(m.F(t, k) >= 0 && m.F(t, k) < m.V.rows(), "triangle index in range");
  FUZZ_EXPECT(m.UV.rows() == 0 || m.UV.rows() == m.V.rows(), "UV rows");
  FUZZ_EXPECT(m.cornerUV.rows() == 0 || m.cornerUV.rows() == 3 * m.F.rows(), "corner UV rows: 0 or 3 per triangle");
  if (readOnly) FUZZ_EXPECT((m.cornerUV.rows() > 0) == (m.UV.rows() > 0), "corner UVs exactly when UVs");
  for (const auto& [name, set] : m.groups)
    for (int v : set) FUZZ_EXPECT(v >= 0 && v < m.V.rows(), "group vertex in range");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text = myo::fuzz::text(data, size);
  bool strictOk = false;
  myo::TriMesh rest;
  try {
    rest = myo::readObjFromString(text, "fuzz.obj");
    strictOk = true;
    checkMesh(rest, true);
    FUZZ_EXPECT(rest.F.rows() > 0, "a strict mesh has faces");
    FUZZ_EXPECT(rest.V.allFinite(), "a strict mesh has finite positions");
  } catch (const myo::InputError&) {
  }
  try {
    myo::MeshReport report;
    const myo::TriMesh lenient = myo::readObjFromStringLenient(text, report, "fuzz.obj");
    checkMesh(lenient, true);
    FUZZ_EXPECT(report.faults.empty() == strictOk, "lenient read finds faults exactly when the strict read fails");
  } catch (const myo::InputError&) {
    FUZZ_EXPECT(!strictOk, "lenient read throws only when the strict read does");
  }
  if (strictOk) {
    const myo::TriMesh like = myo::readObjLikeFromString(text, rest, "fuzz_like.obj");
    checkMesh(like, false);
    FUZZ_EXPECT(like.V.rows() == rest.V.rows() && like.F == rest.F, "a mesh reads like itself");
    FUZZ_EXPECT((like.V.array() == rest.V.array()).all(), "same positions");
  }
  return 0;
}
