// Shared by the libFuzzer targets: a finding is anything but the documented error of bad input.
// myo::InputError (and, where a reader can raise it, NumericalError) is the expected outcome of a
// malformed file; a CheckError, any other exception, a crash, undefined behaviour, a timeout or
// running out of memory is a bug. A broken property (FUZZ_EXPECT) aborts with its text, which
// libFuzzer reports as a crash and saves as a finding.
#pragma once

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#define FUZZ_EXPECT(cond, what)                                                        \
  do {                                                                                 \
    if (!(cond)) {                                                                     \
      std::fprintf(stderr, "FUZZ property failed: %s (%s) at %s:%d\n", #cond, what,     \
                   __FILE__, __LINE__);                                                \
      std::abort();                                                                    \
    }                                                                                  \
  } while (0)

namespace myo::fuzz {

inline std::string text(const std::uint8_t* data, std::size_t size) {
  return std::string(reinterpret_cast<const char*>(data), size);
}

}  // namespace myo::fuzz
