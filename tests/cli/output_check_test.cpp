// Every command checks its output paths before its work (io/output_paths.h): a folder where a file
// is needed, a file where a folder is needed, a missing or unwritable folder, a device. Each case
// would otherwise fail only at the write, after the build or the solve; here it exits 2 at once,
// naming the option, and writes nothing. The inputs named are mostly absent: the output's fault
// must be the one reported, so the check comes first.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "support/cli_runner.h"

namespace myo {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

class OutputCheck : public testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("myo_output_check_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_ / "folder");
    std::ofstream(dir_ / "file") << "x";
  }
  void TearDown() override { fs::remove_all(dir_); }

  // `myoshell ARGS` must exit 2 with `message` on stderr and leave dir_ as it was.
  void expectRefused(const std::string& args, const std::string& message) {
    const test::CliResult r = test::runCli(args);
    EXPECT_EQ(r.exitCode, 2) << args << "\n" << r.merged;
    EXPECT_THAT(r.err, HasSubstr(message)) << args;
    size_t entries = 0;
    for (auto it = fs::recursive_directory_iterator(dir_); it != fs::recursive_directory_iterator(); ++it) ++entries;
    EXPECT_EQ(entries, 2u) << args << ": wrote into " << dir_;
  }

  std::string q(const fs::path& p) const { return "'" + p.string() + "'"; }
  std::string scene() const { return q(test::sourceDir() / "tests" / "bad_inputs" / "scene_small.json"); }

  fs::path dir_;
};

TEST_F(OutputCheck, AFolderWhereAFileIsNeeded) {
  expectRefused("pose --out " + q(dir_ / "folder"), "--out: is a folder; give the OBJ file to write");
  expectRefused("fit missing.obj --out " + q(dir_ / "folder"), "--out: is a folder; give the JSON file to write");
  expectRefused("fit-rig missing.glb --out " + q(dir_ / "folder"), "--out: is a folder; give the map file (JSON) to write");
  expectRefused("rig --map missing.json --out " + q(dir_ / "folder"), "--out: is a folder; give the rig file (.glb) to write");
  expectRefused("head --render " + q(dir_ / "folder"), "--render: is a folder; give the PNG file to write");
  expectRefused("pose --out " + q(dir_ / "new" / ""), "--out: names a folder (it ends in '/')");
}

TEST_F(OutputCheck, AFileWhereAFolderIsNeeded) {
  const std::string file = q(dir_ / "file");
  expectRefused("run missing.json --out " + file, "--out: output path exists and is not a folder");
  expectRefused("render missing.json --out " + file, "--out: output path exists and is not a folder");
  expectRefused("drive missing.csv --out " + file, "--out: output path exists and is not a folder");
  expectRefused("figures --only fig26 --out " + file, "--out: output path exists and is not a folder");
  expectRefused("demo --out " + file, "--out: output path exists and is not a folder");
  expectRefused("fit-rig missing.glb --report " + file, "--report: output path exists and is not a folder");
  // A folder to be made under a file, and a file to be written under one.
  expectRefused("run " + scene() + " --out " + q(dir_ / "file" / "sub"), "--out: cannot create the output folder: '" +
                                                                             (dir_ / "file").string() + "' is not a folder");
  expectRefused("head --write-obj " + q(dir_ / "file" / "h.obj"), "--write-obj: '" + (dir_ / "file").string() + "' is not a folder");
  expectRefused("head --write-landmarks " + q(dir_ / "missing" / "l.json"), "--write-landmarks: no such folder '");
}

TEST_F(OutputCheck, ADeviceIsNoOutputFile) {
  // A write replaces the file through a rename beside it: /dev/null itself would be replaced.
  expectRefused("fit missing.obj --out /dev/null", "--out: exists and is not a regular file");
  expectRefused("pose --out /dev/null", "--out: exists and is not a regular file");
}

TEST_F(OutputCheck, AnUnwritableFolderIsRefusedBeforeTheWork) {
  // /proc/self takes no new files, not even root's (who passes any permission bits).
  if (::access("/proc/self", W_OK) == 0) GTEST_SKIP() << "/proc/self is writable here";
  // Before the check, pose settled the face (seconds) and failed at the write.
  expectRefused("pose --out /proc/self/shape.obj", "--out: cannot write into the folder '/proc/self'");
  expectRefused("fit-rig missing.glb --out /proc/self/map.json", "--out: cannot write into the folder '/proc/self'");
  expectRefused("head --render /proc/self/head.png", "--render: cannot write into the folder '/proc/self'");
  expectRefused("run " + scene() + " --out /proc/self/out", "--out: cannot create the output folder in '/proc/self'");
  expectRefused("demo --out /proc/self/demo", "--out: cannot create the output folder in '/proc/self'");
  expectRefused("render " + scene() + " --out /proc/self/out", "--out: cannot create the output folder in '/proc/self'");
  expectRefused("figures --out /proc/self/fig", "--out: cannot create the output folder in '/proc/self'");
}

}  // namespace
}  // namespace myo
