// Viewer scripts (`myoshell-view --script FILE`): drive the viewer without a person, for CI and for
// the pictures in the docs. One command per line, words separated by spaces, '#' starts a comment:
//
//   set MUSCLE A          slider of MUSCLE to A in [−1, 1] (the link moves its mirror too)
//   link on|off           left/right link of the sliders
//   gravity on|off        stiffness S    (skin stiffness scale, S > 0)
//   play | pause | seek T | reset
//   grab V                grab skin vertex V (a number) or landmark V (a name) with the mouse drag
//   pull FX FY FZ         force on the grabbed spot, dyn        release
//   probe V               print vertex (or landmark) V's displacement, cm, to stdout
//   sliders               print every muscle's slider (and the jaw's) to stdout
//   calibrate S           live (--live): the next S seconds of the stream are the resting face
//   key                   keys at the playhead from the sliders
//   save PATH | export PATH (GLB) | screenshot PATH (PNG)
//   advance N             N frames of the scene's frame rate: simulate and draw each
//   show LAYER on|off     LAYER: muscles, roi, displacement, pins, wireframe, skull, panel
//   select MUSCLE         the muscle whose ROI is shown
//   view front|three-quarter|profile | orbit YAW PITCH (degrees) | zoom F (> 0, 2 = twice as close)
//
// Errors name the file and line.
#pragma once

#include <string>
#include <vector>

namespace myo::viewer {

struct ScriptCommand {
  int line = 0;                    // 1-based line in the file
  std::string verb;                // one of the commands above
  std::vector<std::string> args;   // its words, checked for count and number syntax
  double number(size_t i) const;   // args[i] as a number (checked at parse time)
};

// Reads and checks a script: unknown commands, wrong word counts, malformed numbers and on/off
// words are InputErrors naming `path` and the line. A missing file is an InputError naming it.
std::vector<ScriptCommand> parseViewerScript(const std::string& text, const std::string& path = "<script>");
std::vector<ScriptCommand> readViewerScript(const std::string& path);

}  // namespace myo::viewer
