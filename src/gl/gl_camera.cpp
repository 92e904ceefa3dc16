// glCameraMatrices: camera.h's project() as an OpenGL view and projection.
#include <cmath>
#include <numbers>

#include "myoshell/gl/gl_renderer.h"

namespace myo {

GlCameraMatrices glCameraMatrices(const Camera& camera, int width, int height) {
  const Vec3 f = camera.forward(), r = camera.right(), u = r.cross(f);
  // View: eye coordinates (r, u, −f), so the view depth of camera.h is −z_eye.
  Eigen::Matrix4d view = Eigen::Matrix4d::Identity();
  view.block<1, 3>(0, 0) = r.transpose();
  view.block<1, 3>(1, 0) = u.transpose();
  view.block<1, 3>(2, 0) = -f.transpose();
  view(0, 3) = -r.dot(camera.eye);
  view(1, 3) = -u.dot(camera.eye);
  view(2, 3) = f.dot(camera.eye);

  const double aspect = static_cast<double>(width) / height;
  const double distance = (camera.target - camera.eye).norm();
  Eigen::Matrix4d proj = Eigen::Matrix4d::Zero();
  GlCameraMatrices m;
  if (camera.perspective) {
    // project(): x_pixel = W/2 + focal·vx/vz with focal = H / (2 tan(fov/2)), so
    // x_ndc = (2 focal / W)·vx / vz and y_ndc = (2 focal / H)·vy / vz, w_clip = vz = −z_eye.
    const double t = std::tan(0.5 * camera.fovYDegrees * std::numbers::pi / 180.0);
    const double viewHeight = 2.0 * distance * t;
    m.depthNear = distance / 100.0;
    m.depthFar = 100.0 * distance + 20.0 * viewHeight;
    const double n = m.depthNear, fa = m.depthFar;
    proj(0, 0) = 1.0 / (t * aspect);
    proj(1, 1) = 1.0 / t;
    proj(2, 2) = -(fa + n) / (fa - n);
    proj(2, 3) = -2.0 * fa * n / (fa - n);
    proj(3, 2) = -1.0;
  } else {
    // x_pixel = W/2 + (H / orthoHeight)·vx: x_ndc = 2 vx / (orthoHeight·aspect), y_ndc = 2 vy / orthoHeight.
    const double h = camera.orthoHeight;
    m.depthFar = distance + 20.0 * h;
    m.depthNear = -m.depthFar;
    const double n = m.depthNear, fa = m.depthFar;
    proj(0, 0) = 2.0 / (h * aspect);
    proj(1, 1) = 2.0 / h;
    proj(2, 2) = -2.0 / (fa - n);
    proj(2, 3) = -(fa + n) / (fa - n);
    proj(3, 3) = 1.0;
  }
  m.view = view.cast<float>();
  m.projection = proj.cast<float>();
  return m;
}

}  // namespace myo
