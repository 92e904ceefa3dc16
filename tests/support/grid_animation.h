// The animated grids the GLB tests write and read back (tests/io): one grid builder instead of a copy
// of the same vertex and triangle loops in each test file.
#pragma once

#include <cmath>
#include <functional>
#include <string>

#include "myoshell/io/animation_export.h"

namespace myo::test {

// An nx × ny grid of vertices, vertex (i, j) at row j·nx + i placed by `rest(i, j)`, each quad split
// into two triangles along its (i, j)–(i+1, j+1) diagonal; frame k's positions are the rest moved by
// `move(k, P)`.
inline AnimationFrames gridAnimation(const std::string& name, double fps, int nx, int ny, int frameCount,
                                     const std::function<Vec3(int i, int j)>& rest,
                                     const std::function<void(int k, MatX3& P)>& move) {
  AnimationFrames a;
  a.name = name;
  a.fps = fps;
  a.rest.resize(nx * ny, 3);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) a.rest.row(j * nx + i) = rest(i, j);
  a.triangles.resize(2 * (nx - 1) * (ny - 1), 3);
  int t = 0;
  for (int j = 0; j + 1 < ny; ++j)
    for (int i = 0; i + 1 < nx; ++i) {
      const int v = j * nx + i;
      a.triangles.row(t++) << v, v + 1, v + nx + 1;
      a.triangles.row(t++) << v, v + nx + 1, v + nx;
    }
  for (int k = 0; k < frameCount; ++k) {
    MatX3 P = a.rest;
    move(k, P);
    a.positions.push_back(P);
  }
  return a;
}

// A 6×4 grid (30 triangles) about 0.5 × 0.7 cm apart, slightly curved, bulging over `frameCount`
// frames at 30 fps (the assimp read-back's mesh).
inline AnimationFrames bulgeAnimation(int frameCount) {
  return gridAnimation(
      "bulge", 30.0, 6, 4, frameCount, [](int i, int j) { return Vec3(0.5 * i + 3, 0.7 * j - 1, 8.0 + 0.1 * i * j); },
      [](int k, MatX3& P) {
        for (int v = 0; v < P.rows(); ++v) {
          P(v, 2) += 0.3 * std::sin(0.4 * k + v);
          P(v, 0) -= 0.02 * k * (v % 3);
        }
      });
}

// An 8×6 grid (70 triangles) in z = 0, 1 cm apart, rippling over `frameCount` frames at 25 fps
// (the glTF-Validator's mesh).
inline AnimationFrames rippleAnimation(int frameCount) {
  return gridAnimation(
      "ripple", 25.0, 8, 6, frameCount, [](int i, int j) { return Vec3(double(i), double(j), 0.0); },
      [](int k, MatX3& P) {
        for (int v = 0; v < P.rows(); ++v) P(v, 2) = 0.2 * std::sin(0.5 * k + 0.8 * P(v, 0)) * std::cos(0.6 * P(v, 1));
      });
}

}  // namespace myo::test
