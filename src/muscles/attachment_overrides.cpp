#include "myoshell/muscles/attachment_overrides.h"

#include <cmath>
#include <map>

#include "myoshell/core/doc_reader.h"
#include "myoshell/core/errors.h"

namespace myo {

std::vector<AttachmentOverride> readAttachmentOverrides(const YAML::Node& root, int vertexCount,
                                                        const std::string& name) {
  DocReader top(root, name);
  top.string("note", "");
  const YAML::Node list = top.node("overrides");
  if (!list.IsSequence()) top.failAt(list, "overrides", "must be a list of {vertices, k_att}");
  top.finish();
  std::vector<AttachmentOverride> out;
  std::map<int, std::string> firstEntry;  // vertex → the entry that named it
  for (size_t i = 0; i < list.size(); ++i) {
    const std::string entry = "overrides[" + std::to_string(i) + "]";
    DocReader r(list[i], name, entry);
    r.string("note", "");
    const double k = r.requiredNumber("k_att");
    r.requireAbove("k_att", k, 0.0);
    const YAML::Node vertices = r.node("vertices");
    const std::string vpath = r.keyPath("vertices");
    if (!vertices.IsSequence()) r.failAt(vertices, vpath, "must be a list of vertex indices");
    if (vertices.size() == 0) r.failAt(vertices, vpath, "must name at least one vertex");
    r.finish();
    for (size_t j = 0; j < vertices.size(); ++j) {
      const std::string at = vpath + "[" + std::to_string(j) + "]";
      const double v = r.asNumber(vertices[j], at);
      if (v < 0 || v != std::floor(v)) r.failAt(vertices[j], at, "must be an integer ≥ 0 (got " + vertices[j].Scalar() + ")");
      if (v >= vertexCount)
        r.failAt(vertices[j], at,
                 "vertex " + vertices[j].Scalar() + " is outside [0, " + std::to_string(vertexCount) + ") of the head");
      const int vertex = static_cast<int>(v);  // < vertexCount: the cast is defined
      const auto inserted = firstEntry.emplace(vertex, entry);
      if (!inserted.second)
        r.failAt(vertices[j], at, "vertex " + std::to_string(vertex) + " is already set by " + inserted.first->second);
      out.push_back({vertex, k});
    }
  }
  return out;
}

std::vector<AttachmentOverride> parseAttachmentOverrides(const std::string& text, int vertexCount,
                                                         const std::string& name) {
  return readAttachmentOverrides(loadDocument(text, name), vertexCount, name);
}

}  // namespace myo
