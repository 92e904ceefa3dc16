#include "myoshell/io/rig_making.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <optional>

#include "myoshell/anatomy/anatomical_skin.h"
#include "myoshell/core/errors.h"
#include "myoshell/core/timer.h"
#include "myoshell/fit/arkit_rig.h"
#include "myoshell/head/jaw.h"
#include "myoshell/io/fit_head.h"
#include "myoshell/io/output_paths.h"
#include "myoshell/io/retarget_map_file.h"
#include "myoshell/muscles/muscle_def.h"

namespace myo {
namespace {

namespace fs = std::filesystem;

bool endsWithGlb(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext == ".glb";
}

}  // namespace

void checkRigOutputPath(const std::string& path) {
  checkOutputFile(path, "--out", "rig file (.glb)");
  if (!endsWithGlb(path)) throw InputError("--out: a rig is written as a glTF binary; give a file name ending in .glb", path);
}

RetargetMap readRigMap(const std::string& path, const std::vector<MuscleDef>& muscleDefs, const std::string& library) {
  if (path.empty()) {
    if (const RetargetMap* shipped = shippedRetargetMap(library)) return *shipped;
    throw InputError("--map: a library file has no shipped map; give the map fitted with it (fit-rig --library " +
                     library + " --out MAP.json)");
  }
  std::vector<std::string> muscles;
  for (const MuscleDef& d : muscleDefs) muscles.push_back(d.name);
  // The library the map records, checked before its muscle names so the error names both libraries.
  const std::string recorded = readRetargetMapFile(path).library;
  if (!recorded.empty() && recorded != muscleLibraryLabel(library))
    throw InputError("the map is for the muscle library '" + recorded + "', and the head's is '" +
                         muscleLibraryLabel(library) + "': give --library " + recorded,
                     path);
  RetargetMap map;
  try {
    map = readRetargetMapFile(path, muscles);
  } catch (const InputError&) {
    // A map fitted with the whole face's muscles needs that library: say so rather than "unknown
    // muscle" (the map is read again, without the muscle list, on this error path only).
    if (library != "face")
      for (const std::string& name : readRetargetMapFile(path).muscleNames())
        if (std::find(muscles.begin(), muscles.end(), name) == muscles.end() &&
            std::any_of(faceMuscleDefs().begin(), faceMuscleDefs().end(), [&](const MuscleDef& d) { return d.name == name; }))
          throw InputError("the map uses the whole face's muscles (" + name + ", …): give --library face", path);
    throw;
  }
  for (const RetargetShape& s : map.shapes)
    try {
      jawPoseOf(s);  // a jaw value's name, here where the file can be named
    } catch (const InputError& e) {
      throw InputError(e.message(), path);
    }
  return map;
}

MadeRig makeArkitRig(const SceneInputs& inputs, const RetargetMap& map, BasisCache* cache) {
  MadeRig made;
  const Stopwatch buildClock;
  const AnatomicalSkin skin(inputs.head, inputs.muscles, inputs.anatomical, {}, cache);
  made.buildSeconds = buildClock.seconds();
  const Stopwatch settleClock;
  // Placed as the playing face places them: the map's jaw shapes (jawOpen, …) move the jaw of a head
  // with the 68-point jaw line, its lid muscles (eyeBlink, eyeWide, …) turn the lids of a head with
  // open eyes, the contact keeps the skin out of eyeballs, teeth and the other lip.
  made.settled = settleArkitRig(skin, map);
  made.settleSeconds = settleClock.seconds();

  const Head& head = skin.head();
  RigExport& rig = made.glb;
  rig.name = head.name;
  rig.rest = head.mesh.V;
  rig.triangles = head.mesh.F;
  rig.uv = head.mesh.UV;
  rig.cornerUV = head.mesh.cornerUV;  // an OBJ head's UV seams become appended duplicate vertices
  for (const ArkitRigShape& s : made.settled.shapes) {
    rig.names.push_back(s.name);
    rig.deltas.push_back(s.delta);
  }
  return made;
}

}  // namespace myo
