// Internal to the gl layer: the GLSL 330 sources of GlRenderer's programs.
//
// mesh:    the software renderer's lighting (render_mesh.cpp) per fragment. The geometry stage adds
//          the flat normal and, for the wireframe, each fragment's pixel distances to the three
//          edges (screen-space barycentrics × heights, interpolated without perspective).
// depth:   position only, for the depth passes of translucent and depth-test-free meshes.
// marker:  one quad per marker. uQuery: a 3×3-pixel quad around the marker's pixel at the marker's
//          depth moved `uTolerance` cm towards the eye, for an occlusion query; otherwise the disc
//          and its outline, drawn where the query saw a sample pass.
#pragma once

namespace myo::gl {

inline constexpr const char* kMeshVertexShader = R"(#version 330 core
layout(location = 0) in vec3 aPosition;  // cm
layout(location = 1) in vec3 aNormal;    // unit, smooth normals only
layout(location = 2) in vec3 aColor;
uniform mat4 uViewProjection;
out vec3 vPosition;
out vec3 vNormal;
out vec3 vColor;
invariant gl_Position;
void main() {
  vPosition = aPosition;
  vNormal = aNormal;
  vColor = aColor;
  gl_Position = uViewProjection * vec4(aPosition, 1.0);
}
)";

inline constexpr const char* kMeshGeometryShader = R"(#version 330 core
layout(triangles) in;
layout(triangle_strip, max_vertices = 3) out;
in vec3 vPosition[];
in vec3 vNormal[];
in vec3 vColor[];
uniform vec2 uViewport;  // pixels
out vec3 gPosition;
out vec3 gNormal;
out vec3 gColor;
flat out vec3 gFlatNormal;
noperspective out vec3 gEdge;  // pixels to the edge opposite each corner
void main() {
  // As the software renderer: triangles reaching behind a perspective eye are skipped.
  for (int i = 0; i < 3; ++i)
    if (gl_in[i].gl_Position.w <= 1e-6) return;
  vec2 s0 = gl_in[0].gl_Position.xy / gl_in[0].gl_Position.w * 0.5 * uViewport;
  vec2 s1 = gl_in[1].gl_Position.xy / gl_in[1].gl_Position.w * 0.5 * uViewport;
  vec2 s2 = gl_in[2].gl_Position.xy / gl_in[2].gl_Position.w * 0.5 * uViewport;
  float area = abs((s1.x - s0.x) * (s2.y - s0.y) - (s2.x - s0.x) * (s1.y - s0.y));
  vec3 heights = area / max(vec3(length(s2 - s1), length(s0 - s2), length(s1 - s0)), vec3(1e-9));
  vec3 n = cross(vPosition[1] - vPosition[0], vPosition[2] - vPosition[0]);
  float len = length(n);
  vec3 flatNormal = len > 0.0 ? n / len : vec3(0.0);
  for (int i = 0; i < 3; ++i) {
    gl_Position = gl_in[i].gl_Position;
    gPosition = vPosition[i];
    gNormal = vNormal[i];
    gColor = vColor[i];
    gFlatNormal = flatNormal;
    gEdge = vec3(0.0);
    gEdge[i] = heights[i];
    EmitVertex();
  }
  EndPrimitive();
}
)";

inline constexpr const char* kMeshFragmentShader = R"(#version 330 core
in vec3 gPosition;
in vec3 gNormal;
in vec3 gColor;
flat in vec3 gFlatNormal;
noperspective in vec3 gEdge;
uniform bool uSmooth;
uniform bool uPerspective;
uniform vec3 uEye;       // cm
uniform vec3 uForward;   // unit viewing direction
uniform vec3 uLight;     // unit, towards the light
uniform bool uHasBackColor;
uniform vec3 uBackColor;
uniform float uAmbient;
uniform float uDiffuse;
uniform float uSpecular;
uniform float uShininess;
uniform bool uWireframe;
uniform vec3 uWireColor;
uniform float uWireWidth;  // pixels
uniform float uOpacity;
// Only this mesh's nearest surface: uNearest holds its own depth (window depth in [0, 1]).
uniform bool uNearestOnly;
uniform sampler2D uNearest;
uniform vec3 uDepthRange;  // near, far (cm of view depth), tolerance (cm)
uniform vec2 uOrigin;      // the frame's lower-left corner in the framebuffer, pixels
out vec4 fragColor;

