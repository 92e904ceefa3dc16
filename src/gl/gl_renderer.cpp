// GlRenderer: render_mesh.cpp's and markers.cpp's pictures with OpenGL 3.3 core.
//
// An opaque, depth-tested, depth-writing mesh is one draw with GL_LESS. Any other mesh (opacity
// < 1, no depth test or no depth write) follows the software renderer's two passes: its own
// nearest surface is first drawn into a private depth texture; the colour pass then shades only
// fragments at that depth (once per sample, through the stencil buffer when there is one), blended
// at `opacity`; a last depth-only pass writes min(depth, the mesh's nearest) when depthWrite.
#include "myoshell/gl/gl_renderer.h"

#include <epoxy/gl.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "gl_program.h"
#include "gl_shaders.h"
#include "myoshell/core/check.h"

namespace myo {

struct GlRenderer::Impl {
  // Programs and their uniforms.
  GLuint meshProgram = 0, depthProgram = 0, markerProgram = 0;
  struct {
    GLint viewProjection, viewport, smooth, perspective, eye, forward, light, hasBackColor, backColor, ambient,
        diffuse, specular, shininess, wireframe, wireColor, wireWidth, opacity, nearestOnly, nearest, depthRange, origin;
  } mesh{};
  GLint depthViewProjection = -1;
  struct {
    GLint view, projection, viewport, query, tolerance, outline, outlineColor, origin;
  } marker{};

  // Streamed geometry: one VAO over position/normal/colour buffers and the triangle indices.
  GLuint meshVao = 0, positionBuffer = 0, normalBuffer = 0, colorBuffer = 0, indexBuffer = 0;
  GLuint markerVao = 0, markerBuffer = 0;
  std::vector<GLuint> queries;  // one occlusion query per marker, grown as needed
  std::vector<float> positions, normals, colors, markerData;

  // A mesh's own nearest surface (translucent / depth-test-free meshes), frame-sized.
  GLuint nearestFbo = 0, nearestDepth = 0;
  int nearestWidth = 0, nearestHeight = 0;

  // The frame.
  bool inFrame = false;
  int originX = 0, originY = 0;  // its lower-left corner in the bound framebuffer
  Camera camera;
  int width = 0, height = 0;
  GlCameraMatrices matrices;
  Eigen::Matrix4f viewProjection;
  Vec3 light = Vec3::UnitZ();

  void ensureNearestTarget();
  void upload(const MatX3& V, const MatX3i& F, const RenderStyle& style);
  void drawTriangles(GLsizei indexCount) const {
    glDrawElements(GL_TRIANGLES, indexCount, GL_UNSIGNED_INT, nullptr);
  }
};

namespace {

void setVec3(GLint location, const Vec3& v) {
  glUniform3f(location, static_cast<float>(v.x()), static_cast<float>(v.y()), static_cast<float>(v.z()));
}

}  // namespace

GlRenderer::GlRenderer() : impl_(std::make_unique<Impl>()) {
  Impl& s = *impl_;
  s.meshProgram = gl::linkProgram("mesh", gl::kMeshVertexShader, gl::kMeshGeometryShader, gl::kMeshFragmentShader);
  try {
    s.depthProgram = gl::linkProgram("depth", gl::kDepthVertexShader, nullptr, gl::kDepthFragmentShader);
    s.markerProgram = gl::linkProgram("marker", gl::kMarkerVertexShader, nullptr, gl::kMarkerFragmentShader);
  } catch (...) {
    glDeleteProgram(s.meshProgram);
    glDeleteProgram(s.depthProgram);
    throw;
  }
  auto m = [&](const char* name) { return glGetUniformLocation(s.meshProgram, name); };
  s.mesh = {m("uViewProjection"), m("uViewport"),   m("uSmooth"),    m("uPerspective"),  m("uEye"),
            m("uForward"),        m("uLight"),      m("uHasBackColor"), m("uBackColor"), m("uAmbient"),
            m("uDiffuse"),        m("uSpecular"),   m("uShininess"), m("uWireframe"),    m("uWireColor"),
            m("uWireWidth"),      m("uOpacity"),    m("uNearestOnly"), m("uNearest"),    m("uDepthRange"),
            m("uOrigin")};
  s.depthViewProjection = glGetUniformLocation(s.depthProgram, "uViewProjection");
  auto k = [&](const char* name) { return glGetUniformLocation(s.markerProgram, name); };
  s.marker = {k("uView"), k("uProjection"), k("uViewport"), k("uQuery"), k("uTolerance"), k("uOutline"),
              k("uOutlineColor"), k("uOrigin")};

  glGenVertexArrays(1, &s.meshVao);
  glGenBuffers(1, &s.positionBuffer);
  glGenBuffers(1, &s.normalBuffer);
  glGenBuffers(1, &s.colorBuffer);
  glGenBuffers(1, &s.indexBuffer);
  glBindVertexArray(s.meshVao);
  const GLuint buffers[] = {s.positionBuffer, s.normalBuffer, s.colorBuffer};
  for (GLuint a = 0; a < 3; ++a) {
    glBindBuffer(GL_ARRAY_BUFFER, buffers[a]);
    glVertexAttribPointer(a, 3, GL_FLOAT, GL_FALSE, 3 * sizeof(float), nullptr);
  }
  glEnableVertexAttribArray(0);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, s.indexBuffer);  // recorded in the VAO

