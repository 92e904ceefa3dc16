#include "myoshell/head/landmarks.h"

#include <algorithm>
#include <nlohmann/json.hpp>
#include <sstream>

#include "myoshell/core/errors.h"

namespace myo {

namespace {

const RequiredLandmark* findRequired(std::string_view name) {
  for (const RequiredLandmark& r : kRequiredLandmarks)
    if (name == r.name) return &r;
  return nullptr;
}

// 1-based line and column of byte offset `byte` (1-based, as nlohmann reports it) in text.
std::pair<int, int> lineColumn(const std::string& text, std::size_t byte) {
  int line = 1, col = 1;
  const std::size_t end = std::min(byte > 0 ? byte - 1 : 0, text.size());
  for (std::size_t i = 0; i < end; ++i) {
    if (text[i] == '\n') {
      ++line;
      col = 1;
    } else {
      ++col;
    }
  }
  return {line, col};
}

int vertexId(const nlohmann::json& v, const std::string& what, int vertexCount,
             const std::string& name) {
  if (!v.is_number_integer())
    throw InputError(what + ": vertex id must be an integer, got " + v.dump(), name);
  // An unsigned integer above INT64_MAX would wrap to a negative long long: compare it unsigned.
  const bool inRange = v.is_number_unsigned()
                           ? v.get<unsigned long long>() < static_cast<unsigned long long>(std::max(vertexCount, 0))
                           : v.get<long long>() >= 0 && v.get<long long>() < vertexCount;
  if (!inRange)
    throw InputError(what + ": vertex id " + v.dump() + " out of range [0, " + std::to_string(vertexCount) + ")",
                     name);
  return static_cast<int>(v.get<long long>());
}

}  // namespace

bool Landmarks::has(std::string_view name) const {
  if (named.count(std::string(name))) return true;
  const RequiredLandmark* r = findRequired(name);
  return r && static_cast<int>(multipie68.size()) == 68;
}

int Landmarks::vertex(std::string_view name) const {
  if (auto it = named.find(std::string(name)); it != named.end()) return it->second;
  const RequiredLandmark* r = findRequired(name);
  if (r && multipie68.size() == 68) return multipie68[static_cast<size_t>(r->multipieIndex)];
  std::string how = r ? " (give it under \"named\" or as Multi-PIE point " +
                            std::to_string(r->multipieIndex) + " in \"multipie68\")"
                      : "";
  throw InputError("missing landmark '" + std::string(name) + "'" + how, sourcePath);
}

std::map<std::string, int> Landmarks::resolved() const {
  std::map<std::string, int> out = named;
  for (const RequiredLandmark& r : kRequiredLandmarks)
    if (has(r.name)) out[r.name] = vertex(r.name);
  return out;
}

void Landmarks::requireAll() const {
  for (const RequiredLandmark& r : kRequiredLandmarks) vertex(r.name);
}

Landmarks parseLandmarks(const std::string& jsonText, int vertexCount, const std::string& name) {
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(jsonText);
  } catch (const nlohmann::json::parse_error& e) {
    auto [line, col] = lineColumn(jsonText, e.byte);
    std::string what = e.what();
    // nlohmann's text reads "[json.exception.parse_error.101] parse error at line L, column C: …";
    // keep what follows the location, which InputError already gives.
    if (const auto p = what.find("parse error"); p != std::string::npos) {
      what = what.substr(p);
      if (const auto q = what.find(": "); q != std::string::npos) what = what.substr(q + 2);
    }
    throw InputError("bad JSON in landmark file: " + what, name, line, col);
  } catch (const nlohmann::json::exception& e) {
    // A number beyond double's range ("number overflow parsing '1e400'") comes without a position:
    // find the number in the text.
    std::string what = e.what();
    if (const auto p = what.find("] "); p != std::string::npos) what = what.substr(p + 2);
    const size_t q1 = what.find('\''), q2 = what.rfind('\'');
    const size_t at = q1 != std::string::npos && q2 > q1 ? jsonText.find(what.substr(q1 + 1, q2 - q1 - 1))
                                                         : std::string::npos;
    if (at == std::string::npos) throw InputError("bad JSON in landmark file: " + what, name);
    auto [line, col] = lineColumn(jsonText, at + 1);
    throw InputError("bad JSON in landmark file: " + what, name, line, col);
  }
  if (!j.is_object())
    throw InputError("landmark file must hold a JSON object ({\"multipie68\": [...], \"named\": "
                     "{...}} or {\"name\": vertex_id, ...})",
                     name);
  Landmarks lm;
  lm.sourcePath = name;
  const bool layout = j.contains("multipie68") || j.contains("named");
  if (layout) {
    if (j.contains("multipie68")) {
      const auto& a = j["multipie68"];
      if (!a.is_array() || a.size() != 68)
        throw InputError("multipie68 must hold 68 vertex ids, got " +
                             (a.is_array() ? std::to_string(a.size()) : std::string("a ") + a.type_name()),
                         name);
      for (size_t i = 0; i < 68; ++i)
        lm.multipie68.push_back(
            vertexId(a[i], "multipie68 point " + std::to_string(i), vertexCount, name));
    }
    if (j.contains("named")) {
      const auto& n = j["named"];
      if (!n.is_object()) throw InputError("\"named\" must be an object name → {\"vertex\": id}", name);
      for (const auto& [key, val] : n.items()) {
        const std::string what = "landmark '" + key + "'";
        if (val.is_object()) {
          if (!val.contains("vertex")) throw InputError(what + ": no \"vertex\"", name);
          lm.named[key] = vertexId(val["vertex"], what, vertexCount, name);
        } else {
          lm.named[key] = vertexId(val, what, vertexCount, name);
        }
      }
    }
  } else {
    for (const auto& [key, val] : j.items()) {
      const std::string what = "landmark '" + key + "'";
      if (val.is_object() && val.contains("vertex"))
        lm.named[key] = vertexId(val["vertex"], what, vertexCount, name);
      else if (val.is_number())
        lm.named[key] = vertexId(val, what, vertexCount, name);
      else if (key == "source" || key == "note" || key == "groups" || key == "confidence")
        continue;
      else
        throw InputError(what + ": expected a vertex id or {\"vertex\": id}, got " + val.dump(), name);
    }
  }
  return lm;
}

std::string landmarksToJson(const Landmarks& landmarks) {
  nlohmann::ordered_json j;
  if (!landmarks.multipie68.empty()) j["multipie68"] = landmarks.multipie68;
  nlohmann::ordered_json named = nlohmann::ordered_json::object();
  for (const auto& [k, v] : landmarks.named) {
    nlohmann::ordered_json e;
    if (const RequiredLandmark* r = findRequired(k);
        r && landmarks.multipie68.size() == 68 &&
        landmarks.multipie68[static_cast<size_t>(r->multipieIndex)] == v)
      e["multipie_index"] = r->multipieIndex;
    e["vertex"] = v;
    named[k] = e;
  }
  j["named"] = named;
  return j.dump(1) + "\n";
}

}  // namespace myo
