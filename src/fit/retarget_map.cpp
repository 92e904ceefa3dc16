#include "myoshell/fit/retarget_map.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <nlohmann/json.hpp>
#include <set>

#include "myoshell/anatomy/eyelids.h"
#include "myoshell/anatomy/mouth_pressure.h"
#include "myoshell/core/check.h"
#include "myoshell/core/close_names.h"
#include "myoshell/core/doc_reader.h"
#include "myoshell/core/errors.h"
#include "myoshell/fit/arkit_names.h"
#include "myoshell/muscles/muscle_def.h"

namespace myo {
namespace detail {
extern const char kUnreachableShapesJson[];
extern const char kArkitIctFaceMapJson[];
extern const char kArkitIctMapJson[];
}  // namespace detail

namespace {

constexpr const char* kFormat = "myoshell-retarget-map";
constexpr int kVersion = 1;

// The ARKit name of a spelling, or an error at `at` with canonicalArkitName's suggestions.
std::string arkitNameAt(const DocReader& r, const YAML::Node& at, const std::string& keyPath, const std::string& spelling) {
  try {
    return canonicalArkitName(spelling);
  } catch (const InputError& e) {
    r.failAt(at, keyPath, e.message());
  }
}

// A mapping of name → number, each value checked by `check` (which fails at the value).
template <class Check>
NamedValues readNamedValues(DocReader& r, const std::string& key, Check check) {
  NamedValues out;
  if (!r.has(key)) {
    r.string(key, "");  // marks the key used when present but null
    return out;
  }
  const YAML::Node node = r.node(key);
  const std::string path = r.keyPath(key);
  if (!node.IsMap()) r.failAt(node, path, "must be an object of name: value");
  std::set<std::string> seen;
  for (const auto& kv : node) {
    const std::string name = r.asString(kv.first, path);
    const std::string at = path + "." + name;
    if (!seen.insert(name).second) r.failAt(kv.first, at, "is given twice");
    const double v = r.asNumber(kv.second, at);
    check(kv.first, kv.second, at, name, v);
    out.emplace_back(name, v);
  }
  return out;
}

}  // namespace

const char* toString(RetargetSource source) { return source == RetargetSource::Derived ? "derived" : "fitted"; }

const RetargetShape* RetargetMap::find(const std::string& anySpelling) const {
  const std::optional<std::string> name = findArkitName(anySpelling);
  if (!name) return nullptr;
  for (const RetargetShape& s : shapes)
    if (s.name == *name) return &s;
  return nullptr;
}

std::vector<std::string> RetargetMap::muscleNames() const {
  std::set<std::string> names;
  for (const RetargetShape& s : shapes)
    for (const auto& [muscle, value] : s.activations) names.insert(muscle);
  return {names.begin(), names.end()};
}

NamedValues RetargetMap::totalActivations(const RetargetShape& shape) const {
  NamedValues out = shape.activations;
  if (shape.correctiveOf.empty()) return out;
  const RetargetShape* base = find(shape.correctiveOf);
  MYO_CHECK(base != nullptr, "corrective of a shape the map does not hold: " << shape.correctiveOf);
  for (const auto& entry : base->activations) {
    auto it = std::find_if(out.begin(), out.end(), [&](const auto& p) { return p.first == entry.first; });
    if (it == out.end()) out.push_back(entry);
    else it->second += entry.second;
  }
  return out;
}

RetargetMap readRetargetMap(const YAML::Node& root, const std::string& name, const std::vector<std::string>& knownMuscles) {
  DocReader top(root, name);
  const std::string format = top.requiredString("format");
  if (format != kFormat) top.fail("format", "must be \"" + std::string(kFormat) + "\" (got \"" + format + "\")");
  const int version = top.integer("version", -1);
  if (version != kVersion)
    top.fail("version", "this Myoshell reads version " + std::to_string(kVersion) + (top.has("version") ? "" : " (missing)"));
  RetargetMap map;
  map.rig = top.string("rig", "");
  map.head = top.string("head", "");
  map.model = top.string("model", "anatomical");
  if (map.model != "anatomical") top.fail("model", "must be \"anatomical\" (the model maps are fitted with)");
  map.library = top.string("library", "");
  if (top.has("library") && map.library.empty()) top.fail("library", "must name the muscle library (builtin, face or a file's name)");
  map.note = top.string("note", "");
  const YAML::Node list = top.node("shapes");
  if (!list.IsSequence()) top.failAt(list, "shapes", "must be a list of {name, activations, …}");
  if (list.size() == 0) top.failAt(list, "shapes", "must hold at least one shape");
  top.finish();

  const std::set<std::string> muscles(knownMuscles.begin(), knownMuscles.end());
  std::map<std::string, size_t> firstEntry;  // ARKit name → the entry that gave it
  std::vector<YAML::Node> correctiveNodes(list.size());
  for (size_t i = 0; i < list.size(); ++i) {
    DocReader r(list[i], name, "shapes[" + std::to_string(i) + "]");
    RetargetShape s;
    const YAML::Node nameNode = r.node("name");
    const std::string spelling = r.asString(nameNode, r.keyPath("name"));
    s.name = arkitNameAt(r, nameNode, r.keyPath("name"), spelling);
    if (const auto [it, fresh] = firstEntry.emplace(s.name, i); !fresh)
      r.failAt(nameNode, r.keyPath("name"),
               "'" + spelling + "' is " + s.name + ", already given by shapes[" + std::to_string(it->second) + "]");
    s.reachable = r.boolean("reachable", true);
    s.reason = r.string("reason", "");
    const bool hasSource = r.has("source");
    const std::string source = r.string("source", "fitted");
    if (source == "derived") s.source = RetargetSource::Derived;
    else if (source != "fitted") r.fail("source", "must be \"fitted\" or \"derived\" (got \"" + source + "\")");
    if (r.has("corrective_of")) {
      correctiveNodes[i] = r.node("corrective_of");
      s.correctiveOf = arkitNameAt(r, correctiveNodes[i], r.keyPath("corrective_of"),
                                   r.asString(correctiveNodes[i], r.keyPath("corrective_of")));
      if (s.correctiveOf == s.name) r.failAt(correctiveNodes[i], r.keyPath("corrective_of"), "a shape cannot correct itself");
    }
    const double lo = s.correctiveOf.empty() ? 0.0 : -1.0;
    s.activations = readNamedValues(r, "activations", [&](const YAML::Node& key, const YAML::Node& value, const std::string& at,
                                                          const std::string& muscle, double v) {
      if (!muscles.empty() && !muscles.count(muscle))
        r.failAt(key, at, "unknown muscle '" + muscle + "' (the model's muscles: " + joinNames(knownMuscles) + ")");
      if (v < lo || v > 1.0)
        r.failAt(value, at,
                 "activation " + value.Scalar() + " is outside " +
                     (s.correctiveOf.empty() ? "[0, 1]" : "[-1, 1] (a corrective's difference from its base)"));
    });
    s.jaw = readNamedValues(r, "jaw", [](const YAML::Node&, const YAML::Node&, const std::string&, const std::string&, double) {});
    s.gaze = readNamedValues(r, "gaze", [&](const YAML::Node& key, const YAML::Node& value, const std::string& at,
                                            const std::string& dof, double v) {
      if (dof != "left_pitch" && dof != "left_yaw" && dof != "right_pitch" && dof != "right_yaw")
        r.failAt(key, at, "'" + dof + "' is not left_pitch, left_yaw, right_pitch or right_yaw");
      if (!(std::abs(v) <= kGazeMaxDeg))
        r.failAt(value, at, "turn " + value.Scalar() + " degrees is outside [-45, 45]");
    });
    s.mouthPressureKpa = r.number("mouth_pressure_kpa", 0.0);
    r.requireWithin("mouth_pressure_kpa", s.mouthPressureKpa, 0.0, kMouthPressureMaxKpa);
    if (r.has("fit")) {
      DocReader f = r.child("fit");
      RetargetFitFigures fig;
      fig.cosine = f.requiredNumber("cosine");
      f.requireWithin("cosine", fig.cosine, -1.0, 1.0);
      fig.magnitudeRatio = f.requiredNumber("magnitude_ratio");
      f.requireAtLeast("magnitude_ratio", fig.magnitudeRatio, 0.0);
      fig.rmsMm = f.requiredNumber("rms_mm");
      f.requireAtLeast("rms_mm", fig.rmsMm, 0.0);
      fig.maxMm = f.requiredNumber("max_mm");
      f.requireAtLeast("max_mm", fig.maxMm, 0.0);
      f.finish();
      s.fit = fig;
    }
    if (hasSource && !s.reachable) r.fail("source", "an unreachable shape has no source");
    if (s.source == RetargetSource::Derived && !s.correctiveOf.empty())
      r.fail("source", "a corrective is fitted on its base's shape, not derived");
    if (s.reachable && !s.reason.empty()) r.fail("reason", "only an unreachable shape (reachable: false) has a reason");
    if (!s.reachable) {
      if (s.reason.empty()) r.fail("reason", "an unreachable shape needs a reason (why muscles cannot make it)");
      if (!s.activations.empty() || !s.jaw.empty() || !s.gaze.empty() || s.mouthPressureKpa > 0.0 || !s.correctiveOf.empty())
        r.fail(!s.activations.empty() ? "activations"
               : !s.jaw.empty()       ? "jaw"
               : !s.gaze.empty()      ? "gaze"
               : s.mouthPressureKpa > 0.0 ? "mouth_pressure_kpa"
                                          : "corrective_of",
               "an unreachable shape has no activations, jaw, gaze, air or base");
    }
    r.finish();
    map.shapes.push_back(std::move(s));
  }
  // A corrective's base must be a reachable, non-corrective shape of the map.
  for (size_t i = 0; i < map.shapes.size(); ++i) {
    const RetargetShape& s = map.shapes[i];
    if (s.correctiveOf.empty()) continue;
    const RetargetShape* base = map.find(s.correctiveOf);
    DocReader r(list[i], name, "shapes[" + std::to_string(i) + "]");
    if (!base || !base->reachable || !base->correctiveOf.empty())
      r.failAt(correctiveNodes[i], r.keyPath("corrective_of"),
               "the base " + s.correctiveOf + " must be a reachable shape of the map that is not itself a corrective");
    // base + difference must stay in [0, 1] for every muscle.
    for (const auto& [muscle, total] : map.totalActivations(s))
      if (total < -1e-9 || total > 1.0 + 1e-9)
        r.failAt(list[i]["activations"].IsDefined() ? list[i]["activations"] : list[i], r.keyPath("activations"),
                 "with its base " + s.correctiveOf + ", " + muscle + " reaches " + std::to_string(total) + ", outside [0, 1]");
  }
  return map;
}

RetargetMap parseRetargetMap(const std::string& text, const std::string& name, const std::vector<std::string>& knownMuscles) {
  return readRetargetMap(loadDocument(text, name), name, knownMuscles);
}

std::string serialiseRetargetMap(const RetargetMap& map) {
  nlohmann::ordered_json j;
  j["format"] = kFormat;
  j["version"] = kVersion;
  if (!map.rig.empty()) j["rig"] = map.rig;
  if (!map.head.empty()) j["head"] = map.head;
  j["model"] = map.model;
  if (!map.library.empty()) j["library"] = map.library;
  if (!map.note.empty()) j["note"] = map.note;
  nlohmann::ordered_json shapes = nlohmann::ordered_json::array();
  for (const RetargetShape& s : map.shapes) {
    nlohmann::ordered_json e;
    e["name"] = s.name;
    if (!s.reachable) {
      e["reachable"] = false;
      e["reason"] = s.reason;
      shapes.push_back(e);
      continue;
    }
    e["source"] = toString(s.source);
    if (!s.correctiveOf.empty()) e["corrective_of"] = s.correctiveOf;
    e["activations"] = nlohmann::ordered_json::object();
    for (const auto& [muscle, v] : s.activations) e["activations"][muscle] = v;
    e["jaw"] = nlohmann::ordered_json::object();
    for (const auto& [dof, v] : s.jaw) e["jaw"][dof] = v;
    if (!s.gaze.empty()) {
      e["gaze"] = nlohmann::ordered_json::object();
      for (const auto& [dof, v] : s.gaze) e["gaze"][dof] = v;
    }
    if (s.mouthPressureKpa > 0.0) e["mouth_pressure_kpa"] = s.mouthPressureKpa;
    if (s.fit) {
      e["fit"] = {{"cosine", s.fit->cosine},
                  {"magnitude_ratio", s.fit->magnitudeRatio},
                  {"rms_mm", s.fit->rmsMm},
                  {"max_mm", s.fit->maxMm}};
    }
    shapes.push_back(e);
  }
  j["shapes"] = shapes;
  return j.dump(2) + "\n";
}

const std::vector<std::pair<std::string, std::string>>& unreachableArkitShapes() {
  static const std::vector<std::pair<std::string, std::string>> list = [] {
    const nlohmann::json j = nlohmann::json::parse(detail::kUnreachableShapesJson);  // shipped data: a bug if bad
    std::map<std::string, std::string> reasons;
    for (const auto& row : j.at("shapes")) {
      const std::string name = row.at("arkit").get<std::string>();
      MYO_CHECK(findArkitName(name) == name, "assets/retarget/unreachable.json: not an ARKit name: " << name);
      reasons[name] = row.at("reason").get<std::string>();
    }
    std::vector<std::pair<std::string, std::string>> out;
    for (const std::string& a : arkitNames())
      if (auto it = reasons.find(a); it != reasons.end()) out.emplace_back(a, it->second);
    return out;
  }();
  return list;
}

std::optional<std::string> unreachableReason(const std::string& anySpelling) {
  const std::optional<std::string> name = findArkitName(anySpelling);
  if (!name) return std::nullopt;
  for (const auto& [arkit, reason] : unreachableArkitShapes())
    if (arkit == *name) return reason;
  return std::nullopt;
}

const RetargetMap& builtinRetargetMap() {
  static const RetargetMap map = [] {
    std::vector<std::string> names;
    for (const MuscleDef& def : faceMuscleDefs()) names.push_back(def.name);
    return parseRetargetMap(detail::kArkitIctFaceMapJson, "<embedded assets/retarget/arkit_ict_face.json>", names);
  }();
  return map;
}

const RetargetMap* shippedRetargetMap(const std::string& library) {
  if (library == "face") return &builtinRetargetMap();
  if (library != "builtin") return nullptr;
  static const RetargetMap map = [] {
    std::vector<std::string> names;
    for (const MuscleDef& def : anatomicalBuiltinDefs()) names.push_back(def.name);
    return parseRetargetMap(detail::kArkitIctMapJson, "<embedded assets/retarget/arkit_ict.json>", names);
  }();
  return &map;
}

}  // namespace myo