  // Markers: centre (3), colour (3), radius (1), corner (2) per vertex, four vertices per marker.
  glGenVertexArrays(1, &s.markerVao);
  glGenBuffers(1, &s.markerBuffer);
  glBindVertexArray(s.markerVao);
  glBindBuffer(GL_ARRAY_BUFFER, s.markerBuffer);
  constexpr GLsizei kStride = 9 * sizeof(float);
  const GLint sizes[] = {3, 3, 1, 2};
  size_t offset = 0;
  for (GLuint a = 0; a < 4; ++a) {
    glVertexAttribPointer(a, sizes[a], GL_FLOAT, GL_FALSE, kStride, reinterpret_cast<const void*>(offset));
    glEnableVertexAttribArray(a);
    offset += sizeof(float) * static_cast<size_t>(sizes[a]);
  }
  glBindVertexArray(0);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
}

GlRenderer::~GlRenderer() {
  Impl& s = *impl_;
  glDeleteProgram(s.meshProgram);
  glDeleteProgram(s.depthProgram);
  glDeleteProgram(s.markerProgram);
  const GLuint vaos[] = {s.meshVao, s.markerVao};
  glDeleteVertexArrays(2, vaos);
  const GLuint buffers[] = {s.positionBuffer, s.normalBuffer, s.colorBuffer, s.indexBuffer, s.markerBuffer};
  glDeleteBuffers(5, buffers);
  if (!s.queries.empty()) glDeleteQueries(static_cast<GLsizei>(s.queries.size()), s.queries.data());
  glDeleteFramebuffers(1, &s.nearestFbo);
  glDeleteTextures(1, &s.nearestDepth);
}

void GlRenderer::beginFrame(const Camera& camera, int width, int height, const Rgb& background, int originX,
                            int originY) {
  MYO_CHECK(width > 0 && height > 0, "frame size " << width << "×" << height);
  Impl& s = *impl_;
  s.inFrame = true;
  s.camera = camera;
  s.width = width;
  s.height = height;
  s.matrices = glCameraMatrices(camera, width, height);
  s.viewProjection = s.matrices.projection * s.matrices.view;
  const Vec3 f = camera.forward(), r = camera.right(), u = r.cross(f);
  s.light = (-0.35 * r + 0.45 * u - 1.0 * f).normalized();  // as render_mesh.cpp

  s.originX = originX;
  s.originY = originY;
  glViewport(originX, originY, width, height);
  glDisable(GL_SCISSOR_TEST);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  glDepthMask(GL_TRUE);
  glStencilMask(0xFF);
  glClearColor(static_cast<float>(background.x()), static_cast<float>(background.y()),
               static_cast<float>(background.z()), 1.0f);
  glClearDepth(1.0);
  glClearStencil(0);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);
}

void GlRenderer::Impl::ensureNearestTarget() {
  if (nearestFbo && nearestWidth == width && nearestHeight == height) return;
  if (!nearestFbo) {
    glGenFramebuffers(1, &nearestFbo);
    glGenTextures(1, &nearestDepth);
  }
  glBindTexture(GL_TEXTURE_2D, nearestDepth);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_DEPTH_COMPONENT24, width, height, 0, GL_DEPTH_COMPONENT, GL_UNSIGNED_INT, nullptr);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_MODE, GL_NONE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  glBindTexture(GL_TEXTURE_2D, 0);
  GLint drawFbo = 0, readFbo = 0;
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &drawFbo);
  glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &readFbo);
  glBindFramebuffer(GL_FRAMEBUFFER, nearestFbo);
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, nearestDepth, 0);
  glDrawBuffer(GL_NONE);
  glReadBuffer(GL_NONE);
  const GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, static_cast<GLuint>(drawFbo));
  glBindFramebuffer(GL_READ_FRAMEBUFFER, static_cast<GLuint>(readFbo));
  if (status != GL_FRAMEBUFFER_COMPLETE) throw RenderError("OpenGL: the depth framebuffer of translucent meshes is incomplete");
  nearestWidth = width;
  nearestHeight = height;
}

