// The ICT-FaceKit head and its ARKit rig from ../shared/data (test_data.h finds the folder), for the
// tests that compare the face with ICT's artist shapes. Call MYO_REQUIRE_SHARED_DATA() first.
#pragma once

#include "myoshell/head/head.h"
#include "myoshell/io/head_files.h"
#include "myoshell/io/rig_file.h"
#include "support/test_data.h"

namespace myo::test {

// The skin with its 68 landmarks (no gravity pins: the anatomical model needs none).
inline Head ictHead() {
  const auto dir = sharedDataDir() / "ict";
  return loadHead((dir / "head_skin.obj").string(), (dir / "landmarks_multipie68.json").string());
}

// ict_arkit_rig.glb, read once per process.
inline const RigFile& ictRig() {
  static const RigFile rig = readRig((sharedDataDir() / "ict" / "ict_arkit_rig.glb").string());
  return rig;
}

}  // namespace myo::test
