// Our GLB exports pass the Khronos glTF-Validator with no error: a small mesh written by writeGlb
// (plain, capped to two targets, a single frame, with UVs and with split UV seams), rigs, and the GLB
// of a `myoshell run`. The validator (npm gltf-validator,
// installed by scripts/fetch_gltf_validator) runs through tools/validate_gltf.mjs under node; the
// tests skip with a message when either is missing.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "myoshell/io/animation_export.h"
#include "myoshell/io/rig_export.h"
#include "myoshell/mesh/obj_reader.h"
#include "support/cli_runner.h"
#include "support/grid_animation.h"
#include "support/scratch_folder.h"
#include "support/seam_rig.h"
#include "support/test_data.h"
#include "support/uv_seam_mesh.h"

namespace myo {
namespace {

namespace fs = std::filesystem;

fs::path validatorScript() { return test::sourceDir() / "tools" / "validate_gltf.mjs"; }
fs::path validatorPackage() {
  if (const char* env = std::getenv("MYO_GLTF_VALIDATOR_DIR")) return fs::path(env) / "node_modules" / "gltf-validator";
  return test::sourceDir() / ".cache" / "gltf-validator" / "node_modules" / "gltf-validator";
}
bool haveNode() { return std::system("node --version > /dev/null 2>&1") == 0; }

#define MYO_REQUIRE_GLTF_VALIDATOR()                                                                  \
  do {                                                                                                \
    if (!haveNode()) GTEST_SKIP() << "node not found on PATH (Debian package nodejs): validator test skipped"; \
    if (!fs::exists(validatorPackage() / "package.json"))                                            \
      GTEST_SKIP() << "glTF-Validator not installed at " << validatorPackage()                        \
                   << " (run scripts/fetch_gltf_validator): validator test skipped";                  \
  } while (0)

std::string shellQuote(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

struct Validation {
  int exitCode = -1;
  nlohmann::json report;  // tools/validate_gltf.mjs's JSON line
  std::string raw;
};

// Runs the validator on `file`.
Validation validate(const fs::path& file) {
  Validation v;
  const std::string cmd = "node " + shellQuote(validatorScript().string()) + " " + shellQuote(file.string()) + " 2>&1";
  FILE* p = ::popen(cmd.c_str(), "r");
  if (!p) return v;
  char buf[4096];
  size_t n;
  while ((n = std::fread(buf, 1, sizeof buf, p)) > 0) v.raw.append(buf, n);
  const int status = ::pclose(p);
  v.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  v.report = nlohmann::json::parse(v.raw, nullptr, false);
  return v;
}

// Asserts no error, and reports the counts in the test output.
void expectValid(const fs::path& file) {
  const Validation v = validate(file);
  ASSERT_FALSE(v.report.is_discarded()) << "validator printed no JSON: " << v.raw;
  ASSERT_TRUE(v.report.contains("numErrors")) << v.raw;
  std::cout << "[ glTF-Validator " << v.report.value("validatorVersion", "?") << " ] " << file.filename().string()
            << ": " << v.report["numErrors"] << " errors, " << v.report["numWarnings"] << " warnings, "
            << v.report["numInfos"] << " infos, " << v.report["numHints"] << " hints\n";
  EXPECT_EQ(v.report["numErrors"].get<int>(), 0) << v.report["messages"].dump(2);
  EXPECT_EQ(v.exitCode, 0) << v.raw;
}

using test::rippleAnimation;

using GltfValidator = test::ScratchFolderTest;
TEST_F(GltfValidator, WriteGlbHasNoErrors) {
  MYO_REQUIRE_GLTF_VALIDATOR();
  const fs::path path = dir_ / "ripple.glb";
  writeGlb(path, rippleAnimation(12));
  expectValid(path);
}

TEST_F(GltfValidator, CappedAndSingleFrameGlbsHaveNoErrors) {
  MYO_REQUIRE_GLTF_VALIDATOR();
  GlbOptions capped;
  capped.maxTargets = 2;
  writeGlb(dir_ / "capped.glb", rippleAnimation(12), capped);  // two targets, twelve keys
  expectValid(dir_ / "capped.glb");
  writeGlb(dir_ / "single.glb", rippleAnimation(1));  // one morph target, one keyframe
  expectValid(dir_ / "single.glb");
}

// With TEXCOORD_0 (the grid's UVs span [0, 1]²).
TEST_F(GltfValidator, GlbWithTexcoordsHasNoErrors) {
  MYO_REQUIRE_GLTF_VALIDATOR();
  AnimationFrames a = rippleAnimation(6);
  a.uv.resize(a.rest.rows(), 2);
  for (Eigen::Index v = 0; v < a.rest.rows(); ++v) a.uv.row(v) << a.rest(v, 0) / 7.0, a.rest(v, 1) / 5.0;
  writeGlb(dir_ / "uv.glb", a);
  expectValid(dir_ / "uv.glb");
}

// A rig with UV seam duplicates (tests/support/uv_seam_mesh.h): 9 vertices for the head's 7.
TEST_F(GltfValidator, RigWithSeamDuplicatesHasNoErrors) {
  MYO_REQUIRE_GLTF_VALIDATOR();
  const TriMesh head = readObjFromString(test::kUvSeamObj, "seam.obj");
  const RigExport rig = test::seamRig(head, {"jawOpen", "mouthSmileLeft"});
  writeRigGlb(dir_ / "seam.glb", rig);
  expectValid(dir_ / "seam.glb");
}

// An animation of a head with UV seams: 9 vertices for the head's 7, every frame a key.
TEST_F(GltfValidator, AnimationWithSeamDuplicatesHasNoErrors) {
  MYO_REQUIRE_GLTF_VALIDATOR();
  const TriMesh head = readObjFromString(test::kUvSeamObj, "seam.obj");
  const RigExport rig = test::seamRig(head, {"a", "b", "c"});
  AnimationFrames a;
  a.name = "seam";
  a.fps = 30.0;
  a.rest = head.V;
  a.triangles = head.F;
  a.uv = head.UV;
  a.cornerUV = head.cornerUV;
  for (int f = 0; f < 8; ++f) a.positions.push_back(head.V + std::sin(0.5 * f) * rig.deltas[f % 3]);
  EXPECT_EQ(writeGlb(dir_ / "seam_animation.glb", a).vertices, 9);
  expectValid(dir_ / "seam_animation.glb");
}

// The validator does find errors: a GLB whose binary chunk is cut short fails (exit 1).
TEST_F(GltfValidator, ATruncatedGlbFails) {
  MYO_REQUIRE_GLTF_VALIDATOR();
  const fs::path path = dir_ / "cut.glb";
  writeGlb(path, rippleAnimation(4));
  fs::resize_file(path, fs::file_size(path) - 64);
  const Validation v = validate(path);
  ASSERT_FALSE(v.report.is_discarded()) << v.raw;
  EXPECT_GT(v.report["numErrors"].get<int>(), 0) << v.raw;
  EXPECT_EQ(v.exitCode, 1) << v.raw;
}

TEST_F(GltfValidator, CliRunGlbHasNoErrors) {
  MYO_REQUIRE_GLTF_VALIDATOR();
  write("small.json", test::kSmallScene);
  const auto r = test::runCli("run " + shellQuote((dir_ / "small.json").string()) + " --out " +
                              shellQuote((dir_ / "out").string()) + " --cache " + shellQuote((dir_ / "cache").string()) +
                              " --format glb");
  ASSERT_EQ(r.exitCode, 0) << r.merged;
  expectValid(dir_ / "out" / "small.glb");
}


// A rig of the 52 ARKit names (io/rig_export.h), with UVs, most targets zero as `myoshell rig`
// writes them for unmapped names.
TEST_F(GltfValidator, RigGlbHasNoErrors) {
  MYO_REQUIRE_GLTF_VALIDATOR();
  const AnimationFrames a = rippleAnimation(2);
  RigExport rig;
  rig.rest = a.rest;
  rig.triangles = a.triangles;
  rig.uv.resize(a.rest.rows(), 2);
  for (Eigen::Index v = 0; v < a.rest.rows(); ++v) rig.uv.row(v) << a.rest(v, 0) / 7.0, a.rest(v, 1) / 5.0;
  for (int k = 0; k < 52; ++k) {
    rig.names.push_back("shape" + std::to_string(k));
    rig.deltas.push_back(k == 7 ? MatX3(a.positions[1] - a.rest) : MatX3(MatX3::Zero(a.rest.rows(), 3)));
  }
  writeRigGlb(dir_ / "rig.glb", rig);
  expectValid(dir_ / "rig.glb");
}


// The rig `myoshell rig` makes on the built-in head from the shipped whole-face map (the default).
TEST_F(GltfValidator, CliRigGlbHasNoErrors) {
  MYO_REQUIRE_GLTF_VALIDATOR();
  const auto r = test::runCli("rig --head default --out " + shellQuote((dir_ / "rig.glb").string()));
  ASSERT_EQ(r.exitCode, 0) << r.merged;
  expectValid(dir_ / "rig.glb");
}

}  // namespace
}  // namespace myo