void GlRenderer::Impl::upload(const MatX3& V, const MatX3i& F, const RenderStyle& style) {
  const Eigen::Index n = V.rows();
  positions.resize(static_cast<size_t>(3 * n));
  for (Eigen::Index i = 0; i < 3 * n; ++i) positions[static_cast<size_t>(i)] = static_cast<float>(V.data()[i]);
  glBindVertexArray(meshVao);
  glBindBuffer(GL_ARRAY_BUFFER, positionBuffer);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(positions.size() * sizeof(float)), positions.data(),
               GL_STREAM_DRAW);

  if (style.smooth) {  // area-weighted vertex normals (mesh/geometry.h's vertexNormals)
    normals.assign(static_cast<size_t>(3 * n), 0.0f);
    for (Eigen::Index t = 0; t < F.rows(); ++t) {
      const Vec3 a = V.row(F(t, 0)), b = V.row(F(t, 1)), c = V.row(F(t, 2));
      const Vec3 nt = (b - a).cross(c - a);
      for (int k = 0; k < 3; ++k) {
        float* dst = &normals[static_cast<size_t>(3 * F(t, k))];
        dst[0] += static_cast<float>(nt.x()), dst[1] += static_cast<float>(nt.y()), dst[2] += static_cast<float>(nt.z());
      }
    }
    for (Eigen::Index i = 0; i < n; ++i) {
      float* v = &normals[static_cast<size_t>(3 * i)];
      const float len = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
      if (len > 0) v[0] /= len, v[1] /= len, v[2] /= len;
    }
    glBindBuffer(GL_ARRAY_BUFFER, normalBuffer);
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(normals.size() * sizeof(float)), normals.data(),
                 GL_STREAM_DRAW);
    glEnableVertexAttribArray(1);
  } else {
    glDisableVertexAttribArray(1);
    glVertexAttrib3f(1, 0.0f, 0.0f, 0.0f);
  }

  if (style.vertexColors.rows() > 0) {
    colors.resize(static_cast<size_t>(3 * n));
    for (Eigen::Index i = 0; i < n; ++i)
      for (int k = 0; k < 3; ++k) colors[static_cast<size_t>(3 * i + k)] = static_cast<float>(style.vertexColors(i, k));
    glBindBuffer(GL_ARRAY_BUFFER, colorBuffer);
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(colors.size() * sizeof(float)), colors.data(),
                 GL_STREAM_DRAW);
    glEnableVertexAttribArray(2);
  } else {
    glDisableVertexAttribArray(2);
    glVertexAttrib3f(2, static_cast<float>(style.color.x()), static_cast<float>(style.color.y()),
                     static_cast<float>(style.color.z()));
  }
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  // MatX3i is row-major: its data is the index list.
  glBufferData(GL_ELEMENT_ARRAY_BUFFER, static_cast<GLsizeiptr>(F.size() * sizeof(int)), F.data(), GL_STREAM_DRAW);
}

