// PC2 point caches (layout in animation_export.h).
#include <bit>
#include <cstdint>
#include <cstring>
#include <string>

#include "export_file.h"
#include "myoshell/core/atomic_file.h"
#include "myoshell/core/errors.h"
#include "myoshell/core/whole_file.h"
#include "myoshell/io/animation_export.h"

namespace myo {
namespace {

static_assert(std::endian::native == std::endian::little, "PC2 I/O assumes a little-endian host");

constexpr char kSignature[12] = {'P', 'O', 'I', 'N', 'T', 'C', 'A', 'C', 'H', 'E', '2', '\0'};
constexpr int32_t kVersion = 1;
constexpr size_t kHeaderBytes = 32;

template <class T>
void put(std::string& out, const T& v) {
  out.append(reinterpret_cast<const char*>(&v), sizeof(T));
}

template <class T>
T get(const std::string& in, size_t offset) {
  T v;
  std::memcpy(&v, in.data() + offset, sizeof(T));
  return v;
}

}  // namespace

void writePc2(const std::filesystem::path& path, const AnimationFrames& frames) {
  detail::checkFrames(frames);
  const auto n = static_cast<int32_t>(frames.rest.rows());
  const auto samples = static_cast<int32_t>(frames.positions.size());
  std::string out;
  out.reserve(kHeaderBytes + sizeof(float) * 3 * size_t(n) * size_t(samples));
  out.append(kSignature, sizeof kSignature);
  put(out, kVersion);
  put(out, n);
  put(out, 0.0f);  // startFrame
  put(out, 1.0f);  // sampleRate: one sample per frame
  put(out, samples);
  for (const MatX3& P : frames.positions)
    for (int32_t i = 0; i < n; ++i)
      for (int c = 0; c < 3; ++c) put(out, static_cast<float>(P(i, c)));
  writeFileAtomically(path.string(), out);
}

PointCache readPc2(const std::filesystem::path& path) {
  const std::string in = readWholeFile(path.string(), "cannot open point cache");
  if (in.size() < kHeaderBytes || std::memcmp(in.data(), kSignature, sizeof kSignature) != 0)
    throw InputError("not a PC2 point cache (no POINTCACHE2 signature)", path.string());
  if (const auto version = get<int32_t>(in, 12); version != kVersion)
    throw InputError("unsupported PC2 version " + std::to_string(version), path.string());
  PointCache pc;
  pc.numPoints = get<int32_t>(in, 16);
  pc.startFrame = get<float>(in, 20);
  pc.sampleRate = get<float>(in, 24);
  const int32_t samples = get<int32_t>(in, 28);
  if (pc.numPoints < 0 || samples < 0)
    throw InputError("PC2 header has a negative point or sample count", path.string());
  const size_t expected = kHeaderBytes + sizeof(float) * 3 * size_t(pc.numPoints) * size_t(samples);
  if (in.size() != expected)
    throw InputError("PC2 file is " + std::to_string(in.size()) + " bytes, its header says " +
                         std::to_string(expected),
                     path.string());
  size_t at = kHeaderBytes;
  pc.samples.resize(samples);
  for (MatX3& P : pc.samples) {
    P.resize(pc.numPoints, 3);
    for (int i = 0; i < pc.numPoints; ++i)
      for (int c = 0; c < 3; ++c, at += sizeof(float)) P(i, c) = get<float>(in, at);
  }
  return pc;
}

}  // namespace myo