float viewDepth(float z) {
  float n = uDepthRange.x, f = uDepthRange.y;
  return uPerspective ? n * f / (f - z * (f - n)) : n + z * (f - n);
}

void main() {
  if (uNearestOnly) {
    float nearest = texelFetch(uNearest, ivec2(gl_FragCoord.xy - uOrigin), 0).r;
    if (viewDepth(gl_FragCoord.z) > viewDepth(nearest) + uDepthRange.z) discard;
  }
  vec3 n = uSmooth ? gNormal : gFlatNormal;
  if (length(n) > 0.0) n = normalize(n);
  vec3 base = gColor;
  if (!gl_FrontFacing) {  // the back side is lit as a surface of its own
    n = -n;
    if (uHasBackColor) base = uBackColor;
  }
  vec3 toCamera = uPerspective ? normalize(uEye - gPosition) : -uForward;
  float lambert = max(0.0, dot(n, uLight));
  float spec = 0.0;
  if (uSpecular > 0.0 && lambert > 0.0)
    spec = uSpecular * pow(max(0.0, dot(n, normalize(uLight + toCamera))), uShininess);
  vec3 color = base * (uAmbient + uDiffuse * lambert) + vec3(spec);
  if (uWireframe && min(gEdge.x, min(gEdge.y, gEdge.z)) < 0.5 * uWireWidth) color = uWireColor;
  fragColor = vec4(clamp(color, 0.0, 1.0), uOpacity);
}
)";

inline constexpr const char* kDepthVertexShader = R"(#version 330 core
layout(location = 0) in vec3 aPosition;
uniform mat4 uViewProjection;
invariant gl_Position;
void main() { gl_Position = uViewProjection * vec4(aPosition, 1.0); }
)";

inline constexpr const char* kDepthFragmentShader = R"(#version 330 core
void main() {}
)";

inline constexpr const char* kMarkerVertexShader = R"(#version 330 core
layout(location = 0) in vec3 aCenter;   // cm
layout(location = 1) in vec3 aColor;
layout(location = 2) in float aRadius;  // pixels
layout(location = 3) in vec2 aCorner;   // (±1, ±1)
uniform mat4 uView;
uniform mat4 uProjection;
uniform vec2 uViewport;    // pixels
uniform bool uQuery;
uniform float uTolerance;  // cm
uniform float uOutline;    // pixels
flat out vec2 mCenter;     // image pixels, y down (camera.h)
flat out vec3 mColor;
flat out float mRadius;
void main() {
  vec4 eye = uView * vec4(aCenter, 1.0);
  vec4 clip = uProjection * eye;
  vec2 ndc = clip.xy / clip.w;
  vec2 center = vec2((ndc.x + 1.0) * 0.5 * uViewport.x, (1.0 - ndc.y) * 0.5 * uViewport.y);
  mCenter = center;
  mColor = aColor;
  mRadius = aRadius;
  vec2 corner;
  float z = 0.0;
  if (uQuery) {
    corner = floor(center) + 0.5 + 1.5 * aCorner;  // the 3×3 pixels around the marker's pixel
    vec4 moved = uProjection * vec4(eye.xy, eye.z + uTolerance, 1.0);
    z = moved.w > 0.0 ? clamp(moved.z / moved.w, -1.0, 1.0) : -1.0;
  } else {
    corner = center + (aRadius + max(uOutline, 0.0) + 1.0) * aCorner;
  }
  gl_Position = vec4(2.0 * corner.x / uViewport.x - 1.0, 1.0 - 2.0 * corner.y / uViewport.y, z, 1.0);
}
)";

inline constexpr const char* kMarkerFragmentShader = R"(#version 330 core
flat in vec2 mCenter;
flat in vec3 mColor;
flat in float mRadius;
uniform bool uQuery;
uniform vec2 uViewport;
uniform vec2 uOrigin;  // the frame's lower-left corner in the framebuffer, pixels
uniform float uOutline;
uniform vec3 uOutlineColor;
out vec4 fragColor;
void main() {
  if (uQuery) {
    fragColor = vec4(0.0);
    return;
  }
  vec2 p = gl_FragCoord.xy - uOrigin;
  float d = distance(vec2(p.x, uViewport.y - p.y), mCenter);
  if (d <= mRadius) fragColor = vec4(mColor, 1.0);
  else if (d <= mRadius + max(uOutline, 0.0)) fragColor = vec4(uOutlineColor, 1.0);
  else discard;
}
)";

}  // namespace myo::gl
