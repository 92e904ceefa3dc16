#include "viewer_app.h"

// libepoxy first: it must come before any other GL header (GLFW's included).
#include <epoxy/gl.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <fmt/core.h>
#include <imgui.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "myoshell/core/errors.h"
#include "myoshell/core/timer.h"
#include "myoshell/gl/gl_face_painter.h"
#include "myoshell/gl/gl_renderer.h"
#include "myoshell/mesh/ray_cast.h"
#include "myoshell/render/colormap.h"
#include "myoshell/render/png.h"

namespace myo::viewer {
namespace {

std::string& glfwLastError() {
  static std::string message;
  return message;
}

std::string noWindowMessage() {
  return "cannot open a window: " + glfwLastError() +
         " (is DISPLAY set? Run under `xvfb-run -a`, or use `myoshell render` for pictures without a display)";
}

// What is drawn, and from where.
struct Display {
  bool muscles = false, roi = false, displacement = false, pins = false, wireframe = false, skull = false;
  bool panel = true;
  int selected = 0;              // muscle whose ROI is shown
  double displacementScale = 1;  // cm at the top of the colour map
  double yaw = 0, pitch = 0;     // degrees, about the face frame (camera.h orbitCamera)
  double zoom = 1;               // 2 = twice as close
  Vec3 pan = Vec3::Zero();       // cm, added to the target
  double dragStiffness = 1500;   // dyn/cm: the mouse pulls the grabbed spot like a spring
};

// A ray from pixel (x, y) of a width × height picture of `camera` (camera.h's conventions).
void pixelRay(const Camera& camera, double x, double y, int width, int height, Vec3& origin, Vec3& direction) {
  const Vec3 f = camera.forward(), r = camera.right(), u = camera.trueUp();
  const double sx = x - 0.5 * width, sy = 0.5 * height - y;
  if (camera.perspective) {
    const double focal = 0.5 * height / std::tan(0.5 * camera.fovYDegrees * M_PI / 180.0);
    origin = camera.eye;
    direction = (f * focal + r * sx + u * sy).normalized();
  } else {
    const double pixel = camera.orthoHeight / height;
    origin = camera.eye + r * (sx * pixel) + u * (sy * pixel);
    direction = f;
  }
}

// The skin vertex nearest to where the ray first hits the mesh (mesh/ray_cast.h), or −1.
int pickVertex(const MatX3& V, const MatX3i& F, const Vec3& origin, const Vec3& direction) {
  double best = std::numeric_limits<double>::infinity();
  int hitTriangle = -1;
  Vec3 hitPoint = Vec3::Zero();
  for (Eigen::Index t = 0; t < F.rows(); ++t) {
    const std::optional<LineTriangleHit> hit = lineMeetsTriangle(origin, direction, V.row(F(t, 0)), V.row(F(t, 1)), V.row(F(t, 2)));
    if (hit && hit->t > 0 && hit->t < best) {
      best = hit->t;
      hitTriangle = static_cast<int>(t);
      hitPoint = origin + hit->t * direction;
    }
  }
  if (hitTriangle < 0) return -1;
  int nearest = F(hitTriangle, 0);
  for (int k = 1; k < 3; ++k)
    if ((Vec3(V.row(F(hitTriangle, k))) - hitPoint).norm() < (Vec3(V.row(nearest)) - hitPoint).norm())
      nearest = F(hitTriangle, k);
  return nearest;
}

class ViewerApp {
 public:
  ViewerApp(ViewerSession& session, const ViewerOptions& options) : session_(session), options_(options) {
    glfwSetErrorCallback([](int, const char* description) { glfwLastError() = description; });
    if (!glfwInit()) throw RenderError(noWindowMessage());
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    const std::string title = "Myoshell — " + (session.scene().name.empty() ? std::string("default head") : session.scene().name);
    openWindow(title, options.samples < 0 ? 4 : options.samples);
    if (options.samples < 0) {  // auto: no multisampling on a software rasterizer
      const std::string renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
      if (renderer.find("llvmpipe") != std::string::npos || renderer.find("softpipe") != std::string::npos) {
        glfwDestroyWindow(window_);
        openWindow(title, 0);
      }
    }
    glfwSwapInterval(options.script.empty() && options.screenshot.empty() ? 1 : 0);
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini next to the user's files
    ImGui::StyleColorsDark();
    ImGui_ImplGlfw_InitForOpenGL(window_, true);
    ImGui_ImplOpenGL3_Init("#version 330 core");
    renderer_ = std::make_unique<GlRenderer>();
    const FaceFrame frame = session.model().head().frame();
    viewFrame_.origin = frame.origin;
    viewFrame_.axes = frame.axes;
    viewFrame_.scale = frame.scale;
  }

