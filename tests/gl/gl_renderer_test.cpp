// GlRenderer against the software renderer: coverage, shading, vertex colours, back faces,
// markers, translucency, depth-test-free drawing. Skips (with EGL's reason) where no headless
// OpenGL context can be made.
#include <gtest/gtest.h>

#include <cstdio>
#include <functional>
#include <memory>

#include "myoshell/core/errors.h"
#include "myoshell/gl/gl_context.h"
#include "myoshell/gl/gl_renderer.h"
#include "myoshell/head/head.h"
#include "myoshell/mesh/primitives.h"
#include "myoshell/render/markers.h"
#include "myoshell/render/render_mesh.h"

namespace myo {
namespace {

const Rgb kBlack = Rgb::Zero();

class GlRendering : public ::testing::Test {
 protected:
  void SetUp() override {
    try {
      context_ = std::make_unique<HeadlessGlContext>();
    } catch (const RenderError& e) {
      GTEST_SKIP() << "no headless OpenGL here: " << e.what();
    }
    renderer_ = std::make_unique<GlRenderer>();
  }

  // A GL picture: `draw` is called between beginFrame and read().
  Image gl(const Camera& camera, int width, int height, const std::function<void(GlRenderer&)>& draw,
           int samples = 4, const Rgb& background = kBlack) {
    GlOffscreenTarget target(width, height, samples);
    target.bind();
    renderer_->beginFrame(camera, width, height, background);
    draw(*renderer_);
    return target.read();
  }

