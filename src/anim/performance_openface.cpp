// OpenFace 2 CSV (FeatureExtraction, FaceLandmarkVidMulti): the columns OpenFace documents in its
// wiki's "Output Format" page (github.com/TadasBaltrusaitis/OpenFace/wiki/Output-Format): frame,
// face_id, timestamp (s), confidence, success, gaze_*, eye_lmk_*, pose_T* (mm), pose_R* (rad),
// x_*/y_* (px), X_*/Y_*/Z_* (mm), p_* (shape parameters), AUxx_r (intensity 0–5), AUxx_c (presence
// 0/1). We read timestamp, confidence, success, face_id, pose_R*, gaze_angle_x/y and AUxx_r; the
// rest are known and skipped without a word.
#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include <Eigen/Geometry>

#include "myoshell/core/close_names.h"
#include "myoshell/core/errors.h"
#include "performance_frames.h"

namespace myo::performance_detail {

namespace {

bool allDigits(std::string_view s) {
  return !s.empty() && std::all_of(s.begin(), s.end(), [](char c) { return c >= '0' && c <= '9'; });
}

// The AU number of "AU01_r" / "AU45_c" (kind 'r' or 'c'), or -1.
int auNumber(std::string_view f, char& kind) {
  if (f.size() < 5 || f.substr(0, 2) != "AU" || f[f.size() - 2] != '_') return -1;
  kind = f.back();
  if (kind != 'r' && kind != 'c') return -1;
  const std::string_view digits = f.substr(2, f.size() - 4);
  if (!allDigits(digits) || digits.size() > 4) return -1;
  return std::stoi(std::string(digits));
}

// Columns OpenFace writes that we do not read: not "unknown".
bool isOtherOpenFaceColumn(std::string_view f) {
  if (f == "frame") return true;
  for (const std::string_view prefix : {"gaze_", "eye_lmk_", "pose_T", "p_"})
    if (f.substr(0, prefix.size()) == prefix && f.size() > prefix.size()) return true;
  // 2D landmarks x_0…x_67, y_…; 3D landmarks X_…, Y_…, Z_….
  if (f.size() >= 3 && std::string_view("xyXYZ").find(f[0]) != std::string_view::npos && f[1] == '_' &&
      allDigits(f.substr(2)))
    return true;
  return false;
}

// OpenFace's head rotation as a matrix in face-frame coordinates (below): Rx(rx)·Ry(−ry)·Rz(−rz).
Mat3 faceFrameRotation(double rx, double ry, double rz) {
  return (Eigen::AngleAxisd(rx, Vec3::UnitX()) * Eigen::AngleAxisd(-ry, Vec3::UnitY()) *
          Eigen::AngleAxisd(-rz, Vec3::UnitZ()))
      .toRotationMatrix();
}

// OpenFace's head rotation, converted to the face frame's [pitch, yaw, roll] degrees.
//
// OpenFace (lib/local/Utilities/include/RotationHelpers.h, Euler2RotationMatrix) builds
// R = Rx(pose_Rx)·Ry(pose_Ry)·Rz(pose_Rz), right-handed rotation matrices, which turn the head model
// into camera coordinates: x right in the image, y down, z away from the camera. At R = I the face
// looks into the camera, so the model's axes are the face frame's (face_frame.h: x the subject's
// left — which is the image's right — y up, z out of the face towards the viewer) with y and z
// reversed: C = diag(1, −1, −1), its own inverse. The same rotation in face-frame coordinates is
// C·R·C = Rx(Rx)·Ry(−Ry)·Rz(−Rz): pose_Rx > 0 nods the face down (our +pitch), pose_Ry > 0 turns it
// to the subject's right (our −yaw), pose_Rz > 0 tilts it to the subject's left shoulder (our
// −roll). Our angles compose the other way (R = R_z·R_y·R_x, anatomical_face.h headPoseRotation),
// so the matrix is decomposed again rather than the angles copied. The camera is taken as level: a
// tilted camera tilts gravity by as much.
Vec3 faceFramePose(double rx, double ry, double rz) {
  const Mat3 R = faceFrameRotation(rx, ry, rz);
  // R = Rz(roll)·Ry(yaw)·Rx(pitch): R(2,0) = −sin yaw, R(2,1) = cos yaw sin pitch, R(2,2) = cos yaw
  // cos pitch, R(1,0) = sin roll cos yaw, R(0,0) = cos roll cos yaw.
  const double yaw = std::asin(std::clamp(-R(2, 0), -1.0, 1.0));
  const double pitch = std::atan2(R(2, 1), R(2, 2));
  const double roll = std::atan2(R(1, 0), R(0, 0));
  const double deg = 180.0 / M_PI;
  return Vec3(pitch * deg, yaw * deg, roll * deg);
}

// OpenFace's gaze (gaze_angle_x, gaze_angle_y, radians) as the eyes' turn in the head, degrees.
//
// OpenFace (GazeAnalysis::GetGazeAngle; its wiki's "Output Format") averages the two eyes' unit gaze
// vectors g, in the camera's coordinates (x to the image's right, y down, z away from the camera),
// and writes gaze_angle_x = atan2(g_x, −g_z), gaze_angle_y = atan2(g_y, −g_z): 0 looking into the
// camera, gaze_angle_x > 0 towards the image's right (the subject's left), gaze_angle_y > 0 DOWN.
// So g ∝ (tan x, tan y, −1), and in the face frame's orientation (C = diag(1, −1, −1), as the pose
// above) w = C·g ∝ (tan x, −tan y, 1). The angles are the camera's, not the head's: a face turned
// down by 10° that looks into the camera has its eyes turned up by 10° in their orbits, which is
// what the lids follow. With the head's rotation H (face frame, faceFrameRotation) the direction in
// the head is e = Hᵀ·w, and pitch = atan2(e_y, e_z) (+ up), yaw = atan2(e_x, e_z) (+ towards the
// subject's left) — OpenFace's own tangent-plane angles, so without a pose pitch = −y and yaw = x.
// Both eyes get the mean: the per-eye vectors (gaze_0_*, gaze_1_*) differ by more than the vergence
// they would add (docs/performance_input.md).
EyeGaze headGaze(double x, double y, const Mat3* head) {
  Vec3 e(std::tan(x), -std::tan(y), 1.0);
  if (head) e = head->transpose() * e;
  const double deg = 180.0 / M_PI;
  const double pitch = std::atan2(e.y(), e.z()) * deg, yaw = std::atan2(e.x(), e.z()) * deg;
  EyeGaze g;
  g.pitchDeg = {pitch, pitch};
  g.yawDeg = {yaw, yaw};
  return g;
}

struct AuColumn {
  int au = 0;
  size_t column = 0;
};

}  // namespace

Performance parseOpenFace(const std::string& text, const std::string& name, const PerformanceOptions& options) {
  const std::vector<std::string_view> lines = splitLines(text, name);
  const size_t headerIndex = firstNonBlankLine(lines, name);
  const int headerLine = static_cast<int>(headerIndex + 1);
  const std::vector<std::string_view> header = splitFields(lines[headerIndex]);

  std::map<std::string_view, size_t> columnOf;
  for (size_t c = 0; c < header.size(); ++c) {
    const auto [it, inserted] = columnOf.emplace(header[c], c);
    if (!inserted && !header[c].empty())
      throw InputError("column " + quoted(header[c]) + " appears twice (columns " + std::to_string(it->second + 1) +
                           " and " + std::to_string(c + 1) + ")",
                       name, headerLine);
  }
  auto column = [&](std::string_view key) -> std::ptrdiff_t {
    const auto it = columnOf.find(key);
    return it == columnOf.end() ? -1 : static_cast<std::ptrdiff_t>(it->second);
  };
  const std::ptrdiff_t timeCol = column("timestamp");
  if (timeCol < 0) {
    const std::vector<std::string> close = closeNames("timestamp", std::vector<std::string>(header.begin(), header.end()));
    throw InputError("missing required column 'timestamp'" +
                         (close.empty() ? std::string() : " (is " + quoted(close.front()) + " it? OpenFace writes 'timestamp')"),
                     name, headerLine);
  }
  const std::ptrdiff_t confCol = column("confidence"), successCol = column("success"), faceCol = column("face_id");
  const std::ptrdiff_t rxCol = column("pose_Rx"), ryCol = column("pose_Ry"), rzCol = column("pose_Rz");
  const int poseColumns = (rxCol >= 0) + (ryCol >= 0) + (rzCol >= 0);
  if (poseColumns != 0 && poseColumns != 3)
    throw InputError(std::string("missing required column '") + (rxCol < 0 ? "pose_Rx" : ryCol < 0 ? "pose_Ry" : "pose_Rz") +
                         "' (the head's rotation needs pose_Rx, pose_Ry and pose_Rz)",
                     name, headerLine);

  const std::ptrdiff_t gazeXCol = column("gaze_angle_x"), gazeYCol = column("gaze_angle_y");
  if ((gazeXCol >= 0) != (gazeYCol >= 0))
    throw InputError(std::string("missing required column '") + (gazeXCol < 0 ? "gaze_angle_x" : "gaze_angle_y") +
                         "' (the gaze needs gaze_angle_x and gaze_angle_y)",
                     name, headerLine);

  std::vector<AuColumn> aus;
  bool hasPresence = false;
  std::vector<std::string> unknown;
  for (size_t c = 0; c < header.size(); ++c) {
    const std::string_view f = header[c];
    char kind = 0;
    const int au = auNumber(f, kind);
    if (au >= 0 && kind == 'r') {
      const auto same = std::find_if(aus.begin(), aus.end(), [&](const AuColumn& a) { return a.au == au; });
      if (same != aus.end())
        throw InputError("columns " + quoted(header[same->column]) + " and " + quoted(f) + " are both AU" +
                             std::to_string(au),
                         name, headerLine);
      aus.push_back({au, c});
    } else if (au >= 0) {
      hasPresence = true;  // AUxx_c: presence 0/1, not an intensity; its existence tells the scale
    } else if (f == "timestamp" || f == "confidence" || f == "success" || f == "face_id" || f == "pose_Rx" ||
               f == "pose_Ry" || f == "pose_Rz" || isOtherOpenFaceColumn(f)) {
    } else {
      unknown.push_back(f.empty() ? "(column " + std::to_string(c + 1) + ", unnamed)" : std::string(f));
    }
  }
  if (aus.empty())
    throw InputError("no action-unit intensity column (AUxx_r): OpenFace writes them with -aus", name, headerLine);
  std::sort(aus.begin(), aus.end(), [](const AuColumn& a, const AuColumn& b) { return a.au < b.au; });

  FrameTable table;
  table.hasPose = poseColumns == 3;
  table.hasGaze = gazeXCol >= 0;
  // The scale (issue 18; ../shared/data/openface/README.md): raw OpenFace writes 0–5 and always
  // writes face_id and the AUxx_c columns; cleaned files (FACSvatar's) keep neither and are 0–1.
  const bool raw = faceCol >= 0 || hasPresence;
  table.auScale = options.auScale ? *options.auScale : raw ? 5.0 : 1.0;
  const std::string scaleHint =
      options.auScale ? "the scale given"
      : raw           ? "scale 5: the header has face_id or AUxx_c columns, as raw OpenFace output"
                      : "scale 1: the header has no face_id or AUxx_c column; raw OpenFace intensities 0–5 need "
                        "--au-scale 5";
  for (const AuColumn& a : aus) table.channels.push_back("AU" + std::to_string(a.au));
  if (!unknown.empty())
    table.warnings.push_back("ignored " + std::to_string(unknown.size()) + " unknown column" +
                             (unknown.size() == 1 ? "" : "s") + ": " + joinNames(unknown));

  std::set<long long> faces;  // every face_id seen
  const double scale = table.auScale;
  for (size_t li = headerIndex + 1; li < lines.size(); ++li) {
    if (isBlank(lines[li])) continue;
    const int line = static_cast<int>(li + 1);
    const std::vector<std::string_view> cells = splitFields(lines[li]);
    if (cells.size() != header.size())
      throw InputError("row has " + std::to_string(cells.size()) + " fields, the header has " +
                           std::to_string(header.size()),
                       name, line);
    // A number in column c; empty cells are reported (and the frame dropped) by the caller.
    auto number = [&](std::ptrdiff_t c, double& x) -> bool {
      const std::string_view cell = cells[static_cast<size_t>(c)];
      switch (readCell(cell, x)) {
        case CellRead::Number: return true;
        case CellRead::Empty: return false;
        case CellRead::Unreadable:
          throw InputError("unreadable number " + quoted(cell) + " in column " + quoted(header[static_cast<size_t>(c)]),
                           name, line);
        case CellRead::NotFinite:
          throw InputError("non-finite number " + quoted(cell) + " in column " + quoted(header[static_cast<size_t>(c)]),
                           name, line);
      }
      return false;
    };
    double x = 0;
    if (faceCol >= 0) {
      if (!number(faceCol, x)) {  // the row belongs to no face
        table.leftOut.push_back(Frame{line, 0.0, {}, Vec3::Zero(), EyeGaze{}, "with no face_id"});
        continue;
      }
      if (x != std::floor(x) || std::fabs(x) > 1e9)
        throw InputError("face_id " + quoted(cells[static_cast<size_t>(faceCol)]) + " is not an integer", name, line);
      faces.insert(static_cast<long long>(x));
      if (options.face >= 0 && static_cast<long long>(x) != options.face) continue;
    }
    Frame f;
    f.line = line;
    if (!number(timeCol, f.time)) {
      f.dropped = "with no timestamp";
      table.leftOut.push_back(std::move(f));
      continue;
    }
    bool empty = false;
    f.values.resize(aus.size());
    for (size_t k = 0; k < aus.size(); ++k) {
      double v = 0;
      if (!number(static_cast<std::ptrdiff_t>(aus[k].column), v)) {
        empty = true;
        continue;
      }
      if (v < -kRangeSlack * scale || v > scale * (1 + kRangeSlack))
        throw InputError(std::string(header[aus[k].column]) + " is " + numberText(v) + ", outside [0, " +
                             numberText(scale) + "] (" + scaleHint + ")",
                         name, line);
      f.values[k] = std::clamp(v / scale, 0.0, 1.0);
    }
    double r[3] = {0, 0, 0};
    bool poseRead = false;
    if (table.hasPose) {
      const std::ptrdiff_t cols[3] = {rxCol, ryCol, rzCol};
      poseRead = true;
      for (int a = 0; a < 3; ++a) poseRead = number(cols[a], r[a]) && poseRead;
      empty = empty || !poseRead;
      if (poseRead) f.pose = faceFramePose(r[0], r[1], r[2]);
    }
    if (table.hasGaze) {
      double g[2] = {0, 0};
      const std::ptrdiff_t cols[2] = {gazeXCol, gazeYCol};
      bool read = true;
      for (int a = 0; a < 2; ++a) {
        if (!number(cols[a], g[a])) {
          read = false;
          continue;
        }
        // Beyond ±π/2 the vector points away from the camera: no angle OpenFace's atan2 gives a face it sees.
        if (!(std::fabs(g[a]) < 0.5 * M_PI))
          throw InputError(std::string(header[static_cast<size_t>(cols[a])]) + " is " + numberText(g[a]) +
                               " radians, outside (-π/2, π/2)",
                           name, line);
      }
      empty = empty || !read;
      if (read) {
        const Mat3 head = faceFrameRotation(r[0], r[1], r[2]);
        f.gaze = headGaze(g[0], g[1], poseRead ? &head : nullptr);
      }
    }
    double success = 1, confidence = 1;
    if (successCol >= 0) empty = !number(successCol, success) || empty;
    if (confCol >= 0) empty = !number(confCol, confidence) || empty;
    if (empty)
      f.dropped = "with empty cells";
    else if (success == 0)
      f.dropped = "with success 0";
    else if (confidence < options.minConfidence)
      f.dropped = "with confidence below " + numberText(options.minConfidence);
    table.frames.push_back(std::move(f));
  }

  if (faceCol >= 0 && options.face < 0 && faces.size() > 1) {
    std::vector<std::string> ids;
    for (const long long id : faces) ids.push_back(std::to_string(id));
    throw InputError("the file holds " + std::to_string(faces.size()) + " faces (face_id " + joinNames(ids) +
                         "): choose one (--face N)",
                     name);
  }
  if (options.face >= 0 && (faceCol >= 0 ? faces.count(options.face) == 0 : options.face != 0)) {
    std::vector<std::string> ids;
    for (const long long id : faces) ids.push_back(std::to_string(id));
    throw InputError("face_id " + std::to_string(options.face) + " is not in the file (" +
                         (faceCol < 0 ? std::string("it has no face_id column: one face, 0")
                                      : "its faces: " + (ids.empty() ? std::string("none") : joinNames(ids))) +
                         ")",
                     name);
  }
  return assemblePerformance(std::move(table), PerformanceInput::OpenFace, name);
}

}  // namespace myo::performance_detail