void GlRenderer::drawMesh(const MatX3& V, const MatX3i& F, const RenderStyle& style) {
  Impl& s = *impl_;
  MYO_CHECK(s.inFrame, "GlRenderer::drawMesh before beginFrame");
  if (style.vertexColors.rows() > 0) MYO_CHECK_EQ(style.vertexColors.rows(), V.rows());
  if (F.rows() > 0) MYO_CHECK(F.minCoeff() >= 0 && F.maxCoeff() < V.rows(), "face index out of range");
  if (F.rows() == 0) return;
  s.upload(V, F, style);
  const auto indexCount = static_cast<GLsizei>(F.size());

  glEnable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  glDisable(GL_STENCIL_TEST);
  if (style.cullBackFaces) {
    glEnable(GL_CULL_FACE);
    glCullFace(GL_BACK);
    glFrontFace(GL_CCW);
  } else {
    glDisable(GL_CULL_FACE);
  }
  const double alpha = std::clamp(style.opacity, 0.0, 1.0);
  const bool simple = alpha >= 1.0 && style.depthTest && style.depthWrite;

  if (!simple) {  // 1. this mesh's own nearest surface, in the private depth texture
    glActiveTexture(GL_TEXTURE0);
    s.ensureNearestTarget();
    GLint drawFbo = 0, readFbo = 0;
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &drawFbo);
    glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &readFbo);
    glBindFramebuffer(GL_FRAMEBUFFER, s.nearestFbo);
    glViewport(0, 0, s.width, s.height);  // the private texture is frame-sized, without the origin
    glDepthMask(GL_TRUE);
    glDepthFunc(GL_LESS);
    glClear(GL_DEPTH_BUFFER_BIT);
    glUseProgram(s.depthProgram);
    glUniformMatrix4fv(s.depthViewProjection, 1, GL_FALSE, s.viewProjection.data());
    s.drawTriangles(indexCount);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, static_cast<GLuint>(drawFbo));
    glBindFramebuffer(GL_READ_FRAMEBUFFER, static_cast<GLuint>(readFbo));
    glViewport(s.originX, s.originY, s.width, s.height);
  }

  // 2. colour
  glUseProgram(s.meshProgram);
  const Vec3 f = s.camera.forward();
  glUniformMatrix4fv(s.mesh.viewProjection, 1, GL_FALSE, s.viewProjection.data());
  glUniform2f(s.mesh.viewport, static_cast<float>(s.width), static_cast<float>(s.height));
  glUniform2f(s.mesh.origin, static_cast<float>(s.originX), static_cast<float>(s.originY));
  glUniform1i(s.mesh.smooth, style.smooth);
  glUniform1i(s.mesh.perspective, s.camera.perspective);
  setVec3(s.mesh.eye, s.camera.eye);
  setVec3(s.mesh.forward, f);
  setVec3(s.mesh.light, s.light);
  glUniform1i(s.mesh.hasBackColor, style.backColor.has_value());
  setVec3(s.mesh.backColor, style.backColor.value_or(Rgb::Zero()));
  glUniform1f(s.mesh.ambient, static_cast<float>(style.ambient));
  glUniform1f(s.mesh.diffuse, static_cast<float>(style.diffuse));
  glUniform1f(s.mesh.specular, static_cast<float>(style.specular));
  glUniform1f(s.mesh.shininess, static_cast<float>(style.shininess));
  glUniform1i(s.mesh.wireframe, style.wireframe);
  setVec3(s.mesh.wireColor, style.wireColor);
  glUniform1f(s.mesh.wireWidth, static_cast<float>(style.wireWidth));
  glUniform1f(s.mesh.opacity, static_cast<float>(alpha));
  glUniform1i(s.mesh.nearestOnly, !simple);
  glUniform1i(s.mesh.nearest, 0);
  // Tolerance of "at the nearest depth": 0.1 % of the view height (cm), far above depth-buffer
  // quantisation, far below the gaps between surfaces of a face.
  const double viewHeight = s.camera.perspective
                                ? 2.0 * (s.camera.target - s.camera.eye).norm() *
                                      std::tan(0.5 * s.camera.fovYDegrees * 3.14159265358979323846 / 180.0)
                                : s.camera.orthoHeight;
  glUniform3f(s.mesh.depthRange, static_cast<float>(s.matrices.depthNear), static_cast<float>(s.matrices.depthFar),
              static_cast<float>(1e-3 * viewHeight));
  if (simple) {
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
  } else {
    glBindTexture(GL_TEXTURE_2D, s.nearestDepth);
    glDepthFunc(style.depthTest ? GL_LESS : GL_ALWAYS);
    glDepthMask(GL_FALSE);
    // Shade each sample once even where the nearest surface is drawn twice (coincident triangles).
    glEnable(GL_STENCIL_TEST);
    glStencilMask(0xFF);
    glClearStencil(0);
    glClear(GL_STENCIL_BUFFER_BIT);
    glStencilFunc(GL_EQUAL, 0, 0xFF);
    glStencilOp(GL_KEEP, GL_KEEP, GL_INCR);
    if (alpha < 1.0) {
      glEnable(GL_BLEND);
      glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ZERO, GL_ONE);
    }
  }
  s.drawTriangles(indexCount);

  // 3. depth: min(depth, this mesh's nearest) where drawn
  if (!simple && style.depthWrite) {
    glDisable(GL_BLEND);
    glDisable(GL_STENCIL_TEST);
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    glDepthMask(GL_TRUE);
    glDepthFunc(GL_LESS);
    glUseProgram(s.depthProgram);
    glUniformMatrix4fv(s.depthViewProjection, 1, GL_FALSE, s.viewProjection.data());
    s.drawTriangles(indexCount);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  }

  glDisable(GL_BLEND);
  glDisable(GL_STENCIL_TEST);
  glDisable(GL_CULL_FACE);
  glDepthMask(GL_TRUE);
  glDepthFunc(GL_LESS);
  if (!simple) glBindTexture(GL_TEXTURE_2D, 0);
  glBindVertexArray(0);
  glUseProgram(0);
}