  std::unique_ptr<HeadlessGlContext> context_;
  std::unique_ptr<GlRenderer> renderer_;
};

bool covered(const Image& im, int x, int y, const Rgb& background = kBlack) { return im.at(x, y) != background; }

double intersectionOverUnion(const Image& a, const Image& b) {
  int both = 0, either = 0;
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x) {
      both += covered(a, x, y) && covered(b, x, y);
      either += covered(a, x, y) || covered(b, x, y);
    }
  return either ? static_cast<double>(both) / either : 0.0;
}

// Mean colour (0–255 levels) over pixels covered in both pictures, away from their silhouettes
// (the pixel and its four neighbours covered in both), and how many there were.
std::pair<Vec3, int> meanInteriorColor(const Image& image, const Image& a, const Image& b) {
  Vec3 sum = Vec3::Zero();
  int n = 0;
  for (int y = 1; y + 1 < image.height; ++y)
    for (int x = 1; x + 1 < image.width; ++x) {
      bool inside = true;
      for (auto [dx, dy] : {std::pair{0, 0}, {1, 0}, {-1, 0}, {0, 1}, {0, -1}})
        inside = inside && covered(a, x + dx, y + dy) && covered(b, x + dx, y + dy);
      if (!inside) continue;
      sum += 255.0 * image.at(x, y);
      ++n;
    }
  return {n ? Vec3(sum / n) : sum, n};
}

Image software(const Camera& camera, int width, int height, const std::function<void(Image&, DepthBuffer&)>& draw,
               const Rgb& background = kBlack) {
  Image image(width, height, background);
  DepthBuffer depth(width, height);
  draw(image, depth);
  return image;
}

Camera obliqueCamera(bool perspective) {
  Camera c;
  c.eye = Vec3(3.0, 2.0, 6.0);
  c.target = Vec3(0.1, -0.1, 0.0);
  c.up = Vec3(0.1, 1.0, 0.0);
  c.perspective = perspective;
  c.orthoHeight = 3.0;
  c.fovYDegrees = 35.0;
  return c;
}

void expectSameAsSoftware(const Image& glImage, const Image& swImage) {
  EXPECT_GE(intersectionOverUnion(glImage, swImage), 0.97);
  const auto [glMean, n] = meanInteriorColor(glImage, glImage, swImage);
  const auto [swMean, m] = meanInteriorColor(swImage, glImage, swImage);
  ASSERT_GT(n, 1000);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(glMean[k], swMean[k], 3.0) << "channel " << k;
}

TEST_F(GlRendering, ContextNamesItsRendererAndVersion) {
  EXPECT_FALSE(context_->renderer().empty());
  int major = 0, minor = 0;
  ASSERT_EQ(std::sscanf(context_->version().c_str(), "%d.%d", &major, &minor), 2) << context_->version();
  EXPECT_GE(major * 10 + minor, 33) << context_->version();
}

TEST_F(GlRendering, SphereMatchesTheSoftwareRendererSmoothAndFlat) {
  const TriMesh sphere = icosphere(1.0, 3);
  for (bool perspective : {false, true})
    for (bool smooth : {true, false}) {
      SCOPED_TRACE(::testing::Message() << "perspective " << perspective << " smooth " << smooth);
      RenderStyle style;
      style.smooth = smooth;
      const Camera camera = obliqueCamera(perspective);
      const Image g = gl(camera, 200, 150, [&](GlRenderer& r) { r.drawMesh(sphere.V, sphere.F, style); }, 1);
      const Image s = software(camera, 200, 150, [&](Image& im, DepthBuffer& d) {
        renderMesh(im, d, camera, sphere.V, sphere.F, style);
      });
      expectSameAsSoftware(g, s);
    }
}

TEST_F(GlRendering, DefaultHeadMatchesTheSoftwareRendererWithMultisampling) {
  const Head head = loadDefaultHead();
  Camera camera;
  const FaceFrame frame = head.frame();
  ViewFrame view;
  view.origin = frame.origin;
  view.axes = frame.axes;
  view.scale = frame.scale;
  camera = presetCamera(view, ViewPreset::threeQuarter);
  fitToBounds(camera, head.mesh.V, 240, 240, 0.05);
  RenderStyle style;
  style.backColor = Rgb(0.5, 0.2, 0.2);
  const Image g = gl(camera, 240, 240, [&](GlRenderer& r) { r.drawMesh(head.mesh.V, head.mesh.F, style); });
  const Image s = software(camera, 240, 240, [&](Image& im, DepthBuffer& d) {
    renderMesh(im, d, camera, head.mesh.V, head.mesh.F, style);
  });
  expectSameAsSoftware(g, s);
}

// The triangle of tests/render: pixels (25,75) (75,75) (50,25) of a 100×100 picture.
MatX3 triangle(double z) {
  MatX3 V(3, 3);
  V << -0.5, -0.5, z, 0.5, -0.5, z, 0.0, 0.5, z;
  return V;
}
MatX3i oneFace(bool flipped = false) {
  MatX3i F(1, 3);
  if (flipped) F << 0, 2, 1;
  else F << 0, 1, 2;
  return F;
}
Camera frontCamera() {
  Camera c;
  c.eye = Vec3(0, 0, 10);
  c.orthoHeight = 2.0;
  return c;
}

TEST_F(GlRendering, RowZeroIsTheTopOfThePicture) {
  const Image im = gl(frontCamera(), 100, 100, [&](GlRenderer& r) { r.drawMesh(triangle(0), oneFace()); }, 1);
  int n = 0;
  for (int y = 0; y < 100; ++y)
    for (int x = 0; x < 100; ++x) n += covered(im, x, y);
  EXPECT_NEAR(n, 1250, 60);
  EXPECT_TRUE(covered(im, 50, 30));    // near the apex, at the top
  EXPECT_TRUE(covered(im, 30, 72));    // near the base's left end
  EXPECT_FALSE(covered(im, 50, 80));   // below the base
  EXPECT_FALSE(covered(im, 30, 30));   // left of the apex
  EXPECT_FALSE(covered(im, 10, 90));
}

TEST_F(GlRendering, VertexColorsAreInterpolated) {
  RenderStyle style;
  style.vertexColors = MatX3(3, 3);
  style.vertexColors << 1, 0, 0, 0, 1, 0, 0, 0, 1;
  style.specular = 0;
  style.ambient = 1.0;
  style.diffuse = 0.0;
  const Image im = gl(frontCamera(), 100, 100, [&](GlRenderer& r) { r.drawMesh(triangle(0), oneFace(), style); });
  const Rgb nearRed = im.at(30, 72), nearGreen = im.at(69, 72), nearBlue = im.at(50, 32), centre = im.at(50, 58);
  EXPECT_GT(nearRed.x(), 0.7);
  EXPECT_LT(nearRed.y() + nearRed.z(), 0.35);
  EXPECT_GT(nearGreen.y(), 0.7);
  EXPECT_LT(nearGreen.x() + nearGreen.z(), 0.35);
  EXPECT_GT(nearBlue.z(), 0.7);
  EXPECT_LT(nearBlue.x() + nearBlue.y(), 0.35);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(centre[k], 1.0 / 3.0, 0.08) << k;
}

TEST_F(GlRendering, BackFacesTakeTheBackColorOrAreCulled) {
  RenderStyle style;
  style.color = Rgb(0.9, 0.2, 0.1);
  style.backColor = Rgb(0.2, 0.3, 0.9);
  const Image front = gl(frontCamera(), 100, 100, [&](GlRenderer& r) { r.drawMesh(triangle(0), oneFace(), style); });
  const Image back = gl(frontCamera(), 100, 100, [&](GlRenderer& r) { r.drawMesh(triangle(0), oneFace(true), style); });
  EXPECT_GT(front.at(50, 58).x(), front.at(50, 58).z());
  EXPECT_GT(back.at(50, 58).z(), back.at(50, 58).x());
  EXPECT_GT(back.at(50, 58).sum(), 0.3);  // lit
  // Same shade as the software renderer gives the back side.
  const Image sw = software(frontCamera(), 100, 100, [&](Image& im, DepthBuffer& d) {
    renderMesh(im, d, frontCamera(), triangle(0), oneFace(true), style);
  });
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(back.at(50, 58)[k], sw.at(50, 58)[k], 2.0 / 255) << k;

  style.cullBackFaces = true;
  const Image culled = gl(frontCamera(), 100, 100, [&](GlRenderer& r) { r.drawMesh(triangle(0), oneFace(true), style); });
  for (int y = 0; y < 100; ++y)
    for (int x = 0; x < 100; ++x) ASSERT_FALSE(covered(culled, x, y)) << x << "," << y;
}

TEST_F(GlRendering, NearerSurfaceHidesFartherWhateverTheOrder) {
  RenderStyle red, blue;
  red.color = Rgb(1, 0, 0);
  blue.color = Rgb(0, 0, 1);
  red.specular = blue.specular = 0;
  for (bool nearFirst : {true, false}) {
    const Image im = gl(frontCamera(), 100, 100, [&](GlRenderer& r) {
      if (nearFirst) {
        r.drawMesh(triangle(1.0), oneFace(), red);
        r.drawMesh(triangle(0.0), oneFace(), blue);
      } else {
        r.drawMesh(triangle(0.0), oneFace(), blue);
        r.drawMesh(triangle(1.0), oneFace(), red);
      }
    });
    EXPECT_GT(im.at(50, 58).x(), 0.5) << nearFirst;
    EXPECT_EQ(im.at(50, 58).z(), 0.0) << nearFirst;
  }
}

TEST_F(GlRendering, OpacityHalfBlendsOnlyTheNearestSurface) {
  RenderStyle flat;  // unlit: the colour itself
  flat.ambient = 1.0;
  flat.diffuse = 0.0;
  flat.specular = 0.0;
  RenderStyle blue = flat, red = flat;
  blue.color = Rgb(0, 0, 1);
  red.color = Rgb(1, 0, 0);
  red.opacity = 0.5;
  const Image im = gl(frontCamera(), 100, 100, [&](GlRenderer& r) {
    r.drawMesh(triangle(0.0), oneFace(), blue);
    r.drawMesh(triangle(1.0), oneFace(), red);
  });
  EXPECT_NEAR(im.at(50, 58).x(), 0.5, 2.0 / 255);
  EXPECT_NEAR(im.at(50, 58).z(), 0.5, 2.0 / 255);

  // A closed sphere at half opacity over black: one layer blended (0.5), not two (0.75).
  RenderStyle white = flat;
  white.color = Rgb(1, 1, 1);
  white.opacity = 0.5;
  const TriMesh sphere = icosphere(0.8, 3);
  const Image s = gl(frontCamera(), 100, 100, [&](GlRenderer& r) { r.drawMesh(sphere.V, sphere.F, white); });
  EXPECT_NEAR(s.at(50, 50).x(), 0.5, 2.0 / 255);
  EXPECT_NEAR(s.at(40, 45).y(), 0.5, 2.0 / 255);
  // The same through the software renderer.
  const Image sw = software(frontCamera(), 100, 100, [&](Image& img, DepthBuffer& d) {
    renderMesh(img, d, frontCamera(), sphere.V, sphere.F, white);
  });
  EXPECT_NEAR(s.at(40, 45).x(), sw.at(40, 45).x(), 2.0 / 255);

  // A translucent mesh behind an opaque one is hidden by it, and leaves the depth written.
  const Image hidden = gl(frontCamera(), 100, 100, [&](GlRenderer& r) {
    r.drawMesh(triangle(1.0), oneFace(), blue);
    r.drawMesh(triangle(0.0), oneFace(), red);
  });
  EXPECT_EQ(hidden.at(50, 58).x(), 0.0);
}

TEST_F(GlRendering, WithoutDepthTestAMeshIsDrawnOnTopYetHidesItsOwnBack) {
  RenderStyle near, onTop;
  near.color = Rgb(0, 0, 1);
  near.specular = onTop.specular = 0;
  onTop.color = Rgb(1, 0, 0);
  onTop.depthTest = false;
  const TriMesh sphere = icosphere(0.5, 3);
  MatX3 behind = sphere.V;
  behind.col(2).array() -= 3.0;  // well behind the triangle
  const Image im = gl(frontCamera(), 100, 100, [&](GlRenderer& r) {
    r.drawMesh(triangle(0.0), oneFace(), near);
    r.drawMesh(behind, sphere.F, onTop);
  });
  EXPECT_GT(im.at(50, 50).x(), 0.3);
  EXPECT_EQ(im.at(50, 50).z(), 0.0);
  // Its own front hides its back: the same shading as the software renderer's.
  const Image sw = software(frontCamera(), 100, 100, [&](Image& img, DepthBuffer& d) {
    renderMesh(img, d, frontCamera(), triangle(0.0), oneFace(), near);
    renderMesh(img, d, frontCamera(), behind, sphere.F, onTop);
  });
  for (auto [x, y] : {std::pair{50, 50}, {42, 44}, {58, 55}})
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(im.at(x, y)[k], sw.at(x, y)[k], 3.0 / 255) << x << "," << y << " " << k;
}

TEST_F(GlRendering, WireframeColoursTheEdges) {
  RenderStyle style;
  style.wireframe = true;
  style.wireColor = Rgb(0, 1, 0);
  style.wireWidth = 3.0;
  style.color = Rgb(1, 0, 0);
  style.specular = 0.0;
  const Image im = gl(frontCamera(), 100, 100, [&](GlRenderer& r) { r.drawMesh(triangle(0), oneFace(), style); }, 1);
  EXPECT_EQ(im.at(50, 74), Rgb(0, 1, 0));  // on the base (y = 75)
  EXPECT_GT(im.at(50, 58).x(), 0.5);      // inside
  EXPECT_EQ(im.at(50, 58).y(), 0.0);
  // Nearly the same edge pixels as the software renderer, on a whole sphere too.
  const TriMesh sphere = icosphere(0.9, 2);
  for (const auto& [V, F] : {std::pair{triangle(0), oneFace()}, std::pair{sphere.V, sphere.F}}) {
    const Image g = gl(frontCamera(), 100, 100, [&](GlRenderer& r) { r.drawMesh(V, F, style); }, 1);
    const Image sw = software(frontCamera(), 100, 100, [&](Image& img, DepthBuffer& d) {
      renderMesh(img, d, frontCamera(), V, F, style);
    });
    int both = 0, either = 0;
    for (int y = 0; y < 100; ++y)
      for (int x = 0; x < 100; ++x) {
        const bool a = g.at(x, y) == Rgb(0, 1, 0), b = sw.at(x, y) == Rgb(0, 1, 0);
        both += a && b;
        either += a || b;
      }
    EXPECT_GT(either, 100);
    EXPECT_GE(static_cast<double>(both) / either, 0.85) << both << " of " << either;
  }
}

TEST_F(GlRendering, MarkersShowWhereVisibleAndNotBehindASurface) {
  const TriMesh sphere = icosphere(0.8, 3);
  const Camera camera = frontCamera();
  std::vector<Marker> markers(3);
  markers[0].position = Vec3(-0.3, 0.2, std::sqrt(0.64 - 0.13) + 0.01);  // on the front, visible
  markers[0].color = Rgb(0, 1, 0);
  markers[1].position = Vec3(0.3, -0.2, -std::sqrt(0.64 - 0.13));        // on the back, hidden
  markers[1].color = Rgb(0, 1, 0);
  markers[2].position = Vec3(0.3, 0.3, std::sqrt(0.64 - 0.18) - 0.05);   // 0.05 cm under the front: within tolerance
  markers[2].color = Rgb(0, 1, 0);
  RenderStyle skin;
  skin.color = Rgb(0.9, 0.2, 0.2);
  const Image g = gl(camera, 100, 100, [&](GlRenderer& r) {
    r.drawMesh(sphere.V, sphere.F, skin);
    r.drawMarkers(markers);
  });
  const Image s = software(camera, 100, 100, [&](Image& im, DepthBuffer& d) {
    renderMesh(im, d, camera, sphere.V, sphere.F, skin);
    drawMarkers(im, &d, camera, markers);
  });
  const Rgb green(0, 1, 0);
  for (size_t i = 0; i < markers.size(); ++i) {
    const ScreenPoint p = project(camera, markers[i].position, 100, 100);
    const int x = static_cast<int>(p.x), y = static_cast<int>(p.y);
    const bool visible = i != 1;
    EXPECT_EQ(g.at(x, y) == green, visible) << "marker " << i;
    EXPECT_EQ(s.at(x, y) == green, visible) << "marker " << i << " (software)";
  }
  // The same disc and outline pixels as the software renderer.
  const Rgb outline = Rgb::Constant(13.0 / 255);  // MarkerStyle's 0.05 as a byte
  int discs = 0, outlines = 0, differ = 0;
  for (int y = 0; y < 100; ++y)
    for (int x = 0; x < 100; ++x) {
      discs += g.at(x, y) == green;
      outlines += g.at(x, y) == outline;
      differ += (g.at(x, y) == green) != (s.at(x, y) == green);
      differ += (g.at(x, y) == outline) != (s.at(x, y) == outline);
    }
  EXPECT_GT(discs, 40);     // two discs of radius 3
  EXPECT_GT(outlines, 20);  // and their rings
  EXPECT_LE(differ, 6);
}

}  // namespace
}  // namespace myo
