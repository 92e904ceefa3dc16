#include "interrupt.h"

#include <csignal>

namespace myo::cli {
namespace {

std::atomic<bool> gInterrupted{false};
volatile std::sig_atomic_t gSignal = 0;

extern "C" void onInterrupt(int sig) {
  gSignal = sig;
  gInterrupted.store(true);
}

}  // namespace

const std::atomic<bool>& installInterruptHandlers() {
  static const bool installed = [] {
    struct sigaction sa {};
    sa.sa_handler = onInterrupt;
    sigemptyset(&sa.sa_mask);
    sa.sa_flags = SA_RESTART;  // writes to ffmpeg's pipe and files carry on; the flag is read between steps
    sigaction(SIGINT, &sa, nullptr);
    sigaction(SIGTERM, &sa, nullptr);
    return true;
  }();
  (void)installed;
  return gInterrupted;
}

int interruptSignal() { return gSignal; }

const char* interruptName() { return gSignal == SIGTERM ? "SIGTERM" : "SIGINT"; }

}  // namespace myo::cli
