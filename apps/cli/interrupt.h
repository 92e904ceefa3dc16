// Ctrl-C and `kill`: SIGINT and SIGTERM only set a flag (the handler does nothing else, so it is
// async-signal-safe); a ScenePlayer watching it stops at its next step and the command cleans up
// (temporary files, the ffmpeg child) and exits 128 + the signal (130, 143).
#pragma once

#include <atomic>

namespace myo::cli {

// Installs the handlers (once; later calls do nothing) and returns the flag they set.
const std::atomic<bool>& installInterruptHandlers();
// The signal that set the flag (SIGINT, SIGTERM), 0 when none has come.
int interruptSignal();
// "SIGINT" or "SIGTERM".
const char* interruptName();

}  // namespace myo::cli
