// MediaPipe face-landmarker blendshapes as JSON Lines: one object per video frame,
// {"timestamp_ms": t, "blendshapes": [{"categoryName": "mouthSmileLeft", "score": 0.42}, …]}, the
// layout of the landmarker's result (FaceLandmarkerResult.faceBlendshapes[0], a list of Category
// with index, score, categoryName, displayName: developers.google.com/mediapipe, "Face landmark
// detection guide"). Its 52 categories are ARKit's names plus "_neutral", which is not a weight of
// any shape and is skipped. A frame with an empty list found no face: it is dropped. Each line is
// parsed on its own (nlohmann::json, as the landmark reader), so an error names its line.
#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "myoshell/core/close_names.h"
#include "myoshell/core/errors.h"
#include "myoshell/fit/arkit_names.h"
#include "performance_frames.h"

namespace myo::performance_detail {

namespace {

// nlohmann's message without its "[json.exception.parse_error.101] parse error at line 1, column
// 5: " prefix, whose position we give ourselves.
std::string jsonMessage(const nlohmann::json::exception& e) {
  std::string what = e.what();
  if (const auto p = what.find("] "); p != std::string::npos) what = what.substr(p + 2);
  if (what.rfind("parse error", 0) == 0)
    if (const auto q = what.find(": "); q != std::string::npos) what = what.substr(q + 2);
  return what;
}

// A JSON value for a message, cut to 40 characters.
std::string shown(const nlohmann::json& j) {
  std::string s = j.dump(-1, ' ', true);  // ASCII: a cut cannot split a character
  return s.size() > 40 ? s.substr(0, 40) + "…" : s;
}

}  // namespace

Performance parseMediaPipe(const std::string& text, const std::string& name, const PerformanceOptions&) {
  const std::vector<std::string_view> lines = splitLines(text, name);
  FrameTable table;
  std::vector<std::string> unknownKeys, unknownNames;
  auto note = [](std::vector<std::string>& list, const std::string& s) {
    if (std::find(list.begin(), list.end(), s) == list.end()) list.push_back(s);
  };
  for (size_t li = 0; li < lines.size(); ++li) {
    if (isBlank(lines[li])) continue;
    const int line = static_cast<int>(li + 1);
    nlohmann::json j;
    try {
      j = nlohmann::json::parse(lines[li]);
    } catch (const nlohmann::json::parse_error& e) {
      throw InputError("bad JSON: " + jsonMessage(e), name, line, static_cast<int>(std::max<size_t>(e.byte, 1)));
    } catch (const nlohmann::json::exception& e) {  // a number beyond double's range
      throw InputError("bad JSON: " + jsonMessage(e), name, line);
    }
    if (!j.is_object())
      throw InputError("a frame must be a JSON object {\"timestamp_ms\": …, \"blendshapes\": […]}, got " +
                           std::string(j.type_name()),
                       name, line);
    for (const auto& item : j.items())
      if (item.key() != "timestamp_ms" && item.key() != "blendshapes") note(unknownKeys, item.key());
    if (!j.contains("timestamp_ms")) throw InputError("missing required key 'timestamp_ms'", name, line);
    if (!j.contains("blendshapes")) throw InputError("missing required key 'blendshapes'", name, line);
    const nlohmann::json& t = j["timestamp_ms"];
    const nlohmann::json& shapes = j["blendshapes"];
    Frame f;
    f.line = line;
    if (t.is_null()) {
      f.dropped = "with no timestamp_ms";
      table.leftOut.push_back(std::move(f));
      continue;
    }
    if (!t.is_number()) throw InputError("timestamp_ms must be a number, got " + shown(t), name, line);
    f.time = t.get<double>() / 1000.0;
    if (!shapes.is_array())
      throw InputError("blendshapes must be a list of {\"categoryName\": …, \"score\": …}, got " + shown(shapes), name,
                       line);
    f.values.assign(table.channels.size(), std::nan(""));
    for (size_t k = 0; k < shapes.size(); ++k) {
      const nlohmann::json& s = shapes[k];
      const std::string at = "blendshapes[" + std::to_string(k) + "]";
      if (!s.is_object() || !s.contains("categoryName") || !s.contains("score"))
        throw InputError(at + " must be an object {\"categoryName\": …, \"score\": …}", name, line);
      const nlohmann::json& category = s["categoryName"];
      const nlohmann::json& score = s["score"];
      if (!category.is_string()) throw InputError(at + ".categoryName must be a string, got " + shown(category), name, line);
      const std::string shape = category.get<std::string>();
      if (shape == "_neutral") continue;
      const std::optional<std::string> arkit = findArkitName(shape);
      if (!arkit || *arkit != shape) {
        note(unknownNames, shape);
        continue;
      }
      if (score.is_null()) continue;  // an empty cell: the frame is dropped below
      if (!score.is_number()) throw InputError(at + ".score must be a number, got " + shown(score), name, line);
      const double v = score.get<double>();
      if (!std::isfinite(v)) throw InputError(at + ".score is not finite", name, line);
      if (v < -kRangeSlack || v > 1 + kRangeSlack)
        throw InputError(at + ".score of " + shape + " is " + numberText(v) + ", outside [0, 1]", name, line);
      auto c = std::find(table.channels.begin(), table.channels.end(), shape);
      if (c == table.channels.end()) {
        // A name first seen here: a new channel, absent (dropped) in the frames before.
        table.channels.push_back(shape);
        for (Frame& before : table.frames) {
          before.values.push_back(std::nan(""));
          if (before.dropped.empty()) before.dropped = "with missing blendshapes";
        }
        f.values.push_back(std::nan(""));
        c = table.channels.end() - 1;
      }
      double& slot = f.values[static_cast<size_t>(c - table.channels.begin())];
      if (!std::isnan(slot)) throw InputError(at + ": " + shape + " appears twice in the frame", name, line);
      slot = std::clamp(v, 0.0, 1.0);
    }
    if (shapes.empty())
      f.dropped = "with no face (empty blendshapes)";
    else if (std::any_of(f.values.begin(), f.values.end(), [](double v) { return std::isnan(v); }))
      f.dropped = "with missing blendshapes";
    table.frames.push_back(std::move(f));
  }
  if (table.channels.empty() && !table.frames.empty())
    throw InputError("no frame holds an ARKit blendshape (categoryName eyeBlinkLeft … tongueOut)", name);
  if (!unknownKeys.empty())
    table.warnings.push_back("ignored " + std::to_string(unknownKeys.size()) + " unknown key" +
                             (unknownKeys.size() == 1 ? "" : "s") + ": " + joinNames(unknownKeys));
  if (!unknownNames.empty())
    table.warnings.push_back("ignored " + std::to_string(unknownNames.size()) + " unknown blendshape name" +
                             (unknownNames.size() == 1 ? "" : "s") + ": " + joinNames(unknownNames));
  return assemblePerformance(std::move(table), PerformanceInput::MediaPipe, name);
}

}  // namespace myo::performance_detail
