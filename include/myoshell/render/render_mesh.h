// Z-buffered software rasterization of triangle meshes with smooth Lambert + Blinn–Phong shading.
// Several meshes can be drawn into the same image and depth buffer (skin, then muscles, …).
#pragma once

#include <limits>
#include <optional>
#include <vector>

#include "myoshell/core/types.h"
#include "myoshell/render/camera.h"
#include "myoshell/render/image.h"

namespace myo {

// Per-pixel depth of the nearest surface drawn so far: cm in front of the eye (camera.h), +∞ where
// nothing was drawn. Same size as the image it goes with.
struct DepthBuffer {
  int width = 0, height = 0;
  std::vector<double> depth;  // width·height, row-major from the top-left

  DepthBuffer() = default;
  DepthBuffer(int w, int h)
      : width(w), height(h), depth(static_cast<size_t>(w) * h, std::numeric_limits<double>::infinity()) {}
  double at(int x, int y) const { return depth[static_cast<size_t>(y) * width + x]; }
  double& at(int x, int y) { return depth[static_cast<size_t>(y) * width + x]; }
};

struct RenderStyle {
  Rgb color = Rgb(0.93, 0.78, 0.68);  // base colour of the front side (ignored with vertexColors)
  // Per-vertex colours, n×3 in [0, 1], interpolated across triangles; empty: use `color`.
  MatX3 vertexColors;
  // Colour of the back side of an open mesh (the side facing away from its normals); unset: the
  // front colour. Both sides are lit (two-sided lighting) unless cullBackFaces.
  std::optional<Rgb> backColor;
  bool cullBackFaces = false;
  bool smooth = true;         // per-vertex normals (area-weighted); false: flat per triangle
  double ambient = 0.25;      // light terms: colour·(ambient + diffuse·max(n·l, 0)) + specular
  double diffuse = 0.75;
  double specular = 0.12;     // white Blinn–Phong highlight strength, 0 for none
  double shininess = 32.0;    // Blinn–Phong exponent
  bool wireframe = false;     // overlay the triangle edges
  Rgb wireColor = Rgb(0.15, 0.12, 0.12);
  double wireWidth = 1.0;     // pixels
  // Visibility: depthTest false draws the mesh over everything already in the image ("on top",
  // e.g. muscles under the skin); depthWrite false leaves the depth buffer untouched.
  bool depthTest = true;
  bool depthWrite = true;
  // Blend factor in [0, 1]: 1 opaque; below 1 only the mesh's nearest surface is blended over the
  // image (e.g. skin at 0.4 drawn after the muscles shows them through it).
  double opacity = 1.0;
};

// Draws the mesh V (n×3, cm), F (m×3 vertex indices, counter-clockwise seen from the front side)
// seen by `camera` into `image` and `depth` (same size). The light is fixed to the camera: it
// comes from the upper left behind the viewer. Perspective-correct interpolation of colours and
// normals; triangles crossing the eye plane of a perspective camera are skipped.
void renderMesh(Image& image, DepthBuffer& depth, const Camera& camera, const MatX3& V,
                const MatX3i& F, const RenderStyle& style = {});

}  // namespace myo
