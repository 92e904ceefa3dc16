// The scene key skin.attachment end to end (io reads the file relative to the scene, the anatomical
// face takes the overrides): the tissue map changes at exactly the named vertices, and a stiffer
// attachment there holds those vertices closer to rest when the face settles.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <numeric>

#include "myoshell/anatomy/anatomical_face.h"
#include "myoshell/anim/scene_parser.h"
#include "myoshell/core/errors.h"
#include "myoshell/io/scene_face.h"

namespace myo {
namespace {

namespace fs = std::filesystem;

void write(const fs::path& p, const std::string& text) {
  std::ofstream(p) << text;
}

class SceneAttachment : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::path(::testing::TempDir()) / ("scene_attachment_" + std::to_string(::getpid()));
    fs::create_directories(dir_ / "data");
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::shared_ptr<const AnatomicalFace> face(const std::string& sceneText) const {
    write(dir_ / "s.json", sceneText);
    auto f = std::dynamic_pointer_cast<const AnatomicalFace>(buildSceneFace(readScene((dir_ / "s.json").string())));
    if (!f) throw std::logic_error("not an anatomical face");
    return f;
  }
  static MatX3 settled(const AnatomicalFace& f) {
    SkinLoads loads;
    loads.activations = VecX::Zero(f.muscleCount());
    loads.activations(f.muscleIndex("zygomaticus_major_left")) = 1.0;
    loads.gravity = f.skin().restGravity();  // upright: no gravity load
    return f.skin().settle(loads, false).u;
  }
  fs::path dir_;
};

TEST_F(SceneAttachment, AStifferAttachmentHoldsTheNamedVerticesCloserToRest) {
  const std::string muscles = R"("muscles": {"use": ["zygomaticus_major_left"]}, "gravity": {"enabled": false})";
  const auto plain = face("{" + muscles + "}");
  const MatX3 u0 = settled(*plain);
  // The ten vertices the smile moves most.
  std::vector<int> order(static_cast<size_t>(u0.rows()));
  std::iota(order.begin(), order.end(), 0);
  std::partial_sort(order.begin(), order.begin() + 10, order.end(),
                    [&](int a, int b) { return u0.row(a).norm() > u0.row(b).norm(); });
  const std::vector<int> named(order.begin(), order.begin() + 10);
  std::string list;
  for (const int v : named) list += (list.empty() ? "" : ", ") + std::to_string(v);
  const double kStiff = 3e7;  // 100 × the held value: bone-like
  write(dir_ / "data" / "att.json", "{\"overrides\": [{\"vertices\": [" + list + "], \"k_att\": 3e7}]}");

  const auto held = face("{" + muscles + R"(, "skin": {"attachment": "data/att.json"}})");
  const VecX& k0 = plain->skin().tissue().attachment;
  const VecX& k1 = held->skin().tissue().attachment;
  ASSERT_EQ(k0.size(), k1.size());
  for (Eigen::Index i = 0; i < k0.size(); ++i) {
    const bool isNamed = std::find(named.begin(), named.end(), static_cast<int>(i)) != named.end();
    EXPECT_EQ(k1(i), isNamed ? kStiff : k0(i)) << i;
  }

  const MatX3 u1 = settled(*held);
  double before = 0.0, after = 0.0;
  for (const int v : named) {
    EXPECT_LT(u1.row(v).norm(), u0.row(v).norm()) << "vertex " << v;
    before += u0.row(v).norm();
    after += u1.row(v).norm();
  }
  RecordProperty("named_mean_mm_without", std::to_string(10.0 * before / 10));
  RecordProperty("named_mean_mm_with", std::to_string(10.0 * after / 10));
  EXPECT_LT(after, 0.5 * before);
}

TEST_F(SceneAttachment, AVertexOutsideTheHeadIsAnErrorNamingTheFileAndPlace) {
  write(dir_ / "data" / "att.json", "{\"overrides\": [\n  {\"vertices\": [5, 7152], \"k_att\": 1e5}\n]}");
  try {
    face(R"({"skin": {"attachment": "data/att.json"}})");
    FAIL() << "accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), (dir_ / "data" / "att.json").string() +
                                         ":2:20: key 'overrides[0].vertices[1]': vertex 7152 is outside [0, 6990) of the head");
  }
  try {
    face(R"({"skin": {"attachment": "data/none.json"}})");
    FAIL() << "accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("data/none.json: cannot open file"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace myo
