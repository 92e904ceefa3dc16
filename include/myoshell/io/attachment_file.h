// Attachment overrides from a file (the scene key `skin.attachment`; the face layer parses the text:
// muscles/attachment_overrides.h).
#pragma once

#include <string>
#include <vector>

#include "myoshell/muscles/attachment_overrides.h"

namespace myo {

// Reads an override file for a head of `vertexCount` vertices (parseAttachmentOverrides's format and
// errors; InputError "cannot open file" when unreadable, "file is empty" when empty).
std::vector<AttachmentOverride> readAttachmentOverrideFile(const std::string& path, int vertexCount);

}  // namespace myo
