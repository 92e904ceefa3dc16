// The performance readers' common part: names of the inputs, detection from the first line, the
// shared text helpers, and the assembly of a reader's frames into a Performance (times checked,
// dropped frames bridged or trimmed and reported). The three layouts: performance_openface.cpp,
// performance_livelink.cpp, performance_mediapipe.cpp.
#include "myoshell/anim/performance.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <sstream>
#include <utility>

#include "myoshell/core/errors.h"
#include "myoshell/core/text_lines.h"
#include "performance_frames.h"

namespace myo {

using namespace performance_detail;

PerformanceInput performanceInputFromString(const std::string& name) {
  if (name == "openface") return PerformanceInput::OpenFace;
  if (name == "livelink") return PerformanceInput::LiveLink;
  if (name == "mediapipe") return PerformanceInput::MediaPipe;
  throw InputError("unknown performance input '" + name + "' (use openface, livelink or mediapipe)");
}

const char* toString(PerformanceInput input) {
  switch (input) {
    case PerformanceInput::OpenFace: return "openface";
    case PerformanceInput::LiveLink: return "livelink";
    case PerformanceInput::MediaPipe: return "mediapipe";
  }
  return "?";
}

const PerformanceChannel* Performance::find(const std::string& channelName) const {
  for (const PerformanceChannel& c : channels)
    if (c.name == channelName) return &c;
  return nullptr;
}

namespace {

bool startsWithNoCase(std::string_view s, std::string_view prefix) {
  if (s.size() < prefix.size()) return false;
  for (size_t i = 0; i < prefix.size(); ++i)
    if (std::tolower(static_cast<unsigned char>(s[i])) != std::tolower(static_cast<unsigned char>(prefix[i])))
      return false;
  return true;
}

// An OpenFace action-unit column: "AU" digits "_r" or "_c".
bool isAuColumn(std::string_view f) {
  if (f.size() < 5 || f.substr(0, 2) != "AU") return false;
  const std::string_view tail = f.substr(f.size() - 2);
  if (tail != "_r" && tail != "_c") return false;
  const std::string_view digits = f.substr(2, f.size() - 4);
  return std::all_of(digits.begin(), digits.end(), [](char c) { return c >= '0' && c <= '9'; });
}

}  // namespace

PerformanceInput detectPerformanceInput(const std::string& text, const std::string& name) {
  const std::vector<std::string_view> lines = splitLines(text, name);
  const size_t first = firstNonBlankLine(lines, name);
  const std::string_view head = trim(lines[first]);
  const int line = static_cast<int>(first + 1);
  if (!head.empty() && head.front() == '{') return PerformanceInput::MediaPipe;
  const std::vector<std::string_view> fields = splitFields(head);
  // Live Link Face writes "BlendShapeCount"; tools that imitate it write "BlendshapeCount" too.
  // Each layout is told by its own columns, so that a file missing its time column reaches its
  // reader, which names the column ("missing required column 'timestamp'"), rather than this error.
  if (std::any_of(fields.begin(), fields.end(),
                  [](std::string_view f) { return f.size() == 15 && startsWithNoCase(f, "BlendShapeCount"); }))
    return PerformanceInput::LiveLink;
  if (std::any_of(fields.begin(), fields.end(), isAuColumn)) return PerformanceInput::OpenFace;
  throw InputError("cannot tell the performance's layout from " + quoted(head) +
                       ": expected an OpenFace CSV header (timestamp and AUxx_r columns), a Live Link Face "
                       "header (Timecode,BlendShapeCount,…) or MediaPipe JSON Lines ({\"timestamp_ms\": …})",
                   name, line);
}

Performance parsePerformance(const std::string& text, const std::string& name, const PerformanceOptions& options) {
  if (options.auScale && !(std::isfinite(*options.auScale) && *options.auScale > 0))
    throw InputError("the AU scale must be a positive number (got " + numberText(*options.auScale) + ")");
  if (options.inputFps && !(std::isfinite(*options.inputFps) && *options.inputFps > 0))
    throw InputError("the input frame rate must be a positive number (got " + numberText(*options.inputFps) + ")");
  if (!std::isfinite(options.minConfidence))
    throw InputError("the minimum confidence must be a number (got " + numberText(options.minConfidence) + ")");
  const PerformanceInput input = options.input ? *options.input : detectPerformanceInput(text, name);
  switch (input) {
    case PerformanceInput::OpenFace: return parseOpenFace(text, name, options);
    case PerformanceInput::LiveLink: return parseLiveLink(text, name, options);
    case PerformanceInput::MediaPipe: return parseMediaPipe(text, name, options);
  }
  throw InputError("unknown performance input");
}

namespace performance_detail {

namespace {
}

std::vector<std::string_view> splitLines(const std::string& text, const std::string& name) {
  std::string_view all(text);
  if (all.substr(0, 3) == "\xEF\xBB\xBF") all.remove_prefix(3);
  return myo::splitLines(all, name);
}

size_t firstNonBlankLine(const std::vector<std::string_view>& lines, const std::string& name) {
  size_t first = 0;
  while (first < lines.size() && isBlank(lines[first])) ++first;
  if (first == lines.size()) throw InputError("the performance file is empty", name);
  return first;
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}

bool isBlank(std::string_view line) { return trim(line).empty(); }

std::vector<std::string_view> splitFields(std::string_view line) {
  std::vector<std::string_view> out;
  size_t start = 0;
  while (true) {
    const size_t comma = line.find(',', start);
    out.push_back(trim(line.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start)));
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  return out;
}

std::string quoted(std::string_view s) {
  constexpr size_t kMax = 40;
  std::string out = "'";  // appended piece by piece: gcc 12's -Wrestrict misreads "'" + std::string(…)
  out.append(s.substr(0, kMax));
  out.append(s.size() > kMax ? "…'" : "'");
  return out;
}

std::string numberText(double x) {
  std::ostringstream os;
  os.precision(10);
  os << x;
  return os.str();
}

CellRead readCell(std::string_view cell, double& out) {
  cell = trim(cell);
  if (cell.empty()) return CellRead::Empty;
  if (cell.front() == '+') {  // from_chars reads no sign but '-'
    cell.remove_prefix(1);
    if (cell.empty() || cell.front() == '+' || cell.front() == '-') return CellRead::Unreadable;
  }
  const auto [end, ec] = std::from_chars(cell.data(), cell.data() + cell.size(), out);
  if (end != cell.data() + cell.size()) return CellRead::Unreadable;
  if (ec == std::errc::result_out_of_range) return CellRead::NotFinite;
  if (ec != std::errc()) return CellRead::Unreadable;
  return std::isfinite(out) ? CellRead::Number : CellRead::NotFinite;
}

namespace {

// The eyes' turn a fraction s of the way from a to b, angle by angle (gaps are short).
EyeGaze gazeBetween(const EyeGaze& a, const EyeGaze& b, double s) {
  EyeGaze g;
  for (size_t e = 0; e < 2; ++e) {
    g.pitchDeg[e] = a.pitchDeg[e] + s * (b.pitchDeg[e] - a.pitchDeg[e]);
    g.yawDeg[e] = a.yawDeg[e] + s * (b.yawDeg[e] - a.yawDeg[e]);
  }
  return g;
}

// "3 with empty cells, 1 with success 0": each reason with its count, in order of first appearance.
std::string dropReasons(const std::vector<Frame>& frames, const std::vector<Frame>& leftOut) {
  std::vector<std::pair<std::string, int>> reasons;
  for (const std::vector<Frame>* list : {&frames, &leftOut})
    for (const Frame& f : *list) {
      if (f.dropped.empty()) continue;
      auto it = std::find_if(reasons.begin(), reasons.end(), [&](const auto& r) { return r.first == f.dropped; });
      if (it == reasons.end())
        reasons.emplace_back(f.dropped, 1);
      else
        ++it->second;
    }
  std::string out;
  for (const auto& [why, count] : reasons) out += (out.empty() ? "" : ", ") + std::to_string(count) + " " + why;
  return out;
}

}  // namespace

Performance assemblePerformance(FrameTable table, PerformanceInput input, const std::string& name) {
  std::vector<Frame>& frames = table.frames;
  for (size_t i = 0; i < frames.size(); ++i) {
    const Frame& f = frames[i];
    if (!std::isfinite(f.time)) throw InputError("time is not finite", name, f.line);
    if (f.time < 0) throw InputError("negative time " + numberText(f.time) + " s", name, f.line);
    if (i > 0 && f.time <= frames[i - 1].time)
      throw InputError("time " + numberText(f.time) + " s is not after the previous frame's " +
                           numberText(frames[i - 1].time) + " s (line " + std::to_string(frames[i - 1].line) + ")",
                       name, f.line);
  }
  std::vector<size_t> valid;
  for (size_t i = 0; i < frames.size(); ++i)
    if (frames[i].dropped.empty()) valid.push_back(i);
  const int leftOut = static_cast<int>(table.leftOut.size());
  const int droppedRows = static_cast<int>(frames.size() - valid.size()) + leftOut;
  if (valid.size() < 2) {
    std::string why = std::to_string(frames.size() + table.leftOut.size()) + " rows";
    if (droppedRows > 0) why += ", " + dropReasons(frames, table.leftOut);
    throw InputError("fewer than two valid frames (" + why + ")", name);
  }

  Performance out;
  out.input = input;
  out.auScale = table.auScale;
  out.warnings = std::move(table.warnings);
  const size_t first = valid.front(), last = valid.back();
  const size_t n = last - first + 1;
  out.times.reserve(n);
  for (size_t i = first; i <= last; ++i) out.times.push_back(frames[i].time - frames[first].time);
  out.channels.resize(table.channels.size());
  for (size_t c = 0; c < table.channels.size(); ++c) {
    out.channels[c].name = table.channels[c];
    out.channels[c].values.resize(n);
  }
  if (table.hasPose) out.headPose.resize(n);
  if (table.hasGaze) out.gaze.resize(n);
  // Walk the kept span; between valid frames a and b every dropped frame gets the linear
  // interpolation in time of their values (pose and gaze component-wise: gaps are short, angles small).
  for (size_t k = 0; k + 1 < valid.size(); ++k) {
    const size_t a = valid[k];
    const size_t b = valid[k + 1];
    for (size_t i = a; i < b; ++i) {
      const double s = i == a ? 0.0 : (frames[i].time - frames[a].time) / (frames[b].time - frames[a].time);
      // Between two values in [0, 1], and kept there against round-off.
      for (size_t c = 0; c < out.channels.size(); ++c)
        out.channels[c].values[i - first] =
            std::clamp(frames[a].values[c] + s * (frames[b].values[c] - frames[a].values[c]), 0.0, 1.0);
      if (table.hasPose) out.headPose[i - first] = frames[a].pose + s * (frames[b].pose - frames[a].pose);
      if (table.hasGaze) out.gaze[i - first] = gazeBetween(frames[a].gaze, frames[b].gaze, s);
    }
  }
  for (size_t c = 0; c < out.channels.size(); ++c) out.channels[c].values[n - 1] = frames[last].values[c];
  if (table.hasPose) out.headPose[n - 1] = frames[last].pose;
  if (table.hasGaze) out.gaze[n - 1] = frames[last].gaze;

  out.fps = table.fps > 0 ? table.fps : static_cast<double>(n - 1) / out.duration();
  if (!std::isfinite(out.fps))  // times that increase by less than double's range can hold
    throw InputError("the frames are too close in time: " + std::to_string(n) + " frames within " +
                         numberText(out.duration()) + " s",
                     name);
  out.droppedFrames = droppedRows;
  if (droppedRows > 0) {
    const int trimmed = static_cast<int>(first + (frames.size() - 1 - last));
    const int bridged = static_cast<int>(n - (valid.size()));
    const int total = static_cast<int>(frames.size()) + leftOut;
    int firstLine = 0;
    for (const std::vector<Frame>* list : {&frames, &table.leftOut})
      for (const Frame& f : *list)
        if (!f.dropped.empty() && (firstLine == 0 || f.line < firstLine)) firstLine = f.line;
    std::string w = "dropped " + std::to_string(droppedRows) + " of " + std::to_string(total) + " frames (" +
                    std::to_string(bridged) + " bridged by interpolation, " + std::to_string(trimmed) +
                    " trimmed at the ends";
    if (leftOut > 0) w += ", " + std::to_string(leftOut) + " left out";
    w += "): " + dropReasons(frames, table.leftOut);
    if (firstLine > 0) w += "; the first at line " + std::to_string(firstLine);
    out.warnings.push_back(std::move(w));
  }
  return out;
}

}  // namespace performance_detail

}  // namespace myo
