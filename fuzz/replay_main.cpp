// The seed corpus replayed without libFuzzer: each file named on the command line is passed once to
// the target's LLVMFuzzerTestOneInput, as libFuzzer does when it is given files. Linked into the
// fuzz targets in the sanitized GCC build (make fuzz-replay, CI), so the corpus runs under ASan and
// UBSan without compiling every layer again under clang; `make fuzz` still fuzzes with libFuzzer in
// build-fuzz/ (docs/RELIABILITY.md, "Fuzzing").
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <memory>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

int main(int argc, char** argv) {
  int replayed = 0;
  for (int i = 1; i < argc; ++i) {
    if (argv[i][0] == '-') continue;  // libFuzzer's options (-timeout=…, -rss_limit_mb=…): not ours
    std::ifstream in(argv[i], std::ios::binary);
    if (!in) {
      std::fprintf(stderr, "%s: cannot be read\n", argv[i]);
      return 2;
    }
    const std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    // A heap copy of exactly the input's size, as libFuzzer makes: a read past its end is an ASan report.
    const std::unique_ptr<std::uint8_t[]> copy(new std::uint8_t[bytes.size()]);
    std::copy(bytes.begin(), bytes.end(), copy.get());
    std::fprintf(stderr, "Running: %s\n", argv[i]);
    LLVMFuzzerTestOneInput(copy.get(), bytes.size());
    ++replayed;
  }
  std::fprintf(stderr, "Executed %d inputs\n", replayed);
  return 0;
}
