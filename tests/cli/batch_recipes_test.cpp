// The batch recipes of examples/batch (docs/batch.md), end to end: 4 performances × 2 heads (the
// built-in head and a smaller one, the built-in head at one subdivision level written as OBJ +
// landmarks by `myoshell head`) through GNU parallel, then through a Slurm job array on a
// single-node cluster the test starts itself (when Slurm and munge are installed and the test runs
// as root; skipped otherwise, with the job list still checked).
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <thread>

#include "support/cli_runner.h"

namespace myo {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

std::string readRecipeFile(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

struct Shell {
  int exitCode;
  std::string out;
};
Shell sh(const std::string& cmd) {
  Shell r{-1, {}};
  FILE* p = ::popen((cmd + " 2>&1").c_str(), "r");
  if (!p) return r;
  char buf[4096];
  for (size_t n; (n = std::fread(buf, 1, sizeof buf, p)) > 0;) r.out.append(buf, n);
  const int status = ::pclose(p);
  r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}
bool have(const std::string& program) { return sh("command -v " + program + " > /dev/null").exitCode == 0; }

std::string q(const fs::path& p) { return "'" + p.string() + "'"; }

constexpr const char* kDriveArgs = "--library builtin --format pc2";

class BatchRecipes : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = fs::temp_directory_path() / ("myo_BatchRecipes_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_ / "perf");
    // Four short synthetic OpenFace takes (8–14 frames at 25 fps), each a different expression.
    const char* aus[] = {"AU12_r", "AU1_r", "AU26_r", "AU4_r"};
    for (int k = 0; k < 4; ++k) {
      std::ofstream out(dir_ / "perf" / ("take" + std::to_string(k) + ".csv"));
      out << "timestamp,confidence,success," << aus[k] << "\n";
      for (int f = 0; f < 8 + 2 * k; ++f) out << f * 0.04 << ",0.98,1," << 0.07 * f * (k + 1) / 4.0 << "\n";  // ≤ 0.91
    }
    const test::CliResult head = test::runCli("head default --levels 1 --write-obj " + q(dir_ / "small.obj") +
                                              " --write-landmarks " + q(dir_ / "small.json"));
    ASSERT_EQ(head.exitCode, 0) << head.merged;
    std::ofstream(dir_ / "heads.txt") << "# name head [landmarks]\ndefault default\nsmall " << (dir_ / "small.obj").string()
                                      << " " << (dir_ / "small.json").string() << "\n";
  }
  static void TearDownTestSuite() {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  static fs::path recipe(const std::string& name) { return test::sourceDir() / "examples" / "batch" / name; }
  static std::string env() { return "MYOSHELL='" + std::string(MYO_CLI_PATH) + "' "; }

  // The 8 job folders of a batch in `out`: each has its pc2, a job.json with peak_rss_mb, and the
  // same bytes as a direct `myoshell drive` of the pair (checked for two pairs, one per head).
  static void expectEightJobs(const fs::path& out, bool cacheBuiltFirst) {
    int jobs = 0, hits = 0;
    for (const std::string head : {"default", "small"})
      for (int k = 0; k < 4; ++k) {
        const fs::path d = out / head / ("take" + std::to_string(k));
        SCOPED_TRACE(d.string());
        ASSERT_TRUE(fs::exists(d / "job.json")) << readRecipeFile(d / "job.log");
        const nlohmann::json j = nlohmann::json::parse(readRecipeFile(d / "job.json"));
        EXPECT_GT(j.at("peak_rss_mb").get<double>(), 1.0);
        EXPECT_EQ(j.at("frames"), 8 + 2 * k);
        ASSERT_TRUE(fs::exists(d / ("take" + std::to_string(k) + ".pc2")));
        hits += j.at("basis_cache") == "hit";
        if (k == 0) EXPECT_EQ(j.at("basis_cache"), "computed") << "the first performance's job builds its head's cache";
        ++jobs;
      }
    EXPECT_EQ(jobs, 8);
    if (cacheBuiltFirst) EXPECT_EQ(hits, 6) << "the other jobs only read the cache";
    int entries = 0;
    for (const auto& e : fs::directory_iterator(out / "cache")) entries += e.path().extension() == ".myobasis";
    EXPECT_EQ(entries, 4) << "two bases per head (held and released)";
    for (const auto& [head, extra] : {std::pair<std::string, std::string>{"default", ""},
                                      {"small", " --landmarks " + q(dir_ / "small.json")}}) {
      const std::string headArg = head == "default" ? "default" : q(dir_ / "small.obj");
      const test::CliResult r = test::runCli("drive " + q(dir_ / "perf" / "take3.csv") + " --head " + headArg + extra +
                                             " " + kDriveArgs + " --out " + q(dir_ / ("direct_" + head)) +
                                             " --cache " + q(out / "cache"));
      ASSERT_EQ(r.exitCode, 0) << r.merged;
      EXPECT_EQ(readRecipeFile(out / head / "take3" / "take3.pc2"), readRecipeFile(dir_ / ("direct_" + head) / "take3.pc2")) << head;
    }
  }

  static fs::path dir_;
};
fs::path BatchRecipes::dir_;

TEST_F(BatchRecipes, TheJobListIsPerformanceMajorAndTheSameForBothRecipes) {
  const Shell p = sh("bash " + q(recipe("parallel.sh")) + " --dry-run " + q(dir_ / "perf") + " " + q(dir_ / "heads.txt") +
                     " " + q(dir_ / "unused"));
  ASSERT_EQ(p.exitCode, 0) << p.out;
  const Shell s = sh("bash " + q(recipe("slurm_array.sh")) + " list " + q(dir_ / "perf") + " " + q(dir_ / "heads.txt"));
  ASSERT_EQ(s.exitCode, 0) << s.out;
  EXPECT_EQ(p.out, s.out);
  std::istringstream lines(s.out);
  std::string line;
  int k = 0;
  while (std::getline(lines, line)) {
    const std::string take = (dir_ / "perf" / ("take" + std::to_string(k / 2) + ".csv")).string();
    const std::string head = k % 2 == 0 ? "default\tdefault\t"
                                        : "small\t" + (dir_ / "small.obj").string() + "\t" + (dir_ / "small.json").string();
    EXPECT_EQ(line, std::to_string(k) + "\t" + take + "\t" + head) << k;
    ++k;
  }
  EXPECT_EQ(k, 8);
  EXPECT_FALSE(fs::exists(dir_ / "unused")) << "a dry run writes nothing";

  // Bad lists: exit 2 naming the file.
  std::ofstream(dir_ / "bad_heads.txt") << "onlyaname\n";
  const Shell bad = sh("bash " + q(recipe("slurm_array.sh")) + " list " + q(dir_ / "perf") + " " + q(dir_ / "bad_heads.txt"));
  EXPECT_EQ(bad.exitCode, 2);
  EXPECT_THAT(bad.out, HasSubstr((dir_ / "bad_heads.txt").string() + ": expected 'NAME HEAD [LANDMARKS]'"));
  const Shell none = sh("bash " + q(recipe("parallel.sh")) + " --dry-run " + q(dir_ / "nothing") + " " +
                        q(dir_ / "heads.txt") + " " + q(dir_ / "unused"));
  EXPECT_EQ(none.exitCode, 2);
  EXPECT_THAT(none.out, HasSubstr((dir_ / "nothing").string() + ": not a folder of performances"));
}

TEST_F(BatchRecipes, GnuParallelDrivesFourPerformancesOnTwoHeadsBuildingTheCacheFirst) {
  if (!have("parallel")) GTEST_SKIP() << "GNU parallel is not installed (scripts/setup --test installs it)";
  const fs::path out = dir_ / "parallel_out";
  const Shell r = sh(env() + "JOBS=2 bash " + q(recipe("parallel.sh")) + " " + q(dir_ / "perf") + " " +
                     q(dir_ / "heads.txt") + " " + q(out) + " -- " + kDriveArgs);
  ASSERT_EQ(r.exitCode, 0) << r.out;
  EXPECT_THAT(r.out, HasSubstr("8 jobs done"));
  expectEightJobs(out, true);
  EXPECT_TRUE((fs::status(out / "cache").permissions() & fs::perms::owner_write) != fs::perms::none)
      << "the cache is writable again after the batch";

  // A failing job: reported, exit 1.
  fs::create_directories(dir_ / "perf_bad");
  std::ofstream(dir_ / "perf_bad" / "broken.csv") << "not,a,performance\n";
  const Shell bad = sh(env() + "bash " + q(recipe("parallel.sh")) + " " + q(dir_ / "perf_bad") + " " +
                       q(dir_ / "heads.txt") + " " + q(dir_ / "bad_out") + " -- " + kDriveArgs);
  EXPECT_EQ(bad.exitCode, 1) << bad.out;
  EXPECT_THAT(bad.out, HasSubstr("failed jobs"));
  EXPECT_THAT(readRecipeFile(dir_ / "bad_out" / "default" / "broken" / "job.log"), HasSubstr("broken.csv"));
}

// A private single-node Slurm cluster (its own munge key and socket, ports, state folder), stopped
// at the end. Only root can start slurmd this way.
class MiniSlurm {
 public:
  explicit MiniSlurm(const fs::path& dir) : dir_(dir) {
    fs::create_directories(dir_ / "state");
    fs::create_directories(dir_ / "spool");
    fs::create_directories(dir_ / "munge");
    char host[256] = {};
    ::gethostname(host, sizeof host - 1);
    std::ofstream(dir_ / "slurm.conf")
        << "ClusterName=myotest\nSlurmctldHost=" << host << "\nSlurmctldPort=16917\nSlurmdPort=16918\n"
        << "AuthType=auth/munge\nAuthInfo=socket=" << (dir_ / "munge" / "socket").string() << "\n"
        << "StateSaveLocation=" << (dir_ / "state").string() << "\nSlurmdSpoolDir=" << (dir_ / "spool").string() << "\n"
        << "SlurmctldPidFile=" << (dir_ / "ctld.pid").string() << "\nSlurmdPidFile=" << (dir_ / "d.pid").string() << "\n"
        << "SlurmctldLogFile=" << (dir_ / "ctld.log").string() << "\nSlurmdLogFile=" << (dir_ / "d.log").string() << "\n"
        << "SlurmUser=root\nProctrackType=proctrack/linuxproc\nTaskPlugin=task/none\nSchedulerType=sched/builtin\n"
        << "SelectType=select/cons_tres\nSelectTypeParameters=CR_Core\nReturnToService=2\nMpiDefault=none\n"
        << "JobAcctGatherType=jobacct_gather/none\nNodeName=" << host << " CPUs=2 State=UNKNOWN\n"
        << "PartitionName=debug Nodes=" << host << " Default=YES MaxTime=INFINITE State=UP\n";
    const std::string m = (dir_ / "munge").string();
    started_ = sh("mungekey -c -k '" + m + "/key' && munged --key-file='" + m + "/key' --socket='" + m +
                  "/socket' --pid-file='" + m + "/pid' --log-file='" + m + "/log' --seed-file='" + m + "/seed' && " +
                  env() + "slurmctld -i && " + env() + "slurmd")
                   .exitCode == 0;
    for (int i = 0; started_ && i < 200; ++i) {  // up to 20 s for the node to come up
      if (sh(env() + "sinfo -h -o %T").out.find("idle") != std::string::npos) return;
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
    started_ = false;
  }
  ~MiniSlurm() {  // stops the daemons and waits (up to 10 s each) until they are gone
    for (const char* pidFile : {"d.pid", "ctld.pid", "munge/pid"}) {
      const std::string pid = readRecipeFile(dir_ / pidFile);
      if (pid.empty()) continue;
      const pid_t p = std::stoi(pid);
      ::kill(p, SIGTERM);
      for (int i = 0; i < 1000 && ::kill(p, 0) == 0; ++i) std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
  }
  bool started() const { return started_; }
  std::string env() const { return "SLURM_CONF='" + (dir_ / "slurm.conf").string() + "' "; }
  std::string log() const { return readRecipeFile(dir_ / "ctld.log") + readRecipeFile(dir_ / "d.log"); }

 private:
  fs::path dir_;
  bool started_ = false;
};

TEST_F(BatchRecipes, ASlurmJobArrayDrivesTheSameJobs) {
  for (const char* p : {"slurmctld", "slurmd", "sbatch", "munged", "mungekey"})
    if (!have(p)) GTEST_SKIP() << p << " is not installed (Debian slurm-wlm); the job list is tested above";
  if (::geteuid() != 0) GTEST_SKIP() << "starting slurmd needs root; the job list is tested above";
  MiniSlurm slurm(dir_ / "slurm");
  ASSERT_TRUE(slurm.started()) << slurm.log();
  const fs::path out = dir_ / "slurm_out";
  const Shell r = sh(slurm.env() + env() + "bash " + q(recipe("slurm_array.sh")) + " submit " + q(dir_ / "perf") + " " +
                     q(dir_ / "heads.txt") + " " + q(out) + " -- " + kDriveArgs);
  ASSERT_EQ(r.exitCode, 0) << r.out;
  EXPECT_THAT(r.out, HasSubstr("drive array"));
  for (int i = 0; i < 1800; ++i) {  // up to 3 min for the 8 tasks
    if (sh(slurm.env() + "squeue -h").out.empty()) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  EXPECT_TRUE(sh(slurm.env() + "squeue -h").out.empty()) << "tasks still queued";
  expectEightJobs(out, true);
}

}  // namespace
}  // namespace myo
