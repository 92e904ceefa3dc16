// Live Link Face CSV (Epic's iPhone app, a take's .csv): `Timecode,BlendShapeCount,` then ARKit's 52
// weights in PascalCase (EyeBlinkLeft … TongueOut) and nine rotations HeadYaw, HeadPitch, HeadRoll,
// LeftEyeYaw … RightEyeRoll; one row per captured frame.
//
// Timecode: SMPTE HH:MM:SS:FF with a sub-frame fraction after a dot (FF.fff), FF counted at the
// app's capture rate (60 by default, 30 selectable), which the file does not state: it is the
// largest FF + 1 over the file unless given.
//
// Rotations: Epic's ARKit face support (Unreal Engine's AppleARKitFaceSupport plugin, ToBlendShapeMap:
// "Map the -180..180 range to -1..1", HeadYaw = FRotator.Yaw / 180) writes each angle in degrees
// divided by 180, so HeadPitch = 0.1 is 18°. ARKit's face anchor frame is the face frame
// (face_frame.h): x the face's own left, y up, z out of the face (Apple, ARFaceAnchor). Following
// that plugin's conversion to Unreal's axes and its sign flips of yaw and roll for an unmirrored
// face, HeadPitch, HeadYaw, HeadRoll come out as right-handed angles about the face frame's x, y, z:
// [pitch, yaw, roll] = 180·[HeadPitch, HeadYaw, HeadRoll] degrees. This sign reading is derived from
// the plugin's code, not checked against a recording of a known head motion
// (docs/performance_input.md).
//
// The eyes: the plugin turns ARKit's leftEyeTransform and rightEyeTransform (each eye's pose in the
// face anchor's frame, +z along the eye's gaze; Apple, ARFaceAnchor) into LeftEyePitch, LeftEyeYaw, …
// exactly as the head's (the same conversion, the same sign flips, degrees / 180, the eyes' sides
// kept as ARKit names them), so 180·[LeftEyePitch, LeftEyeYaw] are right-handed angles about the
// face frame's x and y. A right-handed turn about x (the face's left) takes +z (the gaze) down, so
// the eyes' turn (head/eye_gaze.h: pitch + up) is pitch = −180·LeftEyePitch, yaw = 180·LeftEyeYaw
// (+ towards the subject's left), and the right eye's alike. The roll (the eye's torsion about its
// gaze) moves no lid and is not read. Derived from the plugin's code, as the head's.
#include <algorithm>
#include <cmath>

#include "myoshell/core/close_names.h"
#include "myoshell/core/errors.h"
#include "myoshell/fit/arkit_names.h"
#include "performance_frames.h"

