#include "myoshell/render/render_mesh.h"

#include <algorithm>
#include <cmath>

#include "myoshell/core/check.h"
#include "myoshell/mesh/geometry.h"

namespace myo {
namespace {

// One covered pixel of a triangle: pixel, depth (cm) and perspective-correct barycentrics b; the
// screen-space barycentrics w serve the wireframe (pixel distances to the edges).
struct Fragment {
  int x, y;
  double depth;
  double b[3];
  double edgeDistance;  // pixels to the nearest triangle edge
};

// Calls fn(fragment) for every pixel centre inside the screen triangle s0 s1 s2 (inclusive edges).
template <class Fn>
void rasterize(const ScreenPoint& s0, const ScreenPoint& s1, const ScreenPoint& s2, bool perspective,
               int width, int height, Fn&& fn) {
  const double area = (s1.x - s0.x) * (s2.y - s0.y) - (s2.x - s0.x) * (s1.y - s0.y);
  if (std::abs(area) < 1e-12) return;
  const int x0 = std::max(0, static_cast<int>(std::floor(std::min({s0.x, s1.x, s2.x}))));
  const int x1 = std::min(width - 1, static_cast<int>(std::ceil(std::max({s0.x, s1.x, s2.x}))));
  const int y0 = std::max(0, static_cast<int>(std::floor(std::min({s0.y, s1.y, s2.y}))));
  const int y1 = std::min(height - 1, static_cast<int>(std::ceil(std::max({s0.y, s1.y, s2.y}))));
  const double len0 = std::hypot(s2.x - s1.x, s2.y - s1.y), len1 = std::hypot(s0.x - s2.x, s0.y - s2.y),
               len2 = std::hypot(s1.x - s0.x, s1.y - s0.y);
  const double a = std::abs(area);
  for (int y = y0; y <= y1; ++y)
    for (int x = x0; x <= x1; ++x) {
      const double qx = x + 0.5, qy = y + 0.5;
      const double w0 = ((s1.x - qx) * (s2.y - qy) - (s2.x - qx) * (s1.y - qy)) / area;
      const double w1 = ((s2.x - qx) * (s0.y - qy) - (s0.x - qx) * (s2.y - qy)) / area;
      const double w2 = 1.0 - w0 - w1;
      if (w0 < 0 || w1 < 0 || w2 < 0) continue;
      Fragment f;
      f.x = x;
      f.y = y;
      if (perspective) {  // 1/depth is affine in screen space
        const double i0 = w0 / s0.depth, i1 = w1 / s1.depth, i2 = w2 / s2.depth;
        const double inv = i0 + i1 + i2;
        f.depth = 1.0 / inv;
        f.b[0] = i0 / inv, f.b[1] = i1 / inv, f.b[2] = i2 / inv;
      } else {
        f.depth = w0 * s0.depth + w1 * s1.depth + w2 * s2.depth;
        f.b[0] = w0, f.b[1] = w1, f.b[2] = w2;
      }
      f.edgeDistance = std::min({w0 * a / len0, w1 * a / len1, w2 * a / len2});
      fn(f);
    }
}

}  // namespace

void renderMesh(Image& image, DepthBuffer& depth, const Camera& camera, const MatX3& V,
                const MatX3i& F, const RenderStyle& style) {
  MYO_CHECK(depth.width == image.width && depth.height == image.height,
            "depth buffer " << depth.width << "×" << depth.height << " vs image " << image.width
                            << "×" << image.height);
  const bool perVertexColor = style.vertexColors.rows() > 0;
  if (perVertexColor) MYO_CHECK_EQ(style.vertexColors.rows(), V.rows());
  if (F.rows() > 0) MYO_CHECK(F.minCoeff() >= 0 && F.maxCoeff() < V.rows(), "face index out of range");
  const int W = image.width, H = image.height;
  if (W == 0 || H == 0 || F.rows() == 0) return;

  std::vector<ScreenPoint> S(V.rows());
  for (Eigen::Index i = 0; i < V.rows(); ++i) S[i] = project(camera, V.row(i).transpose(), W, H);
  const MatX3 N = style.smooth ? vertexNormals(V, F) : MatX3();
  const Vec3 f = camera.forward(), r = camera.right(), u = r.cross(f);
  const Vec3 light = (-0.35 * r + 0.45 * u - 1.0 * f).normalized();  // towards the light
  const double kNear = 1e-6;  // cm: perspective triangles must lie in front of the eye

  // Which triangles are drawn, and whether their front side faces the camera.
  std::vector<signed char> facing(F.rows(), 0);  // +1 front, −1 back, 0 skipped
  for (Eigen::Index t = 0; t < F.rows(); ++t) {
    const Vec3 a = V.row(F(t, 0)), b = V.row(F(t, 1)), c = V.row(F(t, 2));
    if (camera.perspective &&
        std::min({S[F(t, 0)].depth, S[F(t, 1)].depth, S[F(t, 2)].depth}) <= kNear)
      continue;
    const Vec3 n = (b - a).cross(c - a);
    const Vec3 toCamera = camera.perspective ? Vec3(camera.eye - a) : Vec3(-f);
    const double s = n.dot(toCamera);
    if (s > 0) facing[t] = 1;
    else if (!style.cullBackFaces) facing[t] = -1;
  }

  // Pass 1: which triangle holds this mesh's nearest surface at each pixel (in front of what is
  // already drawn if depthTest). Pass 2: shade each pixel once, with that triangle. This gives
  // self-occlusion even when depthTest is off, and blends only the nearest layer of a translucent
  // mesh.
  const size_t P = static_cast<size_t>(W) * H;
  std::vector<double> nearest(P, std::numeric_limits<double>::infinity());
  std::vector<Eigen::Index> owner(P, -1);
  for (Eigen::Index t = 0; t < F.rows(); ++t) {
    if (!facing[t]) continue;
    rasterize(S[F(t, 0)], S[F(t, 1)], S[F(t, 2)], camera.perspective, W, H, [&](const Fragment& q) {
      if (style.depthTest && q.depth >= depth.at(q.x, q.y)) return;
      const size_t idx = static_cast<size_t>(q.y) * W + q.x;
      if (q.depth < nearest[idx]) nearest[idx] = q.depth, owner[idx] = t;
    });
  }
  const double alpha = std::clamp(style.opacity, 0.0, 1.0);
  for (Eigen::Index t = 0; t < F.rows(); ++t) {
    if (!facing[t]) continue;
    const int i0 = F(t, 0), i1 = F(t, 1), i2 = F(t, 2);
    const Vec3 a = V.row(i0), b = V.row(i1), c = V.row(i2);
    const Vec3 flatNormal = (b - a).cross(c - a).normalized();
    const bool front = facing[t] > 0;
    rasterize(S[i0], S[i1], S[i2], camera.perspective, W, H, [&](const Fragment& q) {
      const size_t idx = static_cast<size_t>(q.y) * W + q.x;
      if (owner[idx] != t) return;
      owner[idx] = -1;  // shade once, even where the triangle's own pixels repeat
      Vec3 n = style.smooth ? Vec3(q.b[0] * N.row(i0) + q.b[1] * N.row(i1) + q.b[2] * N.row(i2))
                            : flatNormal;
      if (n.norm() > 0) n.normalize();
      if (!front) n = -n;  // we see the back side: light it as a surface of its own
      Rgb base = perVertexColor ? Rgb(q.b[0] * style.vertexColors.row(i0) +
                                      q.b[1] * style.vertexColors.row(i1) +
                                      q.b[2] * style.vertexColors.row(i2))
                                : style.color;
      if (!front && style.backColor) base = *style.backColor;
      const Vec3 p = q.b[0] * a + q.b[1] * b + q.b[2] * c;
      const Vec3 toCamera = camera.perspective ? Vec3((camera.eye - p).normalized()) : Vec3(-f);
      const double lambert = std::max(0.0, n.dot(light));
      double spec = 0;
      if (style.specular > 0 && lambert > 0)
        spec = style.specular * std::pow(std::max(0.0, n.dot((light + toCamera).normalized())),
                                         style.shininess);
      Rgb col = base * (style.ambient + style.diffuse * lambert) + Rgb::Constant(spec);
      if (style.wireframe && q.edgeDistance < 0.5 * style.wireWidth) col = style.wireColor;
      if (alpha < 1.0) image.blend(q.x, q.y, col, alpha);
      else image.set(q.x, q.y, col);
      if (style.depthWrite) depth.at(q.x, q.y) = std::min(depth.at(q.x, q.y), q.depth);
    });
  }
}

}  // namespace myo