  void openWindow(const std::string& title, int samples) {
    glfwWindowHint(GLFW_SAMPLES, samples);
    window_ = glfwCreateWindow(options_.width, options_.height, title.c_str(), nullptr, nullptr);
    if (!window_) {
      const std::string why = glfwLastError();
      glfwTerminate();
      throw RenderError("cannot open an OpenGL 3.3 core window: " + why);
    }
    glfwMakeContextCurrent(window_);
  }

  ~ViewerApp() {
    renderer_.reset();
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
    glfwDestroyWindow(window_);
    glfwTerminate();
  }

  ViewerStats stats() const { return stats_; }

  void run() {
    if (!options_.script.empty()) {
      runScript(readViewerScript(options_.script));
      if (!options_.stay && options_.screenshot.empty()) return;
    }
    if (!options_.screenshot.empty()) {
      if (!session_.scene().activations.empty() && session_.playhead() == 0.0) session_.playing = true;
      for (int f = 0; f < options_.frames; ++f) frame(1.0 / session_.scene().fps);
      frame(0.0, options_.screenshot);
      return;
    }
    double last = glfwGetTime();
    while (!glfwWindowShouldClose(window_)) {
      const double now = glfwGetTime();
      frame(std::min(now - last, 0.05));  // a stalled frame does not make the simulation jump
      last = now;
    }
  }

 private:
  ViewerSession& session_;
  ViewerOptions options_;
  GLFWwindow* window_ = nullptr;
  std::unique_ptr<GlRenderer> renderer_;
  ViewFrame viewFrame_;
  Display display_;
  Camera camera_;
  int width_ = 0, height_ = 0;  // framebuffer pixels
  int faceX_ = 0, faceWidth_ = 0;  // the face's viewport: right of the panel when it is shown
  static constexpr int kPanelWidth = 430;
  std::string status_;
  std::string scenePath_ = "viewer_scene.json", glbPath_ = "viewer.glb";
  int screenshots_ = 0;
  ViewerStats stats_;
  bool orbiting_ = false, panning_ = false, f12WasDown_ = false;
  // The grab is the mouse's (Ctrl + left-drag), not a script's: only the mouse's follows the cursor
  // and ends when the button is up (a script's grab, pull and release are its own commands).
  bool mouseGrab_ = false;
  float stiffnessEdit_ = 0.0f;      // the anatomical stiffness slider while it is dragged
  bool stiffnessDragged_ = false;
  double pendingStiffness_ = 0.0;   // > 0: rebuild the anatomical skin at this scale next frame
  double lastX_ = 0, lastY_ = 0;
  Vec3 grabPoint_ = Vec3::Zero();  // where the mouse holds the skin, cm (on the plane ⟂ view)

  Camera makeCamera() const {
    Camera camera = orbitCamera(viewFrame_, display_.yaw, display_.pitch);
    fitToBounds(camera, session_.model().head().mesh.V, faceWidth_, std::max(height_, 1), 0.06);
    camera.orthoHeight /= display_.zoom;
    camera.target += display_.pan;
    camera.eye += display_.pan;
    return camera;
  }

