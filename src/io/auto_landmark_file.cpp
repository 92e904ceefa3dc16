#include "myoshell/io/auto_landmark_file.h"

#include <chrono>
#include <functional>
#include <nlohmann/json.hpp>

#include "myoshell/core/atomic_file.h"
#include "myoshell/core/errors.h"
#include "myoshell/core/whole_file.h"
#include "myoshell/io/head_files.h"
#include "myoshell/mesh/obj_reader.h"
#include "myoshell/reduce/basis_cache.h"

namespace myo {

namespace fs = std::filesystem;

namespace {

// Bump when findLandmarks changes what it finds: kept files of older searches are then not reused.
constexpr int kSearchVersion = 8;  // 8: the nose seed near the top (a neck or shoulders below the face cannot hold the most forward point); 7: a jaw point on the outline's vertex (silhouette or open boundary, not behind) within twice the nearest vertex's distance; 6: the jaw outline's frame across the eye openings' centres; 5: a mask's jaw line on its rim; 2: the jaw line on the frontal outline; 3: outer eye corners on the openings, lids and brows from the eye frame, the jaw by angle; 4: the outline seen frontally at the sides, the nose bridge at thirds, labels to the nearest skin vertex

// A kept search: its landmarks and the "automatic" object.
struct KeptSearch {
  AutoLandmarks found;
  nlohmann::json automatic;
};

std::optional<KeptSearch> readKept(const fs::path& path, int vertexCount) {
  const std::optional<std::string> text = tryReadWholeFile(path.string());
  if (!text) return std::nullopt;
  try {  // an unreadable or foreign file is searched again and overwritten
    const nlohmann::json j = nlohmann::json::parse(*text);
    if (!j.contains("automatic") || j["automatic"].value("version", 0) != kSearchVersion) return std::nullopt;
    KeptSearch k;
    k.found.landmarks = parseLandmarks(*text, vertexCount, path.string());
    k.automatic = j["automatic"];
    k.found.unit = parseLengthUnit(k.automatic.at("units").get<std::string>());
    k.found.unitInferred = k.automatic.at("units_inferred").get<bool>();
    k.found.eyesOpen = k.automatic.at("eyes").get<std::string>() == "open";
    k.found.mouthOpen = k.automatic.at("mouth").get<std::string>() == "open";
    k.found.warnings = k.automatic.at("warnings").get<std::vector<std::string>>();
    if (k.found.landmarks.multipie68.size() != 68) return std::nullopt;
    return k;
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

FoundLandmarkFile describe(const std::string& obj, const fs::path& path, const AutoLandmarks& a) {
  FoundLandmarkFile f;
  f.obj = obj;
  f.path = path.string();
  f.unit = a.unit;
  f.unitInferred = a.unitInferred;
  f.eyesOpen = a.eyesOpen;
  f.mouthOpen = a.mouthOpen;
  f.warnings = a.warnings;
  return f;
}

// The vertex count of an OBJ's text without building the mesh: its "v " lines.
int objVertexCount(const std::string& text) {
  int n = 0;
  size_t at = 0;
  while (at < text.size()) {
    while (at < text.size() && (text[at] == ' ' || text[at] == '\t')) ++at;
    if (at + 1 < text.size() && text[at] == 'v' && (text[at + 1] == ' ' || text[at + 1] == '\t')) ++n;
    at = text.find('\n', at);
    if (at == std::string::npos) break;
    ++at;
  }
  return n;
}

// Writes the landmark file of `found` (the search on `source`) at `path`, making its folder.
std::string storeAt(const fs::path& path, const AutoLandmarks& found, const std::string& source) {
  std::error_code ec;
  fs::create_directories(path.parent_path(), ec);
  if (ec) throw InputError("cannot make the landmark folder " + path.parent_path().string() + ": " + ec.message());
  writeFileAtomically(path.string(), autoLandmarkFileText(found, source), "cannot write landmark file");
  return path.string();
}

// The search kept for `key` (a head's bytes) in the cache folder, else findLandmarks(mesh()) kept
// there (in the temporary folder when the cache folder cannot be written). `unit` given wins.
FoundLandmarkFile findOrReuse(const std::string& key, int vertexCount, const std::function<TriMesh()>& mesh,
                              const std::string& source, const fs::path& cacheDir, std::optional<LengthUnit> unit) {
  const fs::path path = landmarkFilePath(key, cacheDir);
  if (std::optional<KeptSearch> kept = readKept(path, vertexCount)) {
    FoundLandmarkFile f = describe(source, path, kept->found);
    f.reused = true;
    if (unit) {  // the unit given wins; loadHead checks it against the head's size
      f.unit = *unit;
      f.unitInferred = false;
    }
    return f;
  }
  const auto t0 = std::chrono::steady_clock::now();
  AutoLandmarkOptions options;
  options.unit = unit;
  const AutoLandmarks found = findLandmarks(mesh(), options);
  std::string written;
  try {
    written = storeAt(path, found, source);
  } catch (const InputError&) {  // a read-only (shared) cache folder: the temporary folder keeps it
    if (cacheDir.empty()) throw;
    written = storeAt(landmarkFilePath(key, {}), found, source);
  }
  FoundLandmarkFile f = describe(source, written, found);
  f.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return f;
}

}  // namespace

fs::path landmarkFileFolder(const fs::path& cacheDir) {
  if (cacheDir.empty()) return fs::temp_directory_path() / "myoshell-landmarks";
  return cacheDir / "landmarks";
}

fs::path landmarkFilePath(const std::string& objBytes, const fs::path& cacheDir) {
  KeyHasher h;
  h.str("myoshell.auto_landmarks").pod(kSearchVersion).str(objBytes);
  return landmarkFileFolder(cacheDir) / (h.key().hex() + ".landmarks.json");
}

std::string autoLandmarkFileText(const AutoLandmarks& a, const std::string& source) {
  nlohmann::ordered_json j = nlohmann::ordered_json::parse(landmarksToJson(a.landmarks));
  nlohmann::ordered_json out;
  out["source"] = "myoshell landmarks " + source + " (automatic; edit any point and pass the file as --landmarks)";
  out["multipie68"] = j["multipie68"];
  out["named"] = j["named"];
  for (auto& [name, e] : out["named"].items())
    if (a.namedConfidence.count(name)) e["confidence"] = a.namedConfidence.at(name);
  if (!a.confidence68.empty()) out["confidence"]["multipie68"] = a.confidence68;
  out["automatic"] = {{"version", kSearchVersion},
                      {"units", lengthUnitName(a.unit)},
                      {"units_inferred", a.unitInferred},
                      {"eyes", a.eyesOpen ? "open" : "closed"},
                      {"mouth", a.mouthOpen ? "open" : "closed"},
                      {"warnings", a.warnings}};
  return out.dump(1) + "\n";
}

std::string storeAutoLandmarks(const std::string& obj, const AutoLandmarks& found, const fs::path& cacheDir) {
  return storeAt(landmarkFilePath(readWholeFile(obj, "cannot open head OBJ"), cacheDir), found, obj);
}

FoundLandmarkFile findLandmarkFile(const std::string& obj, const fs::path& cacheDir, std::optional<LengthUnit> unit) {
  const std::string bytes = readWholeFile(obj, "cannot open head OBJ");
  return findOrReuse(bytes, objVertexCount(bytes), [&] { return readObjFromString(bytes, obj); }, obj, cacheDir, unit);
}

FoundLandmarkFile findRigBaseLandmarkFile(const RigFile& rig, const fs::path& cacheDir) {
  const TriMesh& base = rig.base;
  // The key is the base's geometry as read (in cm), not the file's bytes: a rig re-exported with
  // other shapes or names keeps its head's landmarks.
  std::string key = "rig base\n";
  key.append(reinterpret_cast<const char*>(base.V.data()), sizeof(double) * base.V.size());
  key.append(reinterpret_cast<const char*>(base.F.data()), sizeof(int) * base.F.size());
  return findOrReuse(key, base.vertexCount(), [&] { return base; }, rig.path + "'s base mesh", cacheDir, LengthUnit::cm);
}

std::vector<std::string> checkLandmarkFile(const std::string& obj, const std::string& landmarks, const fs::path& cacheDir) {
  const std::optional<std::string> bytes = tryReadWholeFile(obj);
  if (!bytes) return {};  // the head's reader names the fault
  const fs::path path = landmarkFilePath(*bytes, cacheDir);
  if (!fs::exists(path)) return {};
  const TriMesh mesh = readObjFromString(*bytes, obj);
  std::optional<KeptSearch> kept = readKept(path, mesh.vertexCount());
  if (!kept) return {};
  const Landmarks given = readLandmarks(landmarks, mesh.vertexCount());
  std::vector<std::string> warnings = checkGivenLandmarks(mesh, given, kept->found);
  for (const std::string& w : kept->found.warnings)  // what the model cannot do with this head
    if (w.find("no opening") != std::string::npos) warnings.push_back(w);
  return warnings;
}

std::optional<FoundLandmarkFile> completeSceneHead(SceneDesc& scene, const fs::path& cacheDir,
                                                   std::vector<std::string>* warnings) {
  if (scene.head.obj.empty()) return std::nullopt;
  // As readSceneInputs resolves them: absolute, or relative to the scene's folder.
  const fs::path base =
      scene.path.empty() || scene.path.front() == '<' ? fs::path() : fs::path(scene.path).parent_path();
  auto resolve = [&](const std::string& p) { return fs::path(p).is_absolute() ? p : (base / p).string(); };
  const std::string obj = resolve(scene.head.obj);
  if (!scene.head.landmarks.empty()) {
    std::vector<std::string> w = checkLandmarkFile(obj, resolve(scene.head.landmarks), cacheDir);
    if (warnings) warnings->insert(warnings->end(), w.begin(), w.end());
    return std::nullopt;
  }
  FoundLandmarkFile f =
      findLandmarkFile(obj, cacheDir, scene.head.unitsGiven ? std::optional<LengthUnit>(scene.head.units) : std::nullopt);
  scene.head.landmarks = f.path;  // absolute unless the cache folder is relative
  scene.head.landmarks = fs::absolute(scene.head.landmarks).string();
  scene.head.units = f.unit;
  return f;
}

}  // namespace myo
