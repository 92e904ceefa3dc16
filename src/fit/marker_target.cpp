#include "myoshell/fit/marker_target.h"

#include <cmath>
#include <map>

#include "myoshell/core/doc_reader.h"
#include "myoshell/core/errors.h"
#include "myoshell/head/head_checks.h"

namespace myo {

MarkerTarget readMarkerTarget(const YAML::Node& root, int vertexCount, const std::string& name) {
  DocReader top(root, name);
  top.string("note", "");
  MarkerTarget out;
  const YAML::Node unitNode = top.node("units");
  const std::string unitText = top.asString(unitNode, "units");
  if (unitText != "cm" && unitText != "mm" && unitText != "m")
    top.failAt(unitNode, "units", "unknown length unit '" + unitText + "' (use cm, mm or m)");
  out.unit = parseLengthUnit(unitText, name);
  const double toCm = centimetresPer(out.unit);
  const YAML::Node list = top.node("markers");
  if (!list.IsSequence()) top.failAt(list, "markers", "must be a list of {vertex, position}");
  if (list.size() == 0) top.failAt(list, "markers", "must hold at least one marker");
  top.finish();
  out.positions.resize(static_cast<Eigen::Index>(list.size()), 3);
  std::map<int, size_t> first;  // vertex → the marker that named it
  for (size_t i = 0; i < list.size(); ++i) {
    const std::string entry = "markers[" + std::to_string(i) + "]";
    DocReader r(list[i], name, entry);
    r.string("note", "");
    const YAML::Node vertexNode = r.node("vertex");
    const double v = r.asNumber(vertexNode, r.keyPath("vertex"));
    if (v < 0 || v != std::floor(v))
      r.failAt(vertexNode, r.keyPath("vertex"), "must be an integer ≥ 0 (got " + vertexNode.Scalar() + ")");
    if (v >= vertexCount)
      r.failAt(vertexNode, r.keyPath("vertex"),
               "vertex " + vertexNode.Scalar() + " is outside [0, " + std::to_string(vertexCount) + ") of the head");
    const int vertex = static_cast<int>(v);  // < vertexCount: the cast is defined
    const auto inserted = first.emplace(vertex, i);
    if (!inserted.second)
      r.failAt(vertexNode, r.keyPath("vertex"),
               "vertex " + std::to_string(vertex) + " is already placed by markers[" + std::to_string(inserted.first->second) + "]");
    const YAML::Node p = r.node("position");
    const std::string ppath = r.keyPath("position");
    if (!p.IsSequence() || p.size() != 3) r.failAt(p, ppath, "must be three numbers [x, y, z]");
    for (int a = 0; a < 3; ++a) {
      const std::string at = ppath + "[" + std::to_string(a) + "]";
      const double cm = r.asNumber(p[static_cast<size_t>(a)], at) * toCm;
      if (!std::isfinite(cm)) r.failAt(p[static_cast<size_t>(a)], at, "is too large (" + p[static_cast<size_t>(a)].Scalar() + ")");
      out.positions(static_cast<Eigen::Index>(i), a) = cm;
    }
    r.finish();
    out.vertices.push_back(vertex);
  }
  return out;
}

MarkerTarget parseMarkerTarget(const std::string& text, int vertexCount, const std::string& name) {
  return readMarkerTarget(loadDocument(text, name), vertexCount, name);
}

}  // namespace myo
