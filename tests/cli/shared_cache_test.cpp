// Many `myoshell` processes starting cold at once on one basis cache folder (issue 20): eight drives
// of one performance on a small head (the built-in head at one subdivision level, ~2 s cold), some killed (SIGKILL, as a crash or a scheduler's
// pre-emption) at random moments and restarted. Every finished run writes the reference run's bytes;
// the folder holds only valid entries (no temporary left, every entry passing the format's length and
// checksum checks); and among the finished runs each basis was computed at most once (their --json
// basis_cache_computed lists do not overlap), the others having waited for it or read it.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <random>
#include <set>
#include <sstream>
#include <thread>

#include "myoshell/io/basis_cache_file.h"
#include "support/cli_runner.h"

namespace myo {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

std::string readCacheFile(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// A short synthetic OpenFace take: 12 frames at 25 fps, a smile and the jaw.
void writeTake(const fs::path& p) {
  std::ofstream out(p);
  out << "timestamp,confidence,success,AU12_r,AU25_r,AU26_r\n";
  for (int f = 0; f < 12; ++f)
    out << f * 0.04 << ",0.98,1," << 0.08 * f << "," << 0.05 * f << "," << 0.04 * f << "\n";
}

std::string driveArgs(const fs::path& dir, const fs::path& out, const fs::path& cache) {
  return "drive '" + (dir / "take.csv").string() + "' --head '" + (dir / "small.obj").string() + "' --landmarks '" +
         (dir / "small.json").string() + "' --library builtin --format pc2 --json --out '" + out.string() +
         "' --cache '" + cache.string() + "'";
}

// `myoshell ARGS > json 2> err` in the background.
pid_t spawnCli(const std::string& args, const fs::path& json, const fs::path& err) {
  const std::string cmd = "exec '" + std::string(MYO_CLI_PATH) + "' " + args + " > '" + json.string() + "' 2> '" +
                          err.string() + "'";
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::execl("/bin/sh", "sh", "-c", cmd.c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  return pid;
}

BasisKey keyFromHex(const std::string& hex) {
  BasisKey k;
  k.words[0] = std::stoull(hex.substr(0, 16), nullptr, 16);
  k.words[1] = std::stoull(hex.substr(16, 16), nullptr, 16);
  return k;
}

class SharedCache : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("myo_SharedCache_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

TEST_F(SharedCache, EightColdProcessesKilledAndRestartedAtRandomComputeEachBasisOnce) {
  writeTake(dir_ / "take.csv");
  const test::CliResult head = test::runCli("head default --levels 1 --write-obj '" + (dir_ / "small.obj").string() +
                                            "' --write-landmarks '" + (dir_ / "small.json").string() + "'");
  ASSERT_EQ(head.exitCode, 0) << head.merged;

  // The reference: one run alone on its own cold cache.
  const auto t0 = Clock::now();
  const test::CliResult ref = test::runCli(driveArgs(dir_, dir_ / "ref", dir_ / "ref_cache"));
  const double coldSeconds = std::chrono::duration<double>(Clock::now() - t0).count();
  ASSERT_EQ(ref.exitCode, 0) << ref.merged;
  const nlohmann::json refJson = nlohmann::json::parse(ref.out);
  EXPECT_EQ(refJson.at("basis_cache"), "computed");
  const std::vector<std::string> refKeys = refJson.at("basis_cache_computed");
  ASSERT_FALSE(refKeys.empty());
  fs::path refPc2;
  for (const auto& e : fs::directory_iterator(dir_ / "ref"))
    if (e.path().extension() == ".pc2") refPc2 = e.path();
  ASSERT_FALSE(refPc2.empty());
  const std::string refBytes = readCacheFile(refPc2);
  ASSERT_GT(refBytes.size(), 100u);

  // Eight at once on one cold cache; four of them killed at random moments within the cold start's
  // span and restarted at once (a restart may be killed again, up to five kills a round). Three
  // rounds, each on a fresh cache.
  const unsigned seed = std::random_device{}();
  std::mt19937 rng(seed);
  constexpr int kJobs = 8;
  int kills = 0;
  for (int round = 0; round < 3; ++round) {
    SCOPED_TRACE("round " + std::to_string(round) + ", seed " + std::to_string(seed) + ", cold start " +
                 std::to_string(coldSeconds) + " s");
    const fs::path cache = dir_ / ("cache" + std::to_string(round));
    const int killsBefore = kills;
    struct Job {
      pid_t pid = -1;
      int attempt = 0;
      Clock::time_point killAt = Clock::time_point::max();
      bool done = false;
      int status = 0;
    };
    std::vector<Job> jobs(kJobs);
    const auto jsonOf = [&](int i) { return dir_ / ("job" + std::to_string(i) + ".json"); };
    const auto errOf = [&](int i) { return dir_ / ("job" + std::to_string(i) + ".err"); };
    const auto start = [&](int i) {
      jobs[i].pid = spawnCli(driveArgs(dir_, dir_ / ("out" + std::to_string(i)), cache), jsonOf(i), errOf(i));
      ASSERT_GT(jobs[i].pid, 0);
    };
    std::uniform_real_distribution<double> moment(0.05, 1.0);
    const auto scheduleKill = [&](int i) {
      jobs[i].killAt = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                          std::chrono::duration<double>(moment(rng) * coldSeconds));
    };
    for (int i = 0; i < kJobs; ++i) start(i);
    std::vector<int> victims = {0, 1, 2, 3, 4, 5, 6, 7};
    std::shuffle(victims.begin(), victims.end(), rng);
    for (int v = 0; v < 4; ++v) scheduleKill(victims[v]);
    const auto deadline = Clock::now() + std::chrono::seconds(static_cast<int>(60 + 20 * coldSeconds));
    for (;;) {
      bool allDone = true;
      for (int i = 0; i < kJobs; ++i) {
        Job& j = jobs[i];
        if (j.done) continue;
        int status = 0;
        if (::waitpid(j.pid, &status, WNOHANG) == j.pid) {
          const bool killed = WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL;
          if (killed) {
            ++j.attempt;
            j.killAt = Clock::time_point::max();
            if (kills - killsBefore < 5 && j.attempt == 1 && std::bernoulli_distribution(0.3)(rng)) scheduleKill(i);
            start(i);
          } else {
            j.done = true;
            j.status = status;
            continue;
          }
        } else if (Clock::now() >= j.killAt) {
          ::kill(j.pid, SIGKILL);
          ++kills;
          j.killAt = Clock::time_point::max();
        }
        allDone = false;
      }
      if (allDone) break;
      if (Clock::now() > deadline) {
        for (Job& j : jobs)
          if (!j.done) ::kill(j.pid, SIGKILL), ::waitpid(j.pid, nullptr, 0);
        FAIL() << "the jobs did not finish in time (a lock never released?)";
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    EXPECT_GE(kills - killsBefore, 1);

    // Every run finished and wrote the reference's bytes.
    std::map<std::string, int> computedBy;  // key → how many finished runs computed it
    std::map<std::string, int> statuses;
    for (int i = 0; i < kJobs; ++i) {
      ASSERT_TRUE(WIFEXITED(jobs[i].status) && WEXITSTATUS(jobs[i].status) == 0)
          << "job " << i << ": " << readCacheFile(errOf(i));
      const nlohmann::json j = nlohmann::json::parse(readCacheFile(jsonOf(i)));
      EXPECT_EQ(readCacheFile(dir_ / ("out" + std::to_string(i)) / refPc2.filename()), refBytes) << "job " << i;
      fs::remove_all(dir_ / ("out" + std::to_string(i)));  // the next round starts with no output either
      statuses[j.at("basis_cache").get<std::string>()]++;
      for (const std::string& k : j.at("basis_cache_computed")) computedBy[k]++;
      EXPECT_GT(j.at("peak_rss_mb").get<double>(), 1.0);
      EXPECT_EQ(j.at("basis_cache_counts").at("rejected"), 0) << "no half-written entry was met: " << readCacheFile(errOf(i));
    }
    for (const auto& [key, n] : computedBy) EXPECT_EQ(n, 1) << "basis " << key << " computed by " << n << " runs";
    for (const auto& [key, n] : computedBy)
      EXPECT_THAT(refKeys, ::testing::Contains(key)) << "the finished runs computed only what the reference did";
    EXPECT_EQ(statuses["computed"] + statuses["waited"] + statuses["hit"], kJobs);

    // The folder: the reference's entries, each valid; lock files; nothing else (no temporary).
    std::set<std::string> entries;
    for (const auto& e : fs::directory_iterator(cache)) {
      const std::string name = e.path().filename().string();
      if (e.path().extension() == ".lock") continue;
      ASSERT_EQ(e.path().extension(), ".myobasis") << "unexpected file " << name;
      const std::string hex = e.path().stem().string();
      std::string why;
      EXPECT_TRUE(readBasisFile(e.path(), keyFromHex(hex), &why).has_value()) << name << ": " << why;
      EXPECT_EQ(readCacheFile(e.path()), readCacheFile(dir_ / "ref_cache" / name)) << name;
      entries.insert(hex);
    }
    EXPECT_EQ(entries, std::set<std::string>(refKeys.begin(), refKeys.end()));
  }
}

// A cache folder the command cannot write (a batch's shared cache, built beforehand): read without
// locks, never written; a basis missing from it is computed, with one warning that it is not kept.
// Read-only through a read-only bind mount in a private mount namespace when root (whom permission
// bits do not stop), through permission bits otherwise.
TEST_F(SharedCache, AReadOnlyCacheFolderIsReadWithoutLocksAndNeverWritten) {
  writeTake(dir_ / "take.csv");
  const test::CliResult head = test::runCli("head default --levels 1 --write-obj '" + (dir_ / "small.obj").string() +
                                            "' --write-landmarks '" + (dir_ / "small.json").string() + "'");
  ASSERT_EQ(head.exitCode, 0) << head.merged;
  const fs::path cache = dir_ / "cache";
  const test::CliResult warm = test::runCli(driveArgs(dir_, dir_ / "warm", cache));
  ASSERT_EQ(warm.exitCode, 0) << warm.merged;
  for (const auto& e : fs::directory_iterator(cache))
    if (e.path().extension() == ".lock") fs::remove(e.path());
  const auto listing = [&] {
    std::set<std::string> names;
    for (const auto& e : fs::directory_iterator(cache)) names.insert(e.path().filename().string());
    return names;
  };
  const std::set<std::string> before = listing();
  ASSERT_EQ(before.size(), 2u);

  std::string prefix;
  if (::geteuid() == 0) {
    if (std::system("unshare -m true 2> /dev/null") != 0)
      GTEST_SKIP() << "root without mount namespaces: no way to make the folder read-only";
    const std::string c = "'" + cache.string() + "'";
    prefix = "unshare -m sh -c 'mount --bind \"$0\" \"$0\" && mount -o remount,bind,ro \"$0\" && exec \"$@\"' " + c;
  } else {
    fs::permissions(cache, fs::perms::owner_write | fs::perms::group_write | fs::perms::others_write,
                    fs::perm_options::remove);
  }
  const test::CliResult hit = test::runCli(driveArgs(dir_, dir_ / "hit", cache), {}, prefix);
  ASSERT_EQ(hit.exitCode, 0) << hit.merged;
  nlohmann::json j = nlohmann::json::parse(hit.out);
  EXPECT_EQ(j.at("basis_cache"), "hit");
  EXPECT_EQ(j.at("basis_cache_counts").at("read_only"), true);
  EXPECT_EQ(hit.err.find("warning"), std::string::npos) << hit.err;
  EXPECT_EQ(readCacheFile(dir_ / "hit" / "take.pc2"), readCacheFile(dir_ / "warm" / "take.pc2"));

  // The whole face's muscles: other bases, computed and not kept.
  std::string args = driveArgs(dir_, dir_ / "miss", cache);
  args.replace(args.find("--library builtin"), 17, "--library face");
  const test::CliResult miss = test::runCli(args, {}, prefix);
  ASSERT_EQ(miss.exitCode, 0) << miss.merged;
  j = nlohmann::json::parse(miss.out);
  EXPECT_EQ(j.at("basis_cache"), "computed");
  EXPECT_THAT(miss.err, ::testing::HasSubstr("warning: the basis cache keeps nothing: the basis cache folder " +
                                             cache.string() + " is read-only"));
  EXPECT_EQ(miss.err.find("warning"), miss.err.rfind("warning")) << "one warning: " << miss.err;
  EXPECT_EQ(listing(), before) << "no entry, lock or temporary file added";
  fs::permissions(cache, fs::perms::owner_all, fs::perm_options::add);
}

}  // namespace
}  // namespace myo
