#include "myoshell/core/parallel.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "myoshell/core/errors.h"

namespace myo {
namespace {

// Restores the process-wide setting, whatever a test sets.
struct ThreadsGuard {
  int saved = parallelThreads();
  ~ThreadsGuard() { setParallelThreads(saved); }
};

TEST(ParallelFor, EveryIndexRunsOnceAndTheResultsMatchTheSerialLoop) {
  ThreadsGuard guard;
  const std::int64_t count = 1000;
  auto run = [&](int threads) {
    setParallelThreads(threads);
    std::vector<double> out(static_cast<size_t>(count), 0.0);
    std::vector<std::atomic<int>> calls(static_cast<size_t>(count));
    parallelFor(count, [&](std::int64_t i) {
      double s = 0.0;
      for (int k = 1; k <= 200 + static_cast<int>(i % 7) * 50; ++k) s += std::sin(static_cast<double>(i * k));
      out[static_cast<size_t>(i)] = s;
      ++calls[static_cast<size_t>(i)];
    });
    for (auto& c : calls) EXPECT_EQ(c.load(), 1);
    return out;
  };
  const std::vector<double> serial = run(1);
  EXPECT_EQ(run(2), serial);
  EXPECT_EQ(run(4), serial);
  EXPECT_EQ(run(7), serial);
}

TEST(ParallelFor, UsesMoreThanOneThreadWhenAsked) {
  ThreadsGuard guard;
  setParallelThreads(3);
  std::vector<std::thread::id> ids(64);
  std::atomic<int> waiting{0};
  parallelFor(64, [&](std::int64_t i) {
    // The first three bodies wait for each other, so three threads must be running them at once.
    if (i < 3) {
      ++waiting;
      while (waiting.load() < 3) std::this_thread::yield();
    }
    ids[static_cast<size_t>(i)] = std::this_thread::get_id();
  });
  std::vector<std::thread::id> distinct;
  for (const auto& id : ids)
    if (std::find(distinct.begin(), distinct.end(), id) == distinct.end()) distinct.push_back(id);
  EXPECT_EQ(distinct.size(), 3u);
}

TEST(ParallelFor, RethrowsTheExceptionOfTheLowestFailingIndexForAnyThreadCount) {
  ThreadsGuard guard;
  for (int threads : {1, 2, 4}) {
    setParallelThreads(threads);
    try {
      parallelFor(100, [](std::int64_t i) {
        if (i == 17 || i == 40 || i == 90) throw std::runtime_error("body " + std::to_string(i));
      });
      ADD_FAILURE() << "no exception with " << threads << " threads";
    } catch (const std::runtime_error& e) {
      EXPECT_STREQ(e.what(), "body 17") << threads << " threads";
    }
  }
}

TEST(ParallelFor, ZeroMeansEveryHardwareThreadAndNegativeIsAnInputError) {
  ThreadsGuard guard;
  setParallelThreads(0);
  EXPECT_EQ(parallelThreads(), hardwareThreads());
  EXPECT_GE(hardwareThreads(), 1);
  try {
    setParallelThreads(-2);
    ADD_FAILURE() << "no exception";
  } catch (const InputError& e) {
    EXPECT_EQ(e.message(), "threads: expected 0 (every hardware thread) or a positive count (got -2)");
  }
  parallelFor(0, [](std::int64_t) { ADD_FAILURE() << "a body ran for count 0"; });
}

}  // namespace
}  // namespace myo