  // One frame: input, the panel, `seconds` of simulation, drawing, an optional screenshot.
  void frame(double seconds, const std::string& screenshot = {}) {
    if (pendingStiffness_ > 0.0) {  // the last frame showed the message: the rebuild blocks this one
      const double s = std::exchange(pendingStiffness_, 0.0);
      try {
        status_ = fmt::format("stiffness ×{:.2f}: skin rebuilt in {:.1f} s", s, session_.setStiffnessScale(s));
        mouseGrab_ = false;
      } catch (const std::exception& e) {
        status_ = e.what();
      }
      seconds = 0.0;  // the rebuild's wall time is not simulated time
    }
    Stopwatch clock;
    glfwPollEvents();
    glfwGetFramebufferSize(window_, &width_, &height_);
    faceX_ = display_.panel && width_ > 2 * kPanelWidth ? kPanelWidth : 0;
    faceWidth_ = std::max(width_ - faceX_, 1);
    camera_ = makeCamera();
    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    handleMouse();
    if (display_.panel) panel();
    session_.advance(seconds);
    draw();
    ImGui::Render();
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
    const bool f12 = glfwGetKey(window_, GLFW_KEY_F12) == GLFW_PRESS;
    if (f12 && !f12WasDown_) saveScreenshot(fmt::format("myoshell_view_{:03d}.png", screenshots_++));
    f12WasDown_ = f12;
    if (!screenshot.empty()) saveScreenshot(screenshot, false);
    glfwSwapBuffers(window_);
    if (screenshot.empty()) {  // a screenshot's PNG encoding is not a frame's cost
      ++stats_.frames;
      stats_.seconds += clock.seconds();
    }
  }

  void saveScreenshot(const std::string& path, bool announce = true) {
    glReadBuffer(GL_BACK);
    writePng(path, readFramebuffer(width_, height_));
    if (announce) status_ = "saved " + path;  // scripted captures keep the panel unchanged
  }

