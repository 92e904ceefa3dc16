// Facial landmarks of a head: the 68 Multi-PIE points and named points, as vertex ids.
//
// File layout (that of ../shared/data/ict/landmarks_multipie68.json; docs/heads.md):
//   { "multipie68": [68 vertex ids],                       optional
//     "named": { "nose_tip": {"vertex": 4}, ... },         optional; "multipie_index" allowed
//     "groups", "source", "note", "confidence" (myoshell landmarks), ...: ignored }
// or a plain map { "nose_tip": 4, "chin_menton": 152, ... }. Multi-PIE order: jaw 0–16 (from the
// subject's right), right brow 17–21, left brow 22–26, nose bridge 27–30, nose base 31–35, right
// eye 36–41, left eye 42–47, outer lips 48–59, inner lips 60–67; 'right'/'left' are the subject's.
#pragma once

#include <array>
#include <map>
#include <string>
#include <string_view>
#include <vector>

namespace myo {

// A landmark the face model places muscles from, with the Multi-PIE point that stands in for it
// when a file does not name it.
struct RequiredLandmark {
  const char* name;
  int multipieIndex;  // 0-based index into the 68 points
};

// The names muscle placement needs (docs/heads.md). A head must resolve every one of them, by
// name or through its Multi-PIE point.
inline constexpr std::array<RequiredLandmark, 17> kRequiredLandmarks = {{
    {"right_eye_outer", 36},
    {"right_eye_inner", 39},
    {"left_eye_inner", 42},
    {"left_eye_outer", 45},
    {"right_brow_outer", 17},
    {"right_brow_inner", 21},
    {"left_brow_inner", 22},
    {"left_brow_outer", 26},
    {"nasion_approx", 27},
    {"nose_tip", 30},
    {"mouth_corner_right", 48},
    {"mouth_corner_left", 54},
    {"upper_lip_top", 51},
    {"lower_lip_bottom", 57},
    {"upper_lip_inner", 62},
    {"lower_lip_inner", 66},
    {"chin_menton", 8},
}};

struct Landmarks {
  std::vector<int> multipie68;          // the 68 points as vertex ids, or empty when not given
  std::map<std::string, int> named;     // name → vertex id, as the file names them
  std::string sourcePath;               // file it came from ("" when built in memory)

  // The vertex of a landmark: the named entry if present, else the Multi-PIE point a required
  // name stands for. Throws InputError naming the landmark (and the file) when neither exists.
  int vertex(std::string_view name) const;
  // Whether vertex(name) would succeed.
  bool has(std::string_view name) const;
  // Every named and required landmark this head resolves, name → vertex id (sorted by name).
  std::map<std::string, int> resolved() const;
  // Throws InputError naming the first required landmark (kRequiredLandmarks) that is missing.
  void requireAll() const;
};

// Parses a landmark file's text; every vertex id must lie in [0, vertexCount). Errors (InputError)
// name `name` and: the line and column of a JSON syntax error; "multipie68 must hold 68 vertex
// ids"; the landmark whose vertex id is out of range or not an integer. Does not check the required
// names (see Landmarks::requireAll, which loadHead calls).
Landmarks parseLandmarks(const std::string& jsonText, int vertexCount,
                         const std::string& name = "<string>");
// (Reading a landmark file: io/head_files.h, readLandmarks.)

// Writes landmarks in the file layout above (multipie68, then named as {"vertex": id}).
std::string landmarksToJson(const Landmarks& landmarks);

}  // namespace myo
