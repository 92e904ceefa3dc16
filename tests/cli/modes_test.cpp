// `myoshell modes`: runs the CLI on a strip written to a temporary folder and checks its JSON
// against the library.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>

#include "myoshell/mesh/edge_table.h"
#include "myoshell/mesh/obj_reader.h"
#include "myoshell/reduce/modal_analysis.h"
#include "myoshell/shell/discrete_shell.h"
#include "support/cli_runner.h"
#include "support/scratch_folder.h"

namespace myo {
namespace {

namespace fs = std::filesystem;


class ModesCli : public test::ScratchFolderTest {
 protected:
  void SetUp() override {
    ScratchFolderTest::SetUp();
    mesh_ = write("strip.obj", stripObj());
    pins_ = write("pins.json", "{\"vertices\": [0, 1, 9, 10, 18, 19]}");
  }

  test::CliResult run(const std::string& args) { return test::runCli(args); }

  // A curved 8×2-quad strip: 9×3 vertices, vertex (i, j) at index 9j + i.
  static std::string stripObj() {
    std::ostringstream os;
    os.precision(17);
    for (int j = 0; j <= 2; ++j)
      for (int i = 0; i <= 8; ++i) os << "v " << i << ' ' << 0.5 * j << ' ' << 0.05 * i * i << '\n';
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 8; ++i) {
        const int a = 9 * j + i + 1;
        os << "f " << a << ' ' << a + 1 << ' ' << a + 10 << ' ' << a + 9 << '\n';
      }
    return os.str();
  }

  std::string quoted(const fs::path& p) const { return "'" + p.string() + "'"; }

  fs::path mesh_, pins_;
};

TEST_F(ModesCli, JsonMatchesTheLibrary) {
  const test::CliResult r = run("modes " + quoted(mesh_) + " --pin " + quoted(pins_) + " --count 6 --kb 2.5 --json");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  for (const char* key : {"eigenvalues", "solve_seconds", "free_vertices", "modes"})
    EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_EQ(j["modes"].get<int>(), 6);
  EXPECT_EQ(j["free_vertices"].get<int>(), 27 - 6);
  EXPECT_GE(j["solve_seconds"].get<double>(), 0.0);
  const auto ev = j["eigenvalues"].get<std::vector<double>>();
  ASSERT_EQ(ev.size(), 6u);
  for (size_t k = 1; k < ev.size(); ++k) EXPECT_LE(ev[k - 1], ev[k]);

  const TriMesh mesh = readObj(mesh_.string());
  ShellMaterial mat;
  mat.kB = 2.5;
  const DiscreteShell shell(mesh.V, mesh.F, buildEdgeTable(mesh.F, mesh.vertexCount()), mat);
  ModalSettings s;
  s.modeCount = 6;
  const ModalBasis b = computeModalBasis(shell, {0, 1, 9, 10, 18, 19}, s);
  for (int k = 0; k < 6; ++k) EXPECT_NEAR(ev[k], b.lambda[k], 1e-10 * b.lambda[k]) << "mode " << k;
  EXPECT_GT(ev[0], 0.0);  // two non-collinear pinned columns: no rigid mode
}

TEST_F(ModesCli, DensityScalesEigenvaluesInversely) {
  const test::CliResult a = run("modes " + quoted(mesh_) + " --pin " + quoted(pins_) + " --count 4 --json");
  const test::CliResult b = run("modes " + quoted(mesh_) + " --pin " + quoted(pins_) + " --count 4 --density 2 --json");
  ASSERT_EQ(a.exitCode, 0) << a.err;
  ASSERT_EQ(b.exitCode, 0) << b.err;
  const auto ea = nlohmann::json::parse(a.out)["eigenvalues"].get<std::vector<double>>();
  const auto eb = nlohmann::json::parse(b.out)["eigenvalues"].get<std::vector<double>>();
  for (int k = 0; k < 4; ++k) EXPECT_NEAR(eb[k], 0.5 * ea[k], 1e-9 * ea[k]);
}

TEST_F(ModesCli, FreeShellShowsRigidModesAndTextOutputWorks) {
  const test::CliResult r = run("modes " + quoted(mesh_) + " --count 8 --solver shift-invert --json");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  const auto ev = j["eigenvalues"].get<std::vector<double>>();
  EXPECT_EQ(j["free_vertices"].get<int>(), 27);
  for (int k = 0; k < 6; ++k) EXPECT_LT(std::abs(ev[k]), 1e-8 * ev[7]) << "mode " << k;
  EXPECT_GT(ev[6], 1e-4 * ev[7]);
  const test::CliResult t = run("modes " + quoted(mesh_) + " --count 3");
  ASSERT_EQ(t.exitCode, 0) << t.err;
  EXPECT_NE(t.out.find("lambda"), std::string::npos) << t.out;
}

TEST_F(ModesCli, BadInputExitsWithCode2) {
  EXPECT_EQ(run("modes " + quoted(mesh_) + " --count 0").exitCode, 2);
  const fs::path bad = write("bad_pins.json", "[0, 99]");
  const test::CliResult r = run("modes " + quoted(mesh_) + " --pin " + quoted(bad));
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.err.find("bad_pins.json"), std::string::npos) << r.err;
  const test::CliResult s = run("modes " + quoted(mesh_) + " --solver lanczos");
  EXPECT_EQ(s.exitCode, 2);
  EXPECT_NE(s.err.find("--solver"), std::string::npos) << s.err;
  const test::CliResult m = run("modes " + quoted(dir_ / "missing.obj"));
  EXPECT_EQ(m.exitCode, 2);
  // More modes than free DOFs.
  const test::CliResult c = run("modes " + quoted(mesh_) + " --count 1000");
  EXPECT_EQ(c.exitCode, 2);
  EXPECT_NE(c.err.find("1000 modes requested"), std::string::npos) << c.err;
}

}  // namespace
}  // namespace myo
