// Per-vertex overrides of the skin's attachment stiffness k_att (tissue_attachment.h), as data: the
// file the scene key `skin.attachment` names (docs/scene_format.md, "Attachment overrides"):
//
//   {"note": "…", "overrides": [{"vertices": [12, 40, 41], "k_att": 3e5, "note": "…"}, …]}
//
// Each entry sets k_att (dyn/cm³, > 0) at the listed vertices of the head; a vertex may be named
// once in the whole file. JSON or YAML (core/doc_reader.h); unknown keys are errors.
#pragma once

#include <string>
#include <vector>

#include "myoshell/muscles/tissue_attachment.h"

namespace YAML {
class Node;
}

namespace myo {

// Parses an override document for a head of `vertexCount` vertices, one AttachmentOverride per named
// vertex, in the file's order. Errors (InputError) name `name:line:col`, the key path and the fault:
// a vertex outside [0, vertexCount), a vertex named twice, k_att ≤ 0, a wrong type, an unknown key.
std::vector<AttachmentOverride> parseAttachmentOverrides(const std::string& text, int vertexCount,
                                                         const std::string& name = "<string>");
// The same over a document already loaded (io reads the file with it).
std::vector<AttachmentOverride> readAttachmentOverrides(const YAML::Node& root, int vertexCount,
                                                        const std::string& name);

}  // namespace myo
