// Per-vertex overrides of the attachment stiffness (muscles/attachment_overrides.h, the scene key
// skin.attachment): the file's entries, its errors, and the tissue map they change.
#include <gtest/gtest.h>

#include "myoshell/core/errors.h"
#include "myoshell/head/head.h"
#include "myoshell/muscles/attachment_overrides.h"

namespace myo {
namespace {

std::string attachmentErrorOf(const std::string& text, int vertexCount = 468) {
  try {
    parseAttachmentOverrides(text, vertexCount, "att.json");
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(AttachmentOverrides, EachEntrySetsItsVerticesInOrder) {
  const std::vector<AttachmentOverride> o = parseAttachmentOverrides(
      R"({"note": "lips", "overrides": [{"vertices": [12, 3], "k_att": 3e5, "note": "upper"}, {"vertices": [40], "k_att": 250}]})",
      468);
  ASSERT_EQ(o.size(), 3u);
  EXPECT_EQ(o[0].vertex, 12);
  EXPECT_EQ(o[1].vertex, 3);
  EXPECT_EQ(o[2].vertex, 40);
  EXPECT_DOUBLE_EQ(o[0].stiffness, 3e5);
  EXPECT_DOUBLE_EQ(o[1].stiffness, 3e5);
  EXPECT_DOUBLE_EQ(o[2].stiffness, 250.0);
  // YAML reads the same.
  const std::vector<AttachmentOverride> y = parseAttachmentOverrides("overrides:\n  - {vertices: [12, 3], k_att: 3e5}\n", 468);
  ASSERT_EQ(y.size(), 2u);
  EXPECT_EQ(y[1].vertex, 3);
}

TEST(AttachmentOverrides, ErrorsNameTheFileLineColumnAndFault) {
  EXPECT_EQ(attachmentErrorOf("{\"overrides\": [\n  {\"vertices\": [1, 468], \"k_att\": 1e5}]}"),
            "att.json:2:20: key 'overrides[0].vertices[1]': vertex 468 is outside [0, 468) of the head");
  EXPECT_EQ(attachmentErrorOf("{\"overrides\": [{\"vertices\": [1], \"k_att\": -5}]}"),
            "att.json:1:43: key 'overrides[0].k_att': must be > 0 (got -5)");
  EXPECT_EQ(attachmentErrorOf("{\"overrides\": [{\"vertices\": [1], \"k_att\": 0}]}"),
            "att.json:1:43: key 'overrides[0].k_att': must be > 0 (got 0)");
  EXPECT_EQ(attachmentErrorOf("{\"overrides\": [{\"vertices\": [1], \"k_att\": 5, \"held\": 1}]}"),
            "att.json:1:46: key 'overrides[0].held': unknown key");
  EXPECT_EQ(attachmentErrorOf("{\"overrides\": [{\"vertices\": \"1\", \"k_att\": 5}]}"),
            "att.json:1:29: key 'overrides[0].vertices': must be a list of vertex indices");
  EXPECT_EQ(attachmentErrorOf("{\"overrides\": [{\"vertices\": [1], \"k_att\": \"5\"}]}"),
            "att.json:1:43: key 'overrides[0].k_att': must be a number");
  EXPECT_EQ(attachmentErrorOf("{\"overrides\": [{\"vertices\": [1.5], \"k_att\": 5}]}"),
            "att.json:1:30: key 'overrides[0].vertices[0]': must be an integer ≥ 0 (got 1.5)");
  EXPECT_EQ(attachmentErrorOf("{\"overrides\": [{\"vertices\": [-1], \"k_att\": 5}]}"),
            "att.json:1:30: key 'overrides[0].vertices[0]': must be an integer ≥ 0 (got -1)");
  EXPECT_EQ(attachmentErrorOf("{\"overrides\": [{\"vertices\": [], \"k_att\": 5}]}"),
            "att.json:1:29: key 'overrides[0].vertices': must name at least one vertex");
  EXPECT_EQ(attachmentErrorOf("{\"overrides\": [{\"vertices\": [2], \"k_att\": 5}, {\"vertices\": [2], \"k_att\": 6}]}"),
            "att.json:1:61: key 'overrides[1].vertices[0]': vertex 2 is already set by overrides[0]");
  EXPECT_EQ(attachmentErrorOf("{\"overrides\": [{\"k_att\": 5}]}"), "att.json:1:16: key 'overrides[0].vertices': missing required key");
  EXPECT_EQ(attachmentErrorOf("{\"overrides\": {\"vertices\": [1]}}"), "att.json:1:15: key 'overrides': must be a list of {vertices, k_att}");
  EXPECT_EQ(attachmentErrorOf("[1, 2]"), "att.json:1:1: key '(document)': must be an object");
  EXPECT_EQ(attachmentErrorOf("{\"overrides\": [{\"vertices\": [1e300], \"k_att\": 5}]}"),
            "att.json:1:30: key 'overrides[0].vertices[0]': vertex 1e300 is outside [0, 468) of the head");
}

// The override replaces k_att at exactly the named vertices; every other vertex, and the other maps,
// keep the region map's values.
TEST(AttachmentOverrides, ChangeTheTissueMapAtExactlyTheNamedVertices) {
  const Head head = loadDefaultHead();
  const TissueMap base = tissueMap(head);
  TissueMap map = base;
  applyAttachmentOverrides(map, parseAttachmentOverrides(
                                    R"({"overrides": [{"vertices": [13, 14], "k_att": 7e5}, {"vertices": [300], "k_att": 20}]})",
                                    head.mesh.vertexCount()));
  for (int i = 0; i < map.size(); ++i) {
    const double expected = i == 13 || i == 14 ? 7e5 : i == 300 ? 20.0 : base.attachment(i);
    EXPECT_EQ(map.attachment(i), expected) << i;
  }
  EXPECT_EQ(map.thickness, base.thickness);
  EXPECT_EQ(map.held, base.held);
  EXPECT_EQ(map.area, base.area);
}

}  // namespace
}  // namespace myo