void GlRenderer::drawMarkers(const std::vector<Marker>& markers, const MarkerStyle& style) {
  Impl& s = *impl_;
  MYO_CHECK(s.inFrame, "GlRenderer::drawMarkers before beginFrame");
  // Four vertices per marker (a triangle strip); markers behind a perspective eye are left out.
  s.markerData.clear();
  const Vec3 f = s.camera.forward();
  const float corners[4][2] = {{-1, -1}, {1, -1}, {-1, 1}, {1, 1}};
  GLsizei count = 0;
  for (const Marker& m : markers) {
    if (s.camera.perspective && f.dot(m.position - s.camera.eye) <= 0) continue;
    for (const auto& c : corners) {
      const float v[9] = {static_cast<float>(m.position.x()), static_cast<float>(m.position.y()),
                          static_cast<float>(m.position.z()), static_cast<float>(m.color.x()),
                          static_cast<float>(m.color.y()),    static_cast<float>(m.color.z()),
                          static_cast<float>(m.radius),       c[0], c[1]};
      s.markerData.insert(s.markerData.end(), v, v + 9);
    }
    ++count;
  }
  if (count == 0) return;
  if (s.queries.size() < static_cast<size_t>(count)) {
    const size_t old = s.queries.size();
    s.queries.resize(static_cast<size_t>(count));
    glGenQueries(count - static_cast<GLsizei>(old), s.queries.data() + old);
  }
  glBindVertexArray(s.markerVao);
  glBindBuffer(GL_ARRAY_BUFFER, s.markerBuffer);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(s.markerData.size() * sizeof(float)), s.markerData.data(),
               GL_STREAM_DRAW);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  glUseProgram(s.markerProgram);
  glUniformMatrix4fv(s.marker.view, 1, GL_FALSE, s.matrices.view.data());
  glUniformMatrix4fv(s.marker.projection, 1, GL_FALSE, s.matrices.projection.data());
  glUniform2f(s.marker.viewport, static_cast<float>(s.width), static_cast<float>(s.height));
  glUniform2f(s.marker.origin, static_cast<float>(s.originX), static_cast<float>(s.originY));
  glUniform1f(s.marker.tolerance, static_cast<float>(style.depthTolerance));
  glUniform1f(s.marker.outline, static_cast<float>(style.outlineWidth));
  setVec3(s.marker.outlineColor, style.outlineColor);
  glDisable(GL_CULL_FACE);
  glDisable(GL_BLEND);
  glDisable(GL_STENCIL_TEST);

  // Visibility: does any sample of the 3×3 pixels around the marker have a surface no nearer than
  // the marker moved depthTolerance towards the eye?
  glUniform1i(s.marker.query, 1);
  glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
  glDepthMask(GL_FALSE);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LEQUAL);
  for (GLsizei i = 0; i < count; ++i) {
    glBeginQuery(GL_ANY_SAMPLES_PASSED, s.queries[static_cast<size_t>(i)]);
    glDrawArrays(GL_TRIANGLE_STRIP, 4 * i, 4);
    glEndQuery(GL_ANY_SAMPLES_PASSED);
  }
  // The discs of the visible ones, in order, over everything.
  glUniform1i(s.marker.query, 0);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  glDisable(GL_DEPTH_TEST);
  for (GLsizei i = 0; i < count; ++i) {
    glBeginConditionalRender(s.queries[static_cast<size_t>(i)], GL_QUERY_WAIT);
    glDrawArrays(GL_TRIANGLE_STRIP, 4 * i, 4);
    glEndConditionalRender();
  }
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  glBindVertexArray(0);
  glUseProgram(0);
}

}  // namespace myo
