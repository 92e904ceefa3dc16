// Functions whose bits do not depend on the C library: the web page's WebAssembly (musl) must
// compute the face the native build (glibc) computes to the last bit, since the basis cache key
// hashes the built face (docs/web.md, "The same bits").
#pragma once

#include <cmath>

namespace myo {

// √(x² + y²) from IEEE's exactly rounded operations. std::hypot differs in the last place between
// glibc and musl (a seventh of random arguments); the arguments here are lengths in cm or face-frame
// units, far from overflow, which is all std::hypot adds.
inline double planarLength(double x, double y) { return std::sqrt(x * x + y * y); }

}  // namespace myo