namespace myo::performance_detail {

namespace {

struct Timecode {
  double seconds = 0;  // h·3600 + m·60 + s
  int frame = 0;       // FF
  double fraction = 0;  // .fff, in [0, 1)
};

bool readDigits(std::string_view s, long long& out) {
  if (s.empty() || s.size() > 9) return false;
  out = 0;
  for (const char c : s) {
    if (c < '0' || c > '9') return false;
    out = out * 10 + (c - '0');
  }
  return true;
}

// "HH:MM:SS:FF" or "HH:MM:SS:FF.fff"; false when unreadable.
bool readTimecode(std::string_view s, Timecode& tc) {
  std::string_view part[4];
  for (int k = 0; k < 3; ++k) {
    const size_t colon = s.find(':');
    if (colon == std::string_view::npos) return false;
    part[k] = s.substr(0, colon);
    s.remove_prefix(colon + 1);
  }
  part[3] = s;
  std::string_view fraction;
  if (const size_t dot = part[3].find('.'); dot != std::string_view::npos) {
    fraction = part[3].substr(dot + 1);
    part[3] = part[3].substr(0, dot);
    if (fraction.empty()) return false;
  }
  long long v[4];
  for (int k = 0; k < 4; ++k)
    if (!readDigits(part[k], v[k])) return false;
  if (v[1] >= 60 || v[2] >= 60) return false;
  tc.seconds = static_cast<double>(v[0]) * 3600 + static_cast<double>(v[1]) * 60 + static_cast<double>(v[2]);
  tc.frame = static_cast<int>(v[3]);
  tc.fraction = 0;
  if (!fraction.empty()) {
    double scale = 0.1;
    for (const char c : fraction) {
      if (c < '0' || c > '9') return false;
      tc.fraction += (c - '0') * scale;
      scale *= 0.1;
    }
  }
  return true;
}

enum class Role { Weight, Head, Eye, Ignored, Unknown };

// The four eye columns read: LeftEyePitch, LeftEyeYaw, RightEyePitch, RightEyeYaw.
constexpr const char* kEyeColumns[4] = {"LeftEyePitch", "LeftEyeYaw", "RightEyePitch", "RightEyeYaw"};

}  // namespace

Performance parseLiveLink(const std::string& text, const std::string& name, const PerformanceOptions& options) {
  const std::vector<std::string_view> lines = splitLines(text, name);
  const size_t headerIndex = firstNonBlankLine(lines, name);
  const int headerLine = static_cast<int>(headerIndex + 1);
  const std::vector<std::string_view> header = splitFields(lines[headerIndex]);
  if (header.empty() || header[0] != "Timecode")
    throw InputError("missing required column 'Timecode' (a Live Link Face CSV starts Timecode,BlendShapeCount,…)",
                     name, headerLine);

  FrameTable table;
  std::vector<Role> role(header.size(), Role::Unknown);
  std::vector<size_t> channelOf(header.size(), 0);
  int headOf[3] = {-1, -1, -1};  // columns of HeadPitch, HeadYaw, HeadRoll
  int eyeOf[4] = {-1, -1, -1, -1};  // columns of kEyeColumns
  std::vector<std::string> unknown;
  role[0] = Role::Ignored;
  for (size_t c = 1; c < header.size(); ++c) {
    const std::string_view f = header[c];
    if (f == "BlendShapeCount" || f == "BlendshapeCount") {
      role[c] = Role::Ignored;  // how many values follow: the header already says
    } else if (f == "HeadPitch" || f == "HeadYaw" || f == "HeadRoll") {
      role[c] = Role::Head;
      const int axis = f == "HeadPitch" ? 0 : f == "HeadYaw" ? 1 : 2;
      if (headOf[axis] >= 0)
        throw InputError("column " + quoted(f) + " appears twice (columns " + std::to_string(headOf[axis] + 1) +
                             " and " + std::to_string(c + 1) + ")",
                         name, headerLine);
      headOf[axis] = static_cast<int>(c);
    } else if (f == "LeftEyeRoll" || f == "RightEyeRoll") {
      role[c] = Role::Ignored;  // the eye's torsion about its gaze: no lid follows it
    } else if (const auto* eye = std::find(std::begin(kEyeColumns), std::end(kEyeColumns), f);
               eye != std::end(kEyeColumns)) {
      role[c] = Role::Eye;
      int& at = eyeOf[eye - std::begin(kEyeColumns)];
      if (at >= 0)
        throw InputError("column " + quoted(f) + " appears twice (columns " + std::to_string(at + 1) + " and " +
                             std::to_string(c + 1) + ")",
                         name, headerLine);
      at = static_cast<int>(c);
    } else {
      // PascalCase ARKit names: EyeBlinkLeft → eyeBlinkLeft. Only ARKit's own spelling counts (not
      // ICT's, which findArkitName also knows).
      std::string lowered(f);
      if (!lowered.empty()) lowered[0] = static_cast<char>(std::tolower(static_cast<unsigned char>(lowered[0])));
      const std::optional<std::string> arkit = findArkitName(lowered);
      if (arkit && *arkit == lowered) {
        const auto same = std::find(table.channels.begin(), table.channels.end(), lowered);
        if (same != table.channels.end())
          throw InputError("column " + quoted(f) + " appears twice", name, headerLine);
        role[c] = Role::Weight;
        channelOf[c] = table.channels.size();
        table.channels.push_back(lowered);
      } else {
        unknown.push_back(f.empty() ? "(column " + std::to_string(c + 1) + ", unnamed)" : std::string(f));
      }
    }
  }
  const int headColumns = (headOf[0] >= 0) + (headOf[1] >= 0) + (headOf[2] >= 0);
  if (headColumns != 0 && headColumns != 3)
    throw InputError(std::string("missing required column '") +
                         (headOf[0] < 0 ? "HeadPitch" : headOf[1] < 0 ? "HeadYaw" : "HeadRoll") +
                         "' (the head's rotation needs HeadPitch, HeadYaw and HeadRoll)",
                     name, headerLine);
  if (table.channels.empty())
    throw InputError("no ARKit blendshape column (EyeBlinkLeft … TongueOut)", name, headerLine);
  const int eyeColumns =
      static_cast<int>(std::count_if(std::begin(eyeOf), std::end(eyeOf), [](int c) { return c >= 0; }));
  if (eyeColumns != 0 && eyeColumns != 4)
    throw InputError(std::string("missing required column '") +
                         kEyeColumns[std::find(std::begin(eyeOf), std::end(eyeOf), -1) - std::begin(eyeOf)] +
                         "' (the eyes' turn needs LeftEyePitch, LeftEyeYaw, RightEyePitch and RightEyeYaw)",
                     name, headerLine);
  table.hasPose = headColumns == 3;
  table.hasGaze = eyeColumns == 4;
  if (!unknown.empty())
    table.warnings.push_back("ignored " + std::to_string(unknown.size()) + " unknown column" +
                             (unknown.size() == 1 ? "" : "s") + ": " + joinNames(unknown));

  std::vector<Timecode> codes;  // per frame of table.frames
  int largestFrame = 0;
  for (size_t li = headerIndex + 1; li < lines.size(); ++li) {
    if (isBlank(lines[li])) continue;
    const int line = static_cast<int>(li + 1);
    const std::vector<std::string_view> cells = splitFields(lines[li]);
    if (cells.size() != header.size())
      throw InputError("row has " + std::to_string(cells.size()) + " fields, the header has " +
                           std::to_string(header.size()),
                       name, line);
    Frame f;
    f.line = line;
    if (cells[0].empty()) {
      f.dropped = "with no timecode";
      table.leftOut.push_back(std::move(f));
      continue;
    }
    Timecode tc;
    if (!readTimecode(cells[0], tc))
      throw InputError("unreadable timecode " + quoted(cells[0]) + " (expected HH:MM:SS:FF or HH:MM:SS:FF.fff)", name,
                       line);
    if (options.inputFps && tc.frame >= *options.inputFps)
      throw InputError("frame " + std::to_string(tc.frame) + " of timecode " + quoted(cells[0]) +
                           " is not below the frame rate " + numberText(*options.inputFps),
                       name, line);
    largestFrame = std::max(largestFrame, tc.frame);
    f.values.resize(table.channels.size());
    bool empty = false;
    for (size_t c = 1; c < cells.size(); ++c) {
      if (role[c] != Role::Weight && role[c] != Role::Head && role[c] != Role::Eye) continue;
      double v = 0;
      switch (readCell(cells[c], v)) {
        case CellRead::Number: break;
        case CellRead::Empty: empty = true; continue;
        case CellRead::Unreadable:
          throw InputError("unreadable number " + quoted(cells[c]) + " in column " + quoted(header[c]), name, line);
        case CellRead::NotFinite:
          throw InputError("non-finite number " + quoted(cells[c]) + " in column " + quoted(header[c]), name, line);
      }
      if (role[c] == Role::Weight) {
        if (v < -kRangeSlack || v > 1 + kRangeSlack)
          throw InputError(std::string(header[c]) + " is " + numberText(v) + ", outside [0, 1]", name, line);
        f.values[channelOf[c]] = std::clamp(v, 0.0, 1.0);
      } else {
        // The plugin maps −180…180° onto −1…1 (above): anything further is not an angle it wrote.
        if (std::fabs(v) > 1 + kRangeSlack)
          throw InputError(std::string(header[c]) + " is " + numberText(v) + ", outside [-1, 1] (degrees / 180)", name,
                           line);
        const int col = static_cast<int>(c);
        if (role[c] == Role::Head) {
          const int axis = col == headOf[0] ? 0 : col == headOf[1] ? 1 : 2;
          f.pose[axis] = 180.0 * v;  // degrees / 180 as written (above)
        } else {
          // kEyeColumns' order: left pitch, left yaw, right pitch, right yaw; EyeGaze's eye 0 is the right.
          const int k = static_cast<int>(std::find(std::begin(eyeOf), std::end(eyeOf), col) - std::begin(eyeOf));
          const size_t eye = k < 2 ? 1 : 0;
          if (k % 2 == 0) f.gaze.pitchDeg[eye] = -180.0 * v;  // a right-handed turn about x looks down (above)
          else f.gaze.yawDeg[eye] = 180.0 * v;
        }
      }
    }
    if (empty) f.dropped = "with empty cells";
    table.frames.push_back(std::move(f));
    codes.push_back(tc);
  }

  // The rate: given, or the largest frame number + 1. A take shorter than a second may not reach
  // the rate's last frame number: then the inference is only a lower bound, and we say so.
  double fps = options.inputFps ? *options.inputFps : largestFrame + 1.0;
  if (!options.inputFps && !codes.empty()) {
    const bool wholeSecond = std::any_of(codes.begin(), codes.end(),
                                         [&](const Timecode& t) { return t.seconds != codes.front().seconds; });
    if (!wholeSecond)
      table.warnings.push_back("frame rate inferred as " + numberText(fps) + " fps from frame numbers up to " +
                               std::to_string(largestFrame) +
                               ", but the take spans no whole second: give the input frame rate (--input-fps)");
  }
  for (size_t i = 0; i < table.frames.size(); ++i)
    table.frames[i].time = codes[i].seconds + (codes[i].frame + codes[i].fraction) / fps;
  table.fps = fps;
  return assemblePerformance(std::move(table), PerformanceInput::LiveLink, name);
}

}  // namespace myo::performance_detail
