// myoshell-web-data OUT [--cache DIR] [--take SCENE]...: writes the page's face data
// (io/web_face_file.h): the whole face's muscles and the released basis of the built-in head's
// anatomical face, the face the page builds (web/web_face.h), the takes it plays (each SCENE's
// timeline) and the FACS map (assets/facs/au_map.json) its action-unit sliders go through. The
// basis comes from the basis cache (DIR, else the CLI's default folder) or is computed and stored
// there. Checks that the face is the one `myoshell pose` builds for the built-in
// head and the one `myoshell run` builds for each take (same basis key, dt and muscles), so the
// page's shapes compare with theirs.
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>
#include <vector>

#include "../web/web_face.h"
#include "myoshell/anatomy/anatomical_skin.h"
#include "myoshell/core/errors.h"
#include "myoshell/io/basis_cache_file.h"
#include "myoshell/io/scene_face.h"
#include "myoshell/fit/facs_map.h"
#include "myoshell/io/web_face_file.h"
#include "myoshell/muscles/muscle_def.h"

namespace {

// Forwards to a file cache and keeps every basis it loads or stores, by key.
class KeepingCache : public myo::BasisCache {
 public:
  explicit KeepingCache(myo::BasisCache& inner) : inner_(inner) {}
  std::optional<myo::ModalBasis> load(const myo::BasisKey& key) override {
    std::optional<myo::ModalBasis> b = inner_.load(key);
    if (b) kept[key.hex()] = *b;
    return b;
  }
  void store(const myo::BasisKey& key, const myo::ModalBasis& basis) override {
    kept[key.hex()] = basis;
    inner_.store(key, basis);
  }
  std::map<std::string, myo::ModalBasis> kept;

 private:
  myo::BasisCache& inner_;
};

}  // namespace

int main(int argc, char** argv) {
  std::string out, dir;
  std::vector<std::string> takePaths;
  bool usage = false;
  for (int i = 1; i < argc && !usage; ++i) {
    const std::string a = argv[i];
    if (a == "--cache" && i + 1 < argc) dir = argv[++i];
    else if (a == "--take" && i + 1 < argc) takePaths.push_back(argv[++i]);
    else if (out.empty() && !a.starts_with("--")) out = a;
    else usage = true;
  }
  if (out.empty() || usage) {
    std::fprintf(stderr, "usage: myoshell-web-data OUT [--cache DIR] [--take SCENE]...\n");
    return 2;
  }
  try {
    // The CLI's default cache folder (apps/cli/resources.h): $MYOSHELL_CACHE, $XDG_CACHE_HOME/myoshell,
    // ~/.cache/myoshell.
    const auto env = [](const char* name) { return std::string(std::getenv(name) ? std::getenv(name) : ""); };
    if (dir.empty()) dir = env("MYOSHELL_CACHE");
    if (dir.empty() && !env("XDG_CACHE_HOME").empty()) dir = env("XDG_CACHE_HOME") + "/myoshell";
    if (dir.empty() && !env("HOME").empty()) dir = env("HOME") + "/.cache/myoshell";
    if (dir.empty()) dir = "myoshell-cache";
    myo::FileBasisCache files(dir);
    KeepingCache cache(files);
    const std::vector<myo::MuscleDef>& muscles = myo::faceMuscleDefs();
    const auto face = myo::web::buildWebFace(muscles, &cache);
    const myo::AnatomicalSkin& skin = face->skin();
    if (skin.settings().warping) throw myo::InputError("the page steps linear modes: warping must be off");

    myo::SceneDesc scene;  // what `myoshell pose` builds for the built-in head
    scene.name = "pose";
    const auto pose = myo::buildSceneFace(scene, &files);
    const auto* poseFace = dynamic_cast<const myo::AnatomicalFace*>(pose.get());
    if (!poseFace || !(poseFace->skin().releasedBasisKey() == skin.releasedBasisKey()))
      throw myo::InputError("the page's face is not the one `myoshell pose` builds (basis keys differ)");

    // Each take plays on the page's face: `myoshell run SCENE` builds the same one.
    std::vector<myo::SceneDesc> takes;
    for (const std::string& path : takePaths) {
      myo::SceneDesc take = myo::readScene(path);
      const auto built = myo::buildSceneFace(take, &files);
      const auto* f = dynamic_cast<const myo::AnatomicalFace*>(built.get());
      if (!f || !(f->skin().releasedBasisKey() == skin.releasedBasisKey()) || f->dt() != face->dt() ||
          f->skin().muscleNames() != skin.muscleNames())
        throw myo::InputError(path + ": the take's face is not the page's (the built-in head's anatomical face, the "
                              "whole face's muscles, the default settings)");
      takes.push_back(std::move(take));
    }

    const std::string key = skin.releasedBasisKey().hex();
    if (!cache.kept.count(key)) throw myo::InputError("the released basis " + key + " was neither loaded nor built");
    myo::writeWebFaceFile(out, muscles, skin.releasedBasisKey(), cache.kept.at(key), takes, myo::builtinFacsMap());
    std::printf("wrote %s: %zu muscles, basis %s (%d vertices, %d modes), %zu take(s)\n", out.c_str(), muscles.size(),
                key.c_str(), skin.basis()->freeCount(), skin.basis()->modeCount(), takes.size());
    return 0;
  } catch (const myo::InputError& e) {
    std::fprintf(stderr, "myoshell-web-data: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "myoshell-web-data: %s\n", e.what());
    return 1;
  }
}
