#include "myoshell/io/attachment_file.h"

#include "myoshell/core/doc_reader.h"

namespace myo {

std::vector<AttachmentOverride> readAttachmentOverrideFile(const std::string& path, int vertexCount) {
  return readAttachmentOverrides(loadDocumentFile(path), vertexCount, path);
}

}  // namespace myo