  void handleMouse() {
    ImGuiIO& io = ImGui::GetIO();
    double x, y;
    glfwGetCursorPos(window_, &x, &y);
    int windowW, windowH;
    glfwGetWindowSize(window_, &windowW, &windowH);
    const double toPixels = windowW > 0 ? static_cast<double>(width_) / windowW : 1.0;
    const double px = x * toPixels - faceX_, py = y * toPixels;  // in the face's viewport
    const bool left = glfwGetMouseButton(window_, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
    const bool right = glfwGetMouseButton(window_, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS;
    const bool ctrl = glfwGetKey(window_, GLFW_KEY_LEFT_CONTROL) == GLFW_PRESS ||
                      glfwGetKey(window_, GLFW_KEY_RIGHT_CONTROL) == GLFW_PRESS;
    if (!io.WantCaptureMouse) {
      if (left && ctrl && !mouseGrab_) grabAt(px, py);
      if (left && !ctrl && !mouseGrab_ && !orbiting_) orbiting_ = true, lastX_ = px, lastY_ = py;
      if (right && !panning_) panning_ = true, lastX_ = px, lastY_ = py;
      if (io.MouseWheel != 0.0f) display_.zoom = std::clamp(display_.zoom * std::pow(1.15, io.MouseWheel), 0.2, 20.0);
    }
    if (!left) {
      orbiting_ = false;
      if (mouseGrab_ && session_.grabbing()) session_.release();
      mouseGrab_ = false;
    }
    if (!right) panning_ = false;
    const double pixel = camera_.orthoHeight / std::max(height_, 1);
    if (orbiting_) {
      display_.yaw -= 0.4 * (px - lastX_);
      display_.pitch = std::clamp(display_.pitch + 0.4 * (py - lastY_), -85.0, 85.0);
    }
    if (panning_) display_.pan += -camera_.right() * ((px - lastX_) * pixel) + camera_.trueUp() * ((py - lastY_) * pixel);
    if (mouseGrab_ && session_.grabbing()) {
      // The spot follows the mouse on the plane through the grab point facing the viewer.
      Vec3 origin, direction;
      pixelRay(camera_, px, py, faceWidth_, height_, origin, direction);
      const double along = (grabPoint_ - origin).dot(camera_.forward()) / direction.dot(camera_.forward());
      const Vec3 target = origin + along * direction;
      const Vec3 now = session_.simulator().skinPositions().row(session_.grabbedVertex());
      session_.pull(display_.dragStiffness * (target - now));
    }
    lastX_ = px;
    lastY_ = py;
  }

  void grabAt(double px, double py) {
    Vec3 origin, direction;
    pixelRay(camera_, px, py, faceWidth_, height_, origin, direction);
    const MatX3 positions = session_.simulator().skinPositions();
    const int vertex = pickVertex(positions, session_.model().head().mesh.F, origin, direction);
    if (vertex < 0) return;
    try {
      session_.grab(vertex);
      mouseGrab_ = true;
      grabPoint_ = positions.row(vertex);
      status_ = fmt::format("pulling vertex {}", vertex);
    } catch (const InputError& e) {
      status_ = e.what();
    }
  }

  void panel() {
    ImGui::SetNextWindowPos(ImVec2(8, 8), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize(ImVec2(kPanelWidth - 16, static_cast<float>(std::max(height_ - 16, 200))), ImGuiCond_FirstUseEver);
    ImGui::Begin("Myoshell");
    ImGui::PushItemWidth(170);
    if (session_.live()) livePanel();
    const StepTimings& t = session_.lastTimings();
    ImGui::Text("simulation %.0f steps/s   render %.0f FPS", session_.stepsPerSecond(), ImGui::GetIO().Framerate);
    ImGui::Text("step %.3f ms: muscles %.3f, springs %.3f, channels+sum %.3f", 1e3 * t.total, 1e3 * t.muscles,
                1e3 * t.springs, 1e3 * t.channels);
    if (ImGui::CollapsingHeader("Muscles", ImGuiTreeNodeFlags_DefaultOpen)) {
      ImGui::Checkbox("link left and right", &session_.linked);
      ImGui::SameLine();
      if (ImGui::Button("reset")) session_.resetSliders();
      for (int m = 0; m < session_.muscleCount(); ++m) {
        float a = static_cast<float>(session_.slider(m));
        if (ImGui::SliderFloat(session_.muscleName(m).c_str(), &a, static_cast<float>(session_.model().minActivation()),
                               1.0f, "%.2f"))
          session_.setSlider(m, a);
      }
    }
    if (session_.hasJaw() && ImGui::CollapsingHeader("Jaw", ImGuiTreeNodeFlags_DefaultOpen)) {
      JawPose jaw = session_.jawSlider();
      float open = static_cast<float>(jaw.openDeg), forward = static_cast<float>(jaw.forwardCm),
            lateral = static_cast<float>(jaw.lateralCm);
      bool moved = ImGui::SliderFloat("open (deg)", &open, static_cast<float>(kJawOpenMinDeg),
                                      static_cast<float>(kJawOpenMaxDeg), "%.1f");
      moved |= ImGui::SliderFloat("forward (cm)", &forward, static_cast<float>(kJawForwardMinCm),
                                  static_cast<float>(kJawForwardMaxCm), "%.2f");
      moved |= ImGui::SliderFloat("lateral (cm)", &lateral, static_cast<float>(-kJawLateralMaxCm),
                                  static_cast<float>(kJawLateralMaxCm), "%.2f");
      if (moved) session_.setJawSlider({open, forward, lateral});
      if (ImGui::Button("Blink")) {
        try {
          session_.blink();
        } catch (const InputError& e) {
          status_ = e.what();
        }
      }
    }
    if (ImGui::CollapsingHeader("Skin", ImGuiTreeNodeFlags_DefaultOpen)) {
      bool gravity = session_.gravity();
      if (session_.hasGravity() && ImGui::Checkbox("gravity", &gravity)) session_.setGravity(gravity);
      if (!session_.stiffnessRebuilds()) {  // thesis: scaled in place, live while dragging
        float s = static_cast<float>(session_.stiffnessScale());
        if (ImGui::SliderFloat("stiffness ×", &s, 0.1f, 10.0f, "%.2f", ImGuiSliderFlags_Logarithmic))
          session_.setStiffnessScale(std::max(s, 0.1f));
      } else {
        // Anatomical: each value is a rebuild of the skin, so only the value let go of is built,
        // on the next frame (this one shows the message first).
        if (!stiffnessDragged_ && pendingStiffness_ == 0.0) stiffnessEdit_ = static_cast<float>(session_.stiffnessScale());
        ImGui::SliderFloat("stiffness ×", &stiffnessEdit_, 0.1f, 10.0f, "%.2f", ImGuiSliderFlags_Logarithmic);
        stiffnessDragged_ = ImGui::IsItemActive();
        if (ImGui::IsItemDeactivatedAfterEdit() && std::abs(stiffnessEdit_ - session_.stiffnessScale()) > 1e-6) {
          pendingStiffness_ = std::max(stiffnessEdit_, 0.1f);
          status_ = fmt::format("rebuilding the skin at stiffness ×{:.2f}…", pendingStiffness_);
        }
      }
      float k = static_cast<float>(display_.dragStiffness);
      if (ImGui::SliderFloat("drag dyn/cm", &k, 100.0f, 20000.0f, "%.0f", ImGuiSliderFlags_Logarithmic)) display_.dragStiffness = k;
      ImGui::TextDisabled("Ctrl + left-drag on the skin pulls it");
    }
    if (ImGui::CollapsingHeader("Timeline", ImGuiTreeNodeFlags_DefaultOpen)) {
      if (ImGui::Button(session_.playing ? "pause" : "play")) {
        if (!session_.playing && session_.playhead() >= session_.duration()) session_.seek(0.0);
        session_.playing = !session_.playing;
      }
      ImGui::SameLine();
      float t = static_cast<float>(session_.playhead());
      if (ImGui::SliderFloat("s", &t, 0.0f, static_cast<float>(session_.duration()), "%.2f")) session_.seek(t);
      if (ImGui::Button("key sliders at playhead")) status_ = fmt::format("{} keys set at {:.2f} s", session_.setKeysAtPlayhead(), session_.playhead());
      pathButton("save scene", scenePath_, [&](const std::string& p) { session_.saveScene(p); });
      pathButton("export GLB", glbPath_, [&](const std::string& p) { session_.exportGlb(p); });
    }
    if (ImGui::CollapsingHeader("Display", ImGuiTreeNodeFlags_DefaultOpen)) {
      ImGui::Checkbox("muscles", &display_.muscles);
      ImGui::SameLine();
      ImGui::Checkbox("pins", &display_.pins);
      ImGui::SameLine();
      ImGui::Checkbox("wireframe", &display_.wireframe);
      if (session_.model().head().hasSkull()) {
        ImGui::SameLine();
        ImGui::Checkbox("skull", &display_.skull);
      }
      ImGui::Checkbox("ROI of", &display_.roi);
      ImGui::SameLine();
      if (session_.muscleCount() > 0 &&
          ImGui::BeginCombo("##roi", session_.muscleName(display_.selected).c_str())) {
        for (int m = 0; m < session_.muscleCount(); ++m)
          if (ImGui::Selectable(session_.muscleName(m).c_str(), m == display_.selected)) display_.selected = m;
        ImGui::EndCombo();
      }
      ImGui::Checkbox("displacement, cm up to", &display_.displacement);
      float scale = static_cast<float>(display_.displacementScale);
      if (ImGui::SliderFloat("##dscale", &scale, 0.05f, 5.0f, "%.2f", ImGuiSliderFlags_Logarithmic)) display_.displacementScale = scale;
      if (ImGui::Button("front")) display_.yaw = display_.pitch = 0;
      ImGui::SameLine();
      if (ImGui::Button("three-quarter")) display_.yaw = 35, display_.pitch = 0;
      ImGui::SameLine();
      if (ImGui::Button("profile")) display_.yaw = 90, display_.pitch = 0;
      ImGui::SameLine();
      if (ImGui::Button("screenshot (F12)")) saveScreenshot(fmt::format("myoshell_view_{:03d}.png", screenshots_++));
    }
    if (!status_.empty()) ImGui::TextWrapped("%s", status_.c_str());
    ImGui::PopItemWidth();
    ImGui::End();
  }

  // The live stream's status line (docs/live.md, "In the viewer") and the calibration.
  void livePanel() {
    const LiveStatus st = session_.liveStatus();
    const LiveCounters& c = st.counters;
    const std::string latency = st.latencySamples > 0 ? fmt::format("{:.1f} ms", st.latencyMs) : "-";
    ImGui::Text("live %s :%d   %.0f packets/s   latency %s", toString(st.protocol), st.port, st.packetsPerSecond,
                latency.c_str());
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("a frame's arrival to its positions ready, median over the last second");
    ImGui::Text("dropped %ld, malformed %ld, superseded %ld", c.dropped, c.malformed, c.superseded);
    if (ImGui::Button("Calibrate neutral")) session_.calibrateNeutral(kCalibrateSeconds);
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("hold a neutral face: the next %.0f s are subtracted as the resting weights", kCalibrateSeconds);
    ImGui::SameLine();
    if (st.calibrating)
      ImGui::TextColored(ImVec4(1.0f, 0.8f, 0.3f, 1.0f), "calibrating: hold a neutral face");
    else if (c.frames == 0)
      ImGui::TextDisabled("waiting for the first frame");
    else if (st.liveness < 1.0)
      ImGui::TextColored(ImVec4(1.0f, 0.5f, 0.4f, 1.0f), "stream silent: easing to neutral");
    else
      ImGui::Text("receiving");
    ImGui::Separator();
  }
  static constexpr double kCalibrateSeconds = 1.0;

  template <class Action>
  void pathButton(const char* label, std::string& path, Action action) {
    char buffer[512];
    std::snprintf(buffer, sizeof buffer, "%s", path.c_str());
    ImGui::PushID(label);
    if (ImGui::InputText("##path", buffer, sizeof buffer)) path = buffer;
    ImGui::SameLine();
    if (ImGui::Button(label)) {
      try {
        action(path);
        status_ = std::string(label) + ": wrote " + path;
      } catch (const std::exception& e) {
        status_ = e.what();
      }
    }
    ImGui::PopID();
  }

  void draw() {
    const FaceSystem& model = session_.model();
    FaceOverlays overlays;
    overlays.muscles = display_.muscles;
    overlays.skull = display_.skull;
    overlays.displacement = display_.displacement;
    overlays.displacementScale = display_.displacementScale;
    overlays.roi = display_.roi && session_.muscleCount() > 0 && session_.thesisModel();  // ROIs: thesis only
    overlays.pins = display_.pins;
    overlays.wireframe = display_.wireframe;
    overlays.grabVertex = session_.grabbing() ? session_.grabbedVertex() : -1;
    const VecX roi = overlays.roi ? roiWeights(*session_.thesisModel(), display_.selected) : VecX();
    const FaceScene scene = faceScene(model, faceFrameState(session_.simulator(), overlays), camera_, faceWidth_,
                                      height_, overlays, &roi);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    drawFaceScene(*renderer_, scene, faceX_, 0);
  }

  // Runs the script's commands in order; each error names the script's file and line.
  void runScript(const std::vector<ScriptCommand>& script) {
    for (const ScriptCommand& cmd : script) {
      try {
        execute(cmd);
        for (const std::string& w : session_.takeWarnings())
          fmt::print(stderr, "myoshell-view: warning: {}:{}: {}\n", options_.script, cmd.line, w);
      } catch (const InputError& e) {
        throw InputError(e.message(), options_.script, cmd.line);
      } catch (const NumericalError& e) {
        throw NumericalError(fmt::format("{}:{}: {}", options_.script, cmd.line, e.what()));
      }
    }
  }

  void execute(const ScriptCommand& c) {
    const auto on = [&](size_t i) { return c.args.at(i) == "on"; };
    if (c.verb == "set") session_.setSlider(c.args[0], c.number(1));
    else if (c.verb == "jaw") session_.setJawSlider({c.number(0), c.number(1), c.number(2)});
    else if (c.verb == "blink") session_.blink();
    else if (c.verb == "link") session_.linked = on(0);
    else if (c.verb == "gravity") session_.setGravity(on(0));
    else if (c.verb == "stiffness") {
      if (session_.stiffnessRebuilds())
        fmt::print(stderr, "myoshell-view: {}:{}: stiffness {}: rebuilding the anatomical skin at E = {:g} dyn/cm²…\n",
                   options_.script, c.line, c.args[0], c.number(0) * session_.scene().anatomical.skinYoungModulus /
                                                           session_.stiffnessScale());
      const double seconds = session_.setStiffnessScale(c.number(0));
      if (session_.stiffnessRebuilds()) fmt::print(stderr, "myoshell-view: skin rebuilt in {:.1f} s\n", seconds);
    }
    else if (c.verb == "play") session_.playing = true;
    else if (c.verb == "pause") session_.playing = false;
    else if (c.verb == "seek") session_.seek(c.number(0));
    else if (c.verb == "reset") session_.resetSliders();
    else if (c.verb == "grab") session_.grab(vertexOf(c.args[0]));
    else if (c.verb == "pull") session_.pull(Vec3(c.number(0), c.number(1), c.number(2)));
    else if (c.verb == "release") session_.release();
    else if (c.verb == "probe") {
      const int v = vertexOf(c.args[0]);
      const MatX3& u = session_.simulator().skinDisplacement();
      if (v < 0 || v >= u.rows())
        throw InputError(fmt::format("'probe': vertex {} is outside [0, {})", v, u.rows()));
      const Vec3 d = u.row(v);
      fmt::print("probe {} (vertex {}): displacement {:.6g} {:.6g} {:.6g} cm, |u| {:.6g} cm\n", c.args[0], v, d.x(),
                 d.y(), d.z(), d.norm());
    }
    else if (c.verb == "sliders") {
      for (int m = 0; m < session_.muscleCount(); ++m)
        fmt::print("slider {} {:.6g}\n", session_.muscleName(m), session_.slider(m));
      if (session_.hasJaw()) {
        const JawPose& j = session_.jawSlider();
        fmt::print("jaw {:.6g} {:.6g} {:.6g}\n", j.openDeg, j.forwardCm, j.lateralCm);
      }
    }
    else if (c.verb == "calibrate") session_.calibrateNeutral(c.number(0));
    else if (c.verb == "key") session_.setKeysAtPlayhead();
    else if (c.verb == "save") session_.saveScene(c.args[0]);
    else if (c.verb == "export") session_.exportGlb(c.args[0]);
    else if (c.verb == "screenshot") frame(0.0, c.args[0]);
    else if (c.verb == "advance") {
      const double frames = c.number(0);
      if (frames < 0 || frames != std::floor(frames)) throw InputError("'advance' takes a whole number of frames ≥ 0");
      for (int f = 0; f < static_cast<int>(frames); ++f) frame(1.0 / session_.scene().fps);
    } else if (c.verb == "show") {
      bool* flag = c.args[0] == "muscles"        ? &display_.muscles
                   : c.args[0] == "roi"          ? &display_.roi
                   : c.args[0] == "displacement" ? &display_.displacement
                   : c.args[0] == "pins"         ? &display_.pins
                   : c.args[0] == "wireframe"    ? &display_.wireframe
                   : c.args[0] == "skull"        ? &display_.skull
                   : c.args[0] == "panel"        ? &display_.panel
                                                 : nullptr;
      if (!flag) throw InputError("'show': unknown layer '" + c.args[0] + "' (use muscles, roi, displacement, pins, wireframe, skull or panel)");
      *flag = on(1);
    } else if (c.verb == "select") display_.selected = session_.model().muscleIndex(c.args[0]);
    else if (c.verb == "view") {
      const ViewPreset v = parseView(c.args[0]);  // the views of `run` and `render`
      display_.pitch = 0;
      display_.yaw = v == ViewPreset::front ? 0 : v == ViewPreset::threeQuarter ? 35 : v == ViewPreset::profile ? 90 : 180;
    } else if (c.verb == "orbit") {
      display_.yaw = c.number(0);
      display_.pitch = std::clamp(c.number(1), -85.0, 85.0);
    } else if (c.verb == "zoom") {
      if (!(c.number(0) > 0)) throw InputError("'zoom' needs a factor > 0");
      display_.zoom = c.number(0);
    }
  }

  int vertexOf(const std::string& word) const {
    if (!word.empty() && std::all_of(word.begin(), word.end(), [](char ch) { return std::isdigit(static_cast<unsigned char>(ch)); }))
      return std::stoi(word);
    return session_.model().head().landmarks.vertex(word);
  }
};

}  // namespace

void checkDisplay() {
  glfwSetErrorCallback([](int, const char* description) { glfwLastError() = description; });
  if (!glfwInit()) throw RenderError(noWindowMessage());
  glfwTerminate();
}

ViewerStats runViewer(ViewerSession& session, const ViewerOptions& options) {
  ViewerApp app(session, options);
  app.run();
  ViewerStats stats = app.stats();
  stats.stepsPerSecond = session.stepsPerSecond();
  return stats;
}

}  // namespace myo::viewer
