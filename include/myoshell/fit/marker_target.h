// Marker targets for fitting (`myoshell fit MARKERS.json`, docs/fitting.md): where a few vertices of
// the head should be, e.g. 68 landmarks tracked on a photo or a scan:
//
//   {"units": "cm", "markers": [{"vertex": 48, "position": [x, y, z]}, …], "note": "…"}
//
// `units` (cm, mm or m) is required: a marker file in the wrong unit would fit nonsense silently.
// JSON or YAML (core/doc_reader.h); unknown keys are errors.
#pragma once

#include <string>
#include <vector>

#include "myoshell/core/types.h"
#include "myoshell/head/head.h"

namespace YAML {
class Node;
}

namespace myo {

struct MarkerTarget {
  LengthUnit unit = LengthUnit::cm;  // as the file gave it
  std::vector<int> vertices;         // k vertex ids of the head, each once, in the file's order
  MatX3 positions;                   // k×3, cm (converted from `unit`)
};

// Parses a marker document for a head of `vertexCount` vertices. Errors (InputError) name
// `name:line:col`, the key path and the fault: a missing or unknown unit, no markers, a vertex
// outside [0, vertexCount) or named twice, a position that is not three finite numbers, a wrong
// type, an unknown key.
MarkerTarget parseMarkerTarget(const std::string& text, int vertexCount, const std::string& name = "<string>");
// The same over a document already loaded (io reads the file with it).
MarkerTarget readMarkerTarget(const YAML::Node& root, int vertexCount, const std::string& name);

}  // namespace myo
