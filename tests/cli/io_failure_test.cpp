// A run-time I/O failure (here a file-size limit, as a full disk would be) exits 1, not 2: the
// message names the output path and the OS's reason, and no half-written file is left (only
// complete files, or none).
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fcntl.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "myoshell/mesh/obj_reader.h"
#include "support/cli_runner.h"

namespace myo {
namespace {

namespace fs = std::filesystem;

struct Child {
  int exitCode = -1;
  std::string err;
};

// Runs `myoshell run SCENE --out OUT --format FORMATS` with RLIMIT_FSIZE = `limit` bytes and SIGXFSZ
// ignored, so that a write past the limit fails with EFBIG ("File too large") instead of killing it.
Child runLimited(const std::string& scene, const fs::path& out, const std::string& formats, rlim_t limit,
                 const fs::path& errFile) {
  const pid_t pid = ::fork();
  if (pid == 0) {
    const int err = ::open(errFile.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int null = ::open("/dev/null", O_WRONLY);
    if (err < 0 || null < 0) ::_exit(100);
    ::dup2(null, STDOUT_FILENO);
    ::dup2(err, STDERR_FILENO);
    ::signal(SIGXFSZ, SIG_IGN);  // stays ignored across exec
    const rlimit rl{limit, limit};
    if (::setrlimit(RLIMIT_FSIZE, &rl) != 0) ::_exit(101);
    const std::string cli = test::cliPath(), outDir = out.string();
    ::execl(cli.c_str(), cli.c_str(), "run", scene.c_str(), "--out", outDir.c_str(), "--format", formats.c_str(),
            static_cast<char*>(nullptr));
    ::_exit(102);
  }
  int status = 0;
  ::waitpid(pid, &status, 0);
  Child c;
  c.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream in(errFile);
  std::ostringstream ss;
  ss << in.rdbuf();
  c.err = ss.str();
  return c;
}

// Every file under `dir` (relative names), hidden ones included.
std::vector<std::string> filesUnder(const fs::path& dir) {
  std::vector<std::string> files;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file()) files.push_back(fs::relative(e.path(), dir).string());
  std::sort(files.begin(), files.end());
  return files;
}

class IoFailure : public testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("myo_io_failure_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    // 31 frames of the default head: an OBJ frame is ~1.1 MB, the PC2 ~86 KB a frame (2.7 MB).
    scene_ = (dir_ / "small.json").string();
    std::ofstream(scene_) << R"({"muscles": {"use": ["zygomaticus_major_left"]}, "gravity": {"enabled": false},
      "numerics": {"skin_modes": 8}, "duration": 1.0, "fps": 30,
      "timeline": {"activations": {"zygomaticus_major_left": [{"t": 0, "value": 0}, {"t": 0.5, "value": 1}]}}})";
  }
  void TearDown() override { fs::remove_all(dir_); }

  fs::path dir_;
  std::string scene_;
};

TEST_F(IoFailure, AFileTooLargeExitsOneNamingThePathAndLeavesOnlyCompleteFiles) {
  // 2 MB: every OBJ frame fits, the PC2 does not. The frames stay, whole; no PC2, no temporary.
  const fs::path out = dir_ / "out";
  const Child c = runLimited(scene_, out, "obj,pc2", 2'000'000, dir_ / "err1.txt");
  EXPECT_EQ(c.exitCode, 1) << c.err;
  EXPECT_NE(c.err.find((out / "small.pc2").string()), std::string::npos) << c.err;
  EXPECT_NE(c.err.find("File too large"), std::string::npos) << c.err;
  const std::vector<std::string> files = filesUnder(out);
  int frames = 0, vertices = -1;
  long triangles = -1;
  for (const std::string& f : files) {
    if (f == ".myoshell-manifest.json") continue;                        // (written whole, if at all)
    ASSERT_EQ(f.rfind("obj/small_", 0), 0u) << "unexpected file " << f;  // no PC2, no .tmp, no stats.json
    const TriMesh m = readObj((out / f).string());                       // complete: it reads, all of it
    if (vertices < 0) vertices = m.vertexCount(), triangles = static_cast<long>(m.F.rows());
    EXPECT_EQ(m.vertexCount(), vertices) << f;
    EXPECT_EQ(static_cast<long>(m.F.rows()), triangles) << f;
    ++frames;
  }
  EXPECT_EQ(frames, 31);
  EXPECT_GT(vertices, 1000);
}

TEST_F(IoFailure, AFrameTooLargeForTheLimitLeavesNoFrame) {
  // 100 KB: the first OBJ frame already fails.
  const fs::path out = dir_ / "out";
  const Child c = runLimited(scene_, out, "obj", 100'000, dir_ / "err2.txt");
  EXPECT_EQ(c.exitCode, 1) << c.err;
  EXPECT_NE(c.err.find((out / "obj" / "small_0000.obj").string()), std::string::npos) << c.err;
  EXPECT_NE(c.err.find("File too large"), std::string::npos) << c.err;
  EXPECT_EQ(filesUnder(out), std::vector<std::string>{}) << "a half-written or temporary file is left";
}

}  // namespace
}  // namespace myo
