// The viewer's window: GLFW + OpenGL 3.3 core + Dear ImGui around a ViewerSession. Draws the face
// with the shared GlRenderer (include/myoshell/gl/gl_renderer.h), takes the mouse (orbit, pan,
// zoom, Ctrl+drag to pull the skin) and runs scripts (viewer_script.h).
#pragma once

#include <optional>
#include <string>

#include "viewer_script.h"
#include "viewer_session.h"

namespace myo::viewer {

struct ViewerOptions {
  int width = 1280, height = 800;     // window size, screen pixels
  std::string script;                 // --script FILE: run it, then exit (unless stay)
  std::string screenshot;             // --screenshot PATH: draw `frames` frames, save, exit
  int frames = 30;
  bool stay = false;                  // keep the window open after the script
  // Multisamples per pixel of the window; −1 (auto): 4 on a GPU, none on a software rasterizer
  // (llvmpipe), where 4× costs about 40% of the frame rate (docs/PERFORMANCE.md).
  int samples = -1;
};

// Throws RenderError (the same message runViewer would give) when no window system can be reached,
// so the viewer fails at once, before building the face.
void checkDisplay();

// What a run measured: frames drawn and the wall time they took (input, panel, simulation, drawing,
// buffer swap), and the simulation's steps per second (ViewerSession::stepsPerSecond).
struct ViewerStats {
  int frames = 0;
  double seconds = 0.0;
  double stepsPerSecond = 0.0;
  double framesPerSecond() const { return seconds > 0.0 ? frames / seconds : 0.0; }
};

// Opens the window and runs until it is closed (or the script / screenshot is done). Throws
// RenderError when no window can be opened (no display), InputError for a bad script.
ViewerStats runViewer(ViewerSession& session, const ViewerOptions& options);

}  // namespace myo::viewer
