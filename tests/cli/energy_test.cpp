// `myoshell energy`: runs the CLI on OBJ files written to a temporary folder and checks its JSON
// against the library.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>
#include <unistd.h>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "myoshell/mesh/edge_table.h"
#include "myoshell/mesh/obj_reader.h"
#include "myoshell/shell/discrete_shell.h"
#include "support/cli_runner.h"

namespace myo {
namespace {

namespace fs = std::filesystem;


class EnergyCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("myoshell_energy_test_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  fs::path write(const std::string& name, const std::string& text) {
    const fs::path p = dir_ / name;
    std::ofstream(p) << text;
    return p;
  }

  test::CliResult run(const std::string& args) { return test::runCli(args); }

  fs::path dir_;
};

// A 3×2 quad grid (quads are triangulated by the reader) and a bent, stretched copy of it.
std::string gridObj(bool deformed) {
  std::ostringstream os;
  os.precision(17);
  for (int j = 0; j <= 2; ++j)
    for (int i = 0; i <= 3; ++i) {
      double x = i, y = j, z = 0.0;
      if (deformed) {
        x *= 1.05;
        z = 0.1 * (i - 1.5) * (i - 1.5) + 0.03 * j * i;
        y += 0.02 * i;
      }
      os << "v " << x << ' ' << y << ' ' << z << '\n';
    }
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 3; ++i) {
      const int a = j * 4 + i + 1;
      os << "f " << a << ' ' << a + 1 << ' ' << a + 5 << ' ' << a + 4 << '\n';
    }
  return os.str();
}

TEST_F(EnergyCli, JsonMatchesTheLibrary) {
  const fs::path rest = write("rest.obj", gridObj(false));
  const fs::path pose = write("pose.obj", gridObj(true));
  const test::CliResult r = run("energy '" + rest.string() + "' '" + pose.string() + "' --ka 12.5 --kl 3 --kb 0.25 --json");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  std::set<std::string> keys;
  for (const auto& [key, value] : j.items()) keys.insert(key);
  EXPECT_EQ(keys, (std::set<std::string>{"E_A", "E_L", "E_B", "E", "k_A", "k_L", "k_B"}));

  const TriMesh restMesh = readObj(rest.string());
  const TriMesh poseMesh = readObjLike(pose.string(), restMesh);
  ShellMaterial mat;
  mat.kA = 12.5;
  mat.kL = 3.0;
  mat.kB = 0.25;
  const DiscreteShell shell(restMesh.V, restMesh.F, buildEdgeTable(restMesh.F, restMesh.vertexCount()), mat);
  const ShellEnergy E = shell.energy(poseMesh.V);
  ASSERT_GT(E.EA, 0.0);
  ASSERT_GT(E.EL, 0.0);
  ASSERT_GT(E.EB, 0.0);
  EXPECT_NEAR(j["E_A"].get<double>(), E.EA, 1e-12 * E.EA);
  EXPECT_NEAR(j["E_L"].get<double>(), E.EL, 1e-12 * E.EL);
  EXPECT_NEAR(j["E_B"].get<double>(), E.EB, 1e-12 * E.EB);
  EXPECT_NEAR(j["E"].get<double>(), E.total, 1e-12 * E.total);
  EXPECT_EQ(j["k_A"].get<double>(), 12.5);
  EXPECT_EQ(j["k_L"].get<double>(), 3.0);
  EXPECT_EQ(j["k_B"].get<double>(), 0.25);
}

TEST_F(EnergyCli, DefaultStiffnessesAreTheMaterialDefaults) {
  const fs::path rest = write("rest.obj", gridObj(false));
  const test::CliResult r = run("energy '" + rest.string() + "' '" + rest.string() + "' --json");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  const ShellMaterial defaults;
  EXPECT_EQ(j["k_A"].get<double>(), defaults.kA);
  EXPECT_EQ(j["k_L"].get<double>(), defaults.kL);
  EXPECT_EQ(j["k_B"].get<double>(), defaults.kB);
  EXPECT_EQ(j["E"].get<double>(), 0.0);  // a pose equal to the rest mesh
}

TEST_F(EnergyCli, TopologyMismatchExitsWithBadInput) {
  const fs::path rest = write("rest.obj", gridObj(false));
  // Same vertices, one face with another corner order.
  std::string other = gridObj(true);
  const size_t at = other.find("f 1 2 6 5");
  ASSERT_NE(at, std::string::npos);
  other.replace(at, 9, "f 1 2 7 6");
  const fs::path pose = write("pose.obj", other);
  const test::CliResult r = run("energy '" + rest.string() + "' '" + pose.string() + "' --json");
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.err.find("differs from the rest mesh"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("pose.obj"), std::string::npos) << r.err;

  // Fewer vertices.
  const fs::path small = write("small.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  const test::CliResult r2 = run("energy '" + rest.string() + "' '" + small.string() + "'");
  EXPECT_EQ(r2.exitCode, 2);
  EXPECT_NE(r2.err.find("vertices but the rest mesh"), std::string::npos) << r2.err;
}

TEST_F(EnergyCli, NegativeStiffnessIsBadInput) {
  const fs::path rest = write("rest.obj", gridObj(false));
  const test::CliResult r = run("energy '" + rest.string() + "' '" + rest.string() + "' --kb -1");
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.err.find("k_B must be ≥ 0 (got -1)"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace myo
