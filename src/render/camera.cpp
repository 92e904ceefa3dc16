#include "myoshell/render/camera.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "myoshell/core/check.h"

namespace myo {
namespace {
double radians(double degrees) { return degrees * std::numbers::pi / 180.0; }
}  // namespace

Vec3 Camera::forward() const {
  const Vec3 f = target - eye;
  MYO_CHECK(f.norm() > 0, "camera eye and target coincide");
  return f.normalized();
}

Vec3 Camera::right() const {
  const Vec3 r = forward().cross(up);
  MYO_CHECK(r.norm() > 1e-12, "camera up is parallel to the viewing direction");
  return r.normalized();
}

Vec3 Camera::trueUp() const { return right().cross(forward()); }

ScreenPoint project(const Camera& camera, const Vec3& p, int width, int height) {
  const Vec3 f = camera.forward(), r = camera.right(), u = r.cross(f);
  const Vec3 d = p - camera.eye;
  const double vx = r.dot(d), vy = u.dot(d), vz = f.dot(d);
  ScreenPoint s;
  s.depth = vz;
  double px, py;
  if (camera.perspective) {
    const double focal = 0.5 * height / std::tan(0.5 * radians(camera.fovYDegrees));
    const double z = vz > 1e-12 ? vz : 1e-12;
    px = focal * vx / z;
    py = focal * vy / z;
  } else {
    const double k = height / camera.orthoHeight;
    px = k * vx;  // the target lies on the axis: r·(target − eye) = 0
    py = k * vy;
  }
  s.x = 0.5 * width + px;
  s.y = 0.5 * height - py;
  return s;
}

Camera orbitCamera(const ViewFrame& frame, double yawDegrees, double pitchDegrees) {
  const double yaw = radians(yawDegrees), pitch = radians(pitchDegrees);
  const Vec3 x = frame.axes.col(0), y = frame.axes.col(1), z = frame.axes.col(2);
  // Turning toward the subject's right (−x) for positive yaw; up for positive pitch.
  const Vec3 horizontal = std::cos(yaw) * z - std::sin(yaw) * x;
  const Vec3 dir = std::cos(pitch) * horizontal + std::sin(pitch) * y;
  Camera c;
  c.target = frame.origin;
  c.eye = frame.origin + 10.0 * frame.scale * dir;
  c.up = std::abs(dir.dot(y)) > 0.999 ? Vec3(-horizontal) : Vec3(y);
  c.perspective = false;
  c.orthoHeight = 3.0 * frame.scale;
  return c;
}

Camera presetCamera(const ViewFrame& frame, ViewPreset preset) {
  switch (preset) {
    case ViewPreset::front: return orbitCamera(frame, 0);
    case ViewPreset::threeQuarter: return orbitCamera(frame, 35);
    case ViewPreset::profile: return orbitCamera(frame, 90);
    case ViewPreset::back: return orbitCamera(frame, 180);
  }
  return orbitCamera(frame, 0);
}

void fitToBounds(Camera& camera, const MatX3& V, int width, int height, double margin) {
  MYO_CHECK(V.rows() >= 1, "fitToBounds needs at least one point");
  MYO_CHECK(width > 0 && height > 0, "image size " << width << "×" << height);
  margin = std::clamp(margin, 0.0, 0.45);
  const Vec3 f = camera.forward(), r = camera.right(), u = r.cross(f);
  const double aspect = static_cast<double>(width) / height;
  const double fill = 1.0 - 2.0 * margin;
  if (!camera.perspective) {
    double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300, z0 = 1e300, z1 = -1e300;
    for (Eigen::Index i = 0; i < V.rows(); ++i) {
      const Vec3 p = V.row(i).transpose();
      x0 = std::min(x0, r.dot(p)), x1 = std::max(x1, r.dot(p));
      y0 = std::min(y0, u.dot(p)), y1 = std::max(y1, u.dot(p));
      z0 = std::min(z0, f.dot(p)), z1 = std::max(z1, f.dot(p));
    }
    const double w = std::max(x1 - x0, 1e-9), h = std::max(y1 - y0, 1e-9);
    camera.orthoHeight = std::max(h, w / aspect) / fill;
    const double zc = 0.5 * (z0 + z1);
    camera.target = 0.5 * (x0 + x1) * r + 0.5 * (y0 + y1) * u + zc * f;
    // Back off so the eye is in front of every point.
    const double back = 0.5 * (z1 - z0) + std::max({w, h, z1 - z0});
    camera.eye = camera.target - back * f;
    camera.up = u;
    return;
  }
  const Vec3 lo = V.colwise().minCoeff(), hi = V.colwise().maxCoeff();
  const Vec3 c = 0.5 * (lo + hi);
  double radius = 0;
  for (Eigen::Index i = 0; i < V.rows(); ++i) radius = std::max(radius, (Vec3(V.row(i)) - c).norm());
  radius = std::max(radius, 1e-9);
  const double halfY = 0.5 * radians(camera.fovYDegrees);
  const double halfX = std::atan(std::tan(halfY) * aspect);
  const double half = std::atan(std::tan(std::min(halfX, halfY)) * fill);
  camera.target = c;
  camera.eye = c - (radius / std::sin(half)) * f;
  camera.up = u;
}

}  // namespace myo
