#include "myoshell/core/parallel.h"

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "myoshell/core/errors.h"

namespace myo {
namespace {

std::atomic<int> threadSetting{1};

}  // namespace

int hardwareThreads() { return std::max(1u, std::thread::hardware_concurrency()); }

void setParallelThreads(int threads) {
  if (threads < 0) throw InputError("threads: expected 0 (every hardware thread) or a positive count (got " + std::to_string(threads) + ")");
  threadSetting = threads == 0 ? hardwareThreads() : threads;
}

int parallelThreads() { return threadSetting; }

void parallelFor(std::int64_t count, const std::function<void(std::int64_t)>& body) {
  if (count <= 0) return;
  const auto threads = static_cast<std::int64_t>(std::min<std::int64_t>(parallelThreads(), count));
  if (threads <= 1) {
    for (std::int64_t i = 0; i < count; ++i) body(i);
    return;
  }
  // Dynamic hand-out (bodies differ in cost: muscles of different sizes, shapes of different fits).
  std::atomic<std::int64_t> next{0};
  std::atomic<bool> failed{false};
  std::exception_ptr error;
  std::int64_t errorIndex = count;
  std::mutex errorMutex;
  auto work = [&] {
    for (std::int64_t i; !failed && (i = next++) < count;) {
      try {
        body(i);
      } catch (...) {
        // The lowest failing index wins: every lower index was handed out before it and runs to the
        // end, so this is the exception a serial loop would have thrown, for any thread count.
        const std::lock_guard<std::mutex> lock(errorMutex);
        if (i < errorIndex) {
          error = std::current_exception();
          errorIndex = i;
        }
        failed = true;
      }
    }
  };
  std::vector<std::thread> helpers;
  helpers.reserve(static_cast<size_t>(threads - 1));
  for (std::int64_t t = 1; t < threads; ++t) helpers.emplace_back(work);
  work();
  for (std::thread& h : helpers) h.join();
  if (error) std::rethrow_exception(error);
}

}  // namespace myo
