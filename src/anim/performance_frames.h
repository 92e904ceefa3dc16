// Private to the performance readers (performance*.cpp): the text helpers the three share, and the
// frame table each reader fills and assemblePerformance turns into a Performance — the one place
// that checks times, bridges and trims dropped frames, and reports them.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "myoshell/anim/performance.h"

namespace myo::performance_detail {

// A value may leave its range by this much (round-off in the writer) and is clamped back.
constexpr double kRangeSlack = 1e-6;

// The text's lines (core/text_lines.h) after a UTF-8 byte-order mark (Excel writes one).
std::vector<std::string_view> splitLines(const std::string& text, const std::string& name);
// The index of the first line that is not blank (the header). InputError "the performance file is
// empty" when there is none.
size_t firstNonBlankLine(const std::vector<std::string_view>& lines, const std::string& name);

// The comma-separated fields of a line, each trimmed of spaces and tabs: OpenFace's Windows builds
// write the header's names separated by ", ".
std::vector<std::string_view> splitFields(std::string_view line);

std::string_view trim(std::string_view s);
bool isBlank(std::string_view line);

// 'text', cut to 40 characters, for messages.
std::string quoted(std::string_view s);
// A number for messages: shortest form that reads back ("0.04", "1e+300").
std::string numberText(double x);

enum class CellRead { Number, Empty, Unreadable, NotFinite };
// A decimal number (an optional leading '+', then what std::from_chars reads in full). "nan",
// "inf" and numbers beyond double's range read as NotFinite.
CellRead readCell(std::string_view cell, double& out);

// One row (frame) as read. A dropped frame keeps its place in time and is bridged.
struct Frame {
  int line = 0;                 // 1-based line in the file
  double time = 0.0;            // s, as written (assemblePerformance subtracts the first kept frame's)
  std::vector<double> values;   // one per FrameTable::channels (anything when dropped)
  Vec3 pose = Vec3::Zero();     // [pitch, yaw, roll] degrees (face frame), when FrameTable::hasPose
  EyeGaze gaze;                 // the eyes' turn in the head, degrees, when FrameTable::hasGaze
  std::string dropped;          // why the frame is dropped ("with empty cells", …); empty: valid
};

struct FrameTable {
  std::vector<std::string> channels;
  bool hasPose = false;
  bool hasGaze = false;
  std::vector<Frame> frames;
  std::vector<Frame> leftOut;  // dropped rows with no place in time (an empty time cell), reason set
  double fps = 0.0;            // > 0: the file's own rate (Live Link's timecode); 0: (frames − 1) / duration
  double auScale = 1.0;
  std::vector<std::string> warnings;  // the reader's own (unknown columns, …), before the dropped-frame one
};

// Checks the times (finite, ≥ 0, strictly increasing: InputError at the frame's line), trims the
// dropped frames at the ends, bridges those inside by linear interpolation in time between the
// valid frames around them, and warns once about them. Fewer than two valid frames is an error.
Performance assemblePerformance(FrameTable table, PerformanceInput input, const std::string& name);

Performance parseOpenFace(const std::string& text, const std::string& name, const PerformanceOptions& options);
Performance parseLiveLink(const std::string& text, const std::string& name, const PerformanceOptions& options);
Performance parseMediaPipe(const std::string& text, const std::string& name, const PerformanceOptions& options);

}  // namespace myo::performance_detail
