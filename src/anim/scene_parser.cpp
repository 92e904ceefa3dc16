#include "myoshell/anim/scene_parser.h"

#include <algorithm>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>

#include "myoshell/core/doc_reader.h"
#include "myoshell/core/errors.h"
#include "myoshell/head/head_checks.h"
#include "myoshell/head/jaw.h"

namespace myo {

namespace fs = std::filesystem;

namespace {

void readMaterial(DocReader& r, ShellMaterial& m) {
  m.kA = r.number("k_a", m.kA);
  r.requireAtLeast("k_a", m.kA, 0.0);
  m.kL = r.number("k_l", m.kL);
  r.requireAtLeast("k_l", m.kL, 0.0);
  m.kB = r.number("k_b", m.kB);
  r.requireAtLeast("k_b", m.kB, 0.0);
  m.density = r.number("density", m.density);
  r.requireAbove("density", m.density, 0.0);
  m.thickness = r.number("thickness", m.thickness);
  r.requireAbove("thickness", m.thickness, 0.0);
}

std::string numberText(double v) {
  std::ostringstream os;
  os << v;
  return os.str();
}

// A track: a list of keys {t, value, interp}; value is a number (or a 3-vector for drags).
// `rangeNote` (optional) follows a range error: activations name the model whose range it is.
template <class Value>
Track<Value> readTrack(const DocReader& owner, const YAML::Node& list, const std::string& path, double lo, double hi,
                       const std::string& rangeNote = "") {
  if (!list.IsSequence()) owner.failAt(list, path, "must be a list of keys {t, value, interp}");
  std::vector<Keyframe<Value>> keys;
  for (size_t i = 0; i < list.size(); ++i) {
    DocReader k(list[i], owner.file(), path + "[" + std::to_string(i) + "]");
    Keyframe<Value> key;
    key.time = k.requiredNumber("t");
    k.requireAtLeast("t", key.time, 0.0);
    if constexpr (std::is_same_v<Value, double>) {
      key.value = k.requiredNumber("value");
      if (rangeNote.empty()) k.requireWithin("value", key.value, lo, hi);
      else if (!(key.value >= lo && key.value <= hi))
        k.fail("value", "must lie in [" + numberText(lo) + ", " + numberText(hi) + "] " + rangeNote + " (got " +
                            numberText(key.value) + ")");
    } else {
      k.node("value");
      key.value = k.vec3("value", Vec3::Zero());
    }
    // `interp` shapes the segment from this key to the next: the last key starts none.
    if (i + 1 == list.size() && k.has("interp"))
      k.fail("interp", "a track's last key starts no segment ('interp' says how the value goes from its key to the "
                       "next; put it on the key that starts the eased segment)");
    const std::string interp = k.string("interp", "linear");
    try {
      key.interpolation = interpolationFromString(interp);
    } catch (const InputError& e) {
      k.fail("interp", e.message());
    }
    k.finish();
    if (!keys.empty() && !(key.time > keys.back().time))
      k.fail("t", "key times must increase (" + std::to_string(key.time) + " s after " +
                       std::to_string(keys.back().time) + " s)");
    keys.push_back(key);
  }
  return Track<Value>(std::move(keys), path);
}

// A key one model reads is an error under the other, naming the model and where it is written.
void onlyFor(FaceModelKind model, const SceneDesc& scene, const DocReader& r, const std::string& key) {
  if (scene.modelKind == model || !r.has(key)) return;
  const std::string other = toString(scene.modelKind);
  r.fail(key, std::string("only \"model\": \"") + toString(model) + "\" uses it (this scene's model is " + other +
                  (scene.modelKind == FaceModelKind::Anatomical ? ", the default" : "") + ")");
}

// Frames closer together than one step, or a scene shorter than one step, would show a face that
// does not move (ScenePlayer steps whole dt's between frames). The error sits at the key the user
// wrote: `fps` / `duration`, or `numerics.dt` when only that one was written.
void checkFramesAgainstStep(const DocReader& root, const SceneDesc& scene) {
  const double dt = scene.model.dt;
  YAML::Node dtNode;
  if (root.has("numerics")) {
    const YAML::Node numerics = root.self()["numerics"];
    if (numerics.IsMap() && numerics["dt"].IsDefined()) dtNode = numerics["dt"];
  }
  const bool dtWritten = dtNode.IsDefined() && !dtNode.IsNull();
  const std::string dtText = "numerics.dt = " + numberText(dt) + " s";
  auto failAtWritten = [&](const std::string& key, const std::string& what) {
    if (root.has(key) || !dtWritten) root.fail(key, what);
    root.failAt(dtNode, "numerics.dt", what);
  };
  if (scene.fps * dt > 1.0 + 1e-9)
    failAtWritten("fps", "fps = " + numberText(scene.fps) + " is above 1/dt = " + numberText(1.0 / dt) + " (" + dtText +
                             "): frames closer than one step would repeat; lower fps or dt");
  if (scene.duration < dt * (1.0 - 1e-9))
    failAtWritten("duration", "duration = " + numberText(scene.duration) + " s is shorter than one step (" + dtText +
                                  "): the face would not move; lengthen duration or lower dt");
}

// The scene key `performance` (docs/performance_input.md, "In a scene").
void readPerformanceDesc(DocReader r, PerformanceDesc& p) {
  p.file = r.requiredString("file");
  if (p.file.empty()) r.fail("file", "must name a performance file");
  if (r.has("input")) {
    try {
      p.read.input = performanceInputFromString(r.string("input", ""));
    } catch (const InputError& e) {
      r.fail("input", e.message());
    }
  }
  if (r.has("au_scale")) {
    p.read.auScale = r.number("au_scale", 1.0);
    r.requireAbove("au_scale", *p.read.auScale, 0.0);
  }
  p.read.face = r.integer("face", p.read.face);
  if (r.has("face")) r.requireAtLeast("face", p.read.face, 0);
  p.read.minConfidence = r.number("min_confidence", p.read.minConfidence);
  r.requireWithin("min_confidence", p.read.minConfidence, 0.0, 1.0);
  if (r.has("input_fps")) {
    p.read.inputFps = r.number("input_fps", 30.0);
    r.requireAbove("input_fps", *p.read.inputFps, 0.0);
  }
  p.map = r.string("map", "");
  p.start = r.number("start", p.start);
  r.requireAtLeast("start", p.start, 0.0);
  if (r.has("end")) {
    p.end = r.number("end", p.end);
    r.requireAbove("end", p.end, p.start);
  }
  if (r.has("interpolation")) {
    const std::string between = r.string("interpolation", "linear");
    if (between == "linear") p.interpolation = Interpolation::Linear;
    else if (between == "step") p.interpolation = Interpolation::Step;
    else r.fail("interpolation", "must be \"linear\" or \"step\" (got \"" + between + "\")");
  }
  if (r.has("filter")) {
    DocReader f = r.child("filter");
    p.filter.enabled = f.boolean("enabled", p.filter.enabled);
    p.filter.minCutoff = f.number("min_cutoff", p.filter.minCutoff);
    f.requireAbove("min_cutoff", p.filter.minCutoff, 0.0);
    p.filter.beta = f.number("beta", p.filter.beta);
    f.requireAtLeast("beta", p.filter.beta, 0.0);
    p.filter.derivativeCutoff = f.number("d_cutoff", p.filter.derivativeCutoff);
    f.requireAbove("d_cutoff", p.filter.derivativeCutoff, 0.0);
    f.finish();
  }
  r.finish();
}

SourceLocation locationOf(const YAML::Node& n) {
  const YAML::Mark m = n.Mark();
  if (m.line < 0 || m.pos < 0) return {};
  return {m.line + 1, m.column + 1};
}

[[noreturn]] void failAtKey(const SceneDesc& scene, const std::string& keyPath, const std::string& what) {
  const auto it = scene.locations.find(keyPath);
  const SourceLocation at = it != scene.locations.end() ? it->second : SourceLocation{};
  throw InputError("key '" + keyPath + "': " + what, scene.path, at.line, at.column);
}

// Every timeline muscle must be one of `muscles` (the scene's, after selection).
void checkTimelineMuscles(const SceneDesc& scene, const std::vector<MuscleDef>& muscles) {
  for (const auto& activation : scene.activations) {
    const std::string& name = activation.first;  // a plain reference: clang 14 cannot capture a structured binding
    const bool known = std::any_of(muscles.begin(), muscles.end(), [&](const MuscleDef& d) { return d.name == name; });
    if (known) continue;
    const std::string hint = scene.muscles.empty() ? "" : " (it is not in 'muscles.use' nor in 'muscles.extra')";
    failAtKey(scene, "timeline.activations." + name, "the scene has no muscle '" + name + "'" + hint);
  }
}

}  // namespace

std::vector<MuscleDef> sceneMuscles(const SceneDesc& scene, const std::vector<MuscleDef>& library) {
  std::vector<MuscleDef> muscles;
  if (scene.muscles.empty()) {
    muscles = library;
  } else {
    for (size_t i = 0; i < scene.muscles.size(); ++i) {
      const std::string& name = scene.muscles[i];
      auto it = std::find_if(library.begin(), library.end(), [&](const MuscleDef& d) { return d.name == name; });
      if (it == library.end()) {
        std::string known;
        for (const auto& d : library) known += (known.empty() ? "" : ", ") + d.name;
        const auto at = scene.locations.find("muscles.use[" + std::to_string(i) + "]");
        const SourceLocation loc = at != scene.locations.end() ? at->second : SourceLocation{};
        throw InputError("key 'muscles.use': unknown muscle '" + name + "' (the library has: " + known + ")",
                         scene.path, loc.line, loc.column);
      }
      muscles.push_back(*it);
    }
  }
  for (const MuscleDef& d : scene.extraMuscles) muscles.push_back(d);
  checkTimelineMuscles(scene, muscles);
  return muscles;
}

SceneDesc parseScene(const std::string& text, const std::string& path) {
  DocReader root(loadDocument(text, path), path);
  SceneDesc scene;
  scene.path = path;
  scene.name = root.string("name", fs::path(path).stem().string());
  // The name names the output files (DIR/NAME.glb, DIR/obj/NAME_0000.obj): it must stay in DIR.
  if (scene.name.find_first_of("/\\") != std::string::npos || scene.name.find("..") != std::string::npos)
    root.fail("name", "must not contain '/', '\\', or '..' (it names the output files inside --out)");

  const std::string modelName = root.string("model", "anatomical");
  if (modelName == "anatomical") scene.modelKind = FaceModelKind::Anatomical;
  else if (modelName == "thesis") scene.modelKind = FaceModelKind::Thesis;
  else root.fail("model", "must be \"anatomical\" or \"thesis\" (got \"" + modelName + "\")");
  const FaceModelKind thesis = FaceModelKind::Thesis, anatomical = FaceModelKind::Anatomical;
  const bool isThesis = scene.modelKind == thesis;
  scene.muscleLibrary = defaultMuscleLibrary(scene.modelKind);
  AnatomicalSettings& an = scene.anatomical;

  if (root.has("head")) {
    DocReader h = root.child("head");
    onlyFor(thesis, scene, h, "gravity_pins");
    scene.head.builtin = h.string("builtin", scene.head.builtin);
    scene.head.obj = h.string("obj", "");
    scene.head.landmarks = h.string("landmarks", "");
    scene.head.gravityPins = h.string("gravity_pins", "");
    scene.head.skull = h.string("skull", "");
    if (h.has("units")) {
      scene.head.unitsGiven = true;
      try {
        scene.head.units = parseLengthUnit(h.string("units", "cm"));
      } catch (const InputError& e) {
        h.fail("units", e.message());
      }
    }
    if (scene.head.obj.empty() && !scene.head.gravityPins.empty())
      h.fail("gravity_pins", "only a head OBJ takes a pin file (the built-in head has its own pins)");
    if (scene.head.obj.empty() && scene.head.units != LengthUnit::cm)
      h.fail("units", "applies to a head OBJ (head.obj); the built-in head is in cm");
    if (scene.head.obj.empty() && scene.head.builtin != "default")
      h.fail("builtin", "unknown built-in head '" + scene.head.builtin + "' (there is \"default\")");
    h.finish();
  }
  if (root.has("muscles")) {
    DocReader m = root.child("muscles");
    scene.muscleLibrary = m.string("library", scene.muscleLibrary);
    // "all" (the default; an empty list says the same) or a list of the library's names.
    if (m.has("use") && m.node("use").IsScalar()) {
      const std::string use = m.string("use", "all");
      if (use != "all") m.fail("use", "must be \"all\" or a list of muscle names (got \"" + use + "\")");
    } else {
      scene.muscles = m.strings("use");
    }
    onlyFor(anatomical, scene, m, "shortening");
    an.coupling.shortening = m.number("shortening", an.coupling.shortening);
    m.requireWithin("shortening", an.coupling.shortening, 0.0, 0.9);
    if (!(an.coupling.shortening > 0.0)) m.fail("shortening", "must be > 0 (got 0)");
    for (size_t i = 0; i < scene.muscles.size(); ++i)
      scene.locations["muscles.use[" + std::to_string(i) + "]"] = locationOf(m.node("use")[i]);
    if (m.has("extra")) {
      const YAML::Node extra = m.node("extra");
      if (!extra.IsSequence()) m.failAt(extra, m.keyPath("extra"), "must be a list of muscles");
      for (size_t i = 0; i < extra.size(); ++i) {
        DocReader r(extra[i], path, m.keyPath("extra") + "[" + std::to_string(i) + "]");
        // A muscle's keys that one model reads (a library file serves both models and is not checked).
        for (const char* key : {"contraction", "spring_stiffness", "roi_alpha"}) onlyFor(thesis, scene, r, key);
        onlyFor(anatomical, scene, r, "coupling");
        scene.extraMuscles.push_back(readMuscleDef(r));
      }
    }
    m.finish();
  }
  FaceModelSettings& s = scene.model;
  if (root.has("skin")) {
    DocReader r = root.child("skin");
    for (const char* key : {"k_a", "k_l", "k_b", "density"}) onlyFor(thesis, scene, r, key);
    onlyFor(anatomical, scene, r, "young_modulus");
    onlyFor(anatomical, scene, r, "attachment");
    scene.skinAttachment = r.string("attachment", "");
    if (r.has("attachment") && scene.skinAttachment.empty())
      r.fail("attachment", "must name a file of attachment overrides");
    an.skinYoungModulus = r.number("young_modulus", an.skinYoungModulus);
    r.requireAbove("young_modulus", an.skinYoungModulus, 0.0);
    readMaterial(r, s.skin);
    s.skinDampingMass = r.number("damping_mass", s.skinDampingMass);
    r.requireAtLeast("damping_mass", s.skinDampingMass, 0.0);
    s.skinDampingStiffness = r.number("damping_stiffness", s.skinDampingStiffness);
    r.requireAtLeast("damping_stiffness", s.skinDampingStiffness, 0.0);
    r.finish();
  }
  if (root.has("muscle_material")) {
    DocReader r = root.child("muscle_material");
    onlyFor(thesis, scene, r, "damping_ratio");
    readMaterial(r, isThesis ? s.muscle : an.coupling.muscle);
    s.muscleDampingRatio = r.number("damping_ratio", s.muscleDampingRatio);
    r.requireAtLeast("damping_ratio", s.muscleDampingRatio, 0.0);
    r.finish();
  }
  onlyFor(thesis, scene, root, "roi_alpha");
  onlyFor(thesis, scene, root, "springs");
  s.roiAlpha = root.number("roi_alpha", s.roiAlpha);
  root.requireAbove("roi_alpha", s.roiAlpha, 1.0);
  if (root.has("springs")) {
    DocReader r = root.child("springs");
    const std::string model = r.string("model", "thesis");
    if (model == "thesis") s.springModel = SpringModel::Thesis;
    else if (model == "displacement") s.springModel = SpringModel::Displacement;
    else r.fail("model", "must be \"thesis\" or \"displacement\" (got \"" + model + "\")");
    s.springStiffness = r.number("stiffness", s.springStiffness);
    r.requireAbove("stiffness", s.springStiffness, 0.0);
    r.finish();
  }
  if (root.has("gravity")) {
    DocReader r = root.child("gravity");
    s.gravity = r.boolean("enabled", s.gravity);
    s.gravityAcceleration = r.number("acceleration", s.gravityAcceleration);
    r.finish();
  }
  if (root.has("drags")) {
    const YAML::Node list = root.node("drags");
    if (!list.IsSequence()) root.failAt(list, "drags", "must be a list of drags");
    for (size_t i = 0; i < list.size(); ++i) {
      DocReader r(list[i], path, "drags[" + std::to_string(i) + "]");
      DragDesc d;
      d.name = r.requiredString("name");
      d.landmark = r.string("landmark", "");
      d.vertex = r.integer("vertex", -1);
      if (d.landmark.empty() == (d.vertex < 0)) r.fail("landmark", "give exactly one of 'landmark' and 'vertex'");
      d.radius = r.number("radius", d.radius);
      r.requireAbove("radius", d.radius, 0.0);
      onlyFor(thesis, scene, r, "pins");
      onlyFor(thesis, scene, r, "pin_landmarks");
      d.pins = r.string("pins", "");
      d.pinLandmarks = r.boolean("pin_landmarks", d.pinLandmarks);
      r.finish();
      for (const DragDesc& other : scene.drags)
        if (other.name == d.name) r.fail("name", "drag '" + d.name + "' is defined twice");
      scene.drags.push_back(d);
    }
  }
  if (root.has("numerics")) {
    DocReader r = root.child("numerics");
    for (const char* key : {"muscle_modes", "stepper", "precision"}) onlyFor(thesis, scene, r, key);
    s.dt = r.number("dt", s.dt);
    r.requireAbove("dt", s.dt, 0.0);
    s.skinModes = r.integer("skin_modes", s.skinModes);
    r.requireAtLeast("skin_modes", s.skinModes, 1);
    s.muscleModes = r.integer("muscle_modes", s.muscleModes);
    r.requireAtLeast("muscle_modes", s.muscleModes, 1);
    s.warping = r.boolean("warping", s.warping);
    an.warping = r.boolean("warping", an.warping);  // each model keeps its own default
    const std::string stepper = r.string("stepper", "exact");
    if (stepper == "exact") s.stepper = ModalStepper::Exact;
    else if (stepper == "semi-implicit") s.stepper = ModalStepper::SemiImplicit;
    else r.fail("stepper", "must be \"exact\" or \"semi-implicit\" (got \"" + stepper + "\")");
    // How the skin answers the activations (docs/live.md, "Lag"): the anatomical model's step only.
    onlyFor(anatomical, scene, r, "response");
    const std::string response = r.string("response", "dynamic");
    if (response == "dynamic") an.response = SkinResponse::Dynamic;
    else if (response == "follow") an.response = SkinResponse::Follow;
    else r.fail("response", "must be \"dynamic\" or \"follow\" (got \"" + response + "\")");
    const std::string precision = r.string("precision", "float");
    if (precision == "float") s.precision = ModalPrecision::Float;
    else if (precision == "double") s.precision = ModalPrecision::Double;
    else r.fail("precision", "must be \"float\" or \"double\" (got \"" + precision + "\")");
    r.finish();
  }
  onlyFor(anatomical, scene, root, "contact");
  if (root.has("contact")) {
    // The lids and lips kept out of the eyeballs, the teeth and each other (docs/mouth_contact.md).
    const std::string contact = root.string("contact", "on");
    if (contact == "on") an.contact = true;
    else if (contact == "off") an.contact = false;
    else root.fail("contact", "must be \"on\" or \"off\" (got \"" + contact + "\")");
  }
  onlyFor(anatomical, scene, root, "performance");
  if (root.has("performance")) {
    // The performance sets the scene's length and frame rate: a second one would contradict it.
    for (const char* key : {"duration", "fps"})
      if (root.has(key))
        root.fail(key, "comes from the performance (key 'performance'): its duration and frame rate are the scene's");
    readPerformanceDesc(root.child("performance"), scene.performance);
  }
  scene.duration = root.number("duration", scene.duration);
  root.requireAbove("duration", scene.duration, 0.0);
  scene.fps = root.number("fps", scene.fps);
  root.requireAbove("fps", scene.fps, 0.0);
  checkFramesAgainstStep(root, scene);

  if (root.has("timeline")) {
    DocReader t = root.child("timeline");
    if (t.has("activations")) {
      DocReader a = t.child("activations");
      for (auto it = a.self().begin(); it != a.self().end(); ++it) {
        const std::string muscle = a.asString(it->first, a.keyPath(it->first.Scalar()));
        scene.locations[a.keyPath(muscle)] = locationOf(it->first);
        scene.activations[muscle] =
            isThesis ? readTrack<double>(a, a.node(muscle), a.keyPath(muscle), -1.0, 1.0)
                     : readTrack<double>(a, a.node(muscle), a.keyPath(muscle), 0.0, 1.0,
                                         "under the anatomical model (relaxing, a < 0, needs \"model\": \"thesis\")");
      }
      a.finish();
    }
    if (t.has("gravity")) scene.gravity = readTrack<double>(t, t.node("gravity"), t.keyPath("gravity"), 0.0, 1e3);
    onlyFor(anatomical, scene, t, "head_pose");
    if (t.has("head_pose")) {
      const VectorTrack degrees = readTrack<Vec3>(t, t.node("head_pose"), t.keyPath("head_pose"), 0, 0);
      for (size_t i = 0; i < degrees.keys().size(); ++i)
        if (!degrees.keys()[i].value.allFinite())
          t.failAt(t.node("head_pose")[i], t.keyPath("head_pose") + "[" + std::to_string(i) + "]",
                   "[pitch, yaw, roll] must be finite degrees");
      scene.headPose = HeadPoseTrack(degrees.keys(), t.keyPath("head_pose"));
    }
    onlyFor(anatomical, scene, t, "jaw");
    if (t.has("jaw")) {
      DocReader j = t.child("jaw");
      const std::string note = "(the jaw's range, docs/jaw.md)";
      if (j.has("open"))
        scene.jawOpen = readTrack<double>(j, j.node("open"), j.keyPath("open"), kJawOpenMinDeg, kJawOpenMaxDeg,
                                          "degrees " + note);
      if (j.has("forward"))
        scene.jawForward = readTrack<double>(j, j.node("forward"), j.keyPath("forward"), kJawForwardMinCm,
                                             kJawForwardMaxCm, "cm " + note);
      if (j.has("lateral"))
        scene.jawLateral = readTrack<double>(j, j.node("lateral"), j.keyPath("lateral"), -kJawLateralMaxCm,
                                             kJawLateralMaxCm, "cm " + note);
      j.finish();
    }
    onlyFor(anatomical, scene, t, "gaze");
    if (t.has("gaze")) {
      DocReader g = t.child("gaze");
      const char* eyes[2] = {"right", "left"};
      for (size_t e = 0; e < 2; ++e)
        for (const bool pitch : {true, false}) {
          const std::string key = std::string(eyes[e]) + (pitch ? "_pitch" : "_yaw");
          if (!g.has(key)) continue;
          (pitch ? scene.gazePitch : scene.gazeYaw)[e] = readTrack<double>(
              g, g.node(key), g.keyPath(key), -kGazeMaxDeg, kGazeMaxDeg, "degrees (the eye's range, docs/eyelids.md)");
        }
      g.finish();
    }
    if (t.has("drags")) {
      DocReader d = t.child("drags");
      for (auto it = d.self().begin(); it != d.self().end(); ++it) {
        const std::string drag = d.asString(it->first, d.keyPath(it->first.Scalar()));
        bool known = false;
        for (const DragDesc& dd : scene.drags) known |= dd.name == drag;
        if (!known) d.failAt(it->first, d.keyPath(drag), "no drag of that name in 'drags'");
        scene.dragForces[drag] = readTrack<Vec3>(d, d.node(drag), d.keyPath(drag), 0, 0);
      }
      d.finish();
    }
    t.finish();
  }
  root.finish();
  s.validate();
  // The keys both models read, onto the anatomical settings.
  an.skinThickness = s.skin.thickness;
  an.dampingMass = s.skinDampingMass;
  an.dampingStiffness = s.skinDampingStiffness;
  an.skinModes = s.skinModes;
  an.dt = s.dt;
  an.gravity = s.gravityAcceleration;
  if (!isThesis) an.validate();
  // The muscle names: against the built-in library here; a library file is io's to read, so here
  // only the timeline against an explicit selection (io checks the rest: readSceneInputs).
  if (const std::vector<MuscleDef>* builtin = builtinMuscleLibrary(scene.muscleLibrary, scene.modelKind)) {
    sceneMuscles(scene, *builtin);
  } else if (!scene.muscles.empty()) {
    std::vector<MuscleDef> named(scene.muscles.size());
    for (size_t i = 0; i < named.size(); ++i) named[i].name = scene.muscles[i];
    for (const MuscleDef& d : scene.extraMuscles) named.push_back(d);
    checkTimelineMuscles(scene, named);
  }
  return scene;
}

namespace {
nlohmann::json materialJson(const ShellMaterial& m) {
  return {{"k_a", m.kA}, {"k_l", m.kL}, {"k_b", m.kB}, {"density", m.density}, {"thickness", m.thickness}};
}
nlohmann::json anchorJson(const MuscleAnchor& a) {
  return {{"landmark", a.landmark}, {"offset", {a.offset.x(), a.offset.y(), a.offset.z()}}, {"depth", a.depth}};
}
template <class Value>
nlohmann::json trackJson(const Track<Value>& track) {
  nlohmann::json keys = nlohmann::json::array();
  for (const auto& k : track.keys()) {
    nlohmann::json key = {{"t", k.time}};
    if (&k != &track.keys().back()) key["interp"] = toString(k.interpolation);  // the last key starts no segment
    if constexpr (std::is_same_v<Value, double>) key["value"] = k.value;
    else key["value"] = {k.value.x(), k.value.y(), k.value.z()};
    keys.push_back(key);
  }
  return keys;
}
}  // namespace

std::string sceneToJson(const SceneDesc& scene) {
  using nlohmann::json;
  const FaceModelSettings& s = scene.model;
  const bool thesis = scene.modelKind == FaceModelKind::Thesis;
  const AnatomicalSettings& an = scene.anatomical;
  json j;
  j["name"] = scene.name;
  j["model"] = toString(scene.modelKind);
  j["head"] = scene.head.obj.empty() ? json{{"builtin", scene.head.builtin}}
                                     : json{{"obj", scene.head.obj}, {"landmarks", scene.head.landmarks}};
  // No pin file: no key (the head's own pins, the rim and the landmarks, are meant; docs/heads.md).
  if (thesis && !scene.head.obj.empty() && !scene.head.gravityPins.empty())
    j["head"]["gravity_pins"] = scene.head.gravityPins;
  if (!scene.head.skull.empty()) j["head"]["skull"] = scene.head.skull;
  if (scene.head.units != LengthUnit::cm) j["head"]["units"] = lengthUnitName(scene.head.units);
  json extra = json::array();
  for (const MuscleDef& d : scene.extraMuscles) {
    json m = d.imported() ? json{{"name", d.name}, {"side", d.side}, {"facs", d.facs}, {"obj", d.obj},
                                 {"origin_nodes", d.originNodes}, {"central_nodes", d.centralNodes},
                                 {"insertion_nodes", d.insertionNodes}}
                          : json{{"name", d.name}, {"side", d.side}, {"facs", d.facs}, {"origin", anchorJson(d.origin)},
                                 {"insertion", anchorJson(d.insertion)}, {"width", d.width}, {"thickness", d.thickness},
                                 {"stations", d.stations}, {"ring_nodes", d.ringNodes}};
    if (thesis) {  // the keys only the thesis model reads (the parser refuses them under the other)
      m["contraction"] = d.contraction;
      m["spring_stiffness"] = d.springStiffness;
      m["roi_alpha"] = d.roiAlpha > 0 ? d.roiAlpha : s.roiAlpha;
    } else if (d.coupling) {
      const CouplingProfile& c = *d.coupling;
      m["coupling"] = {{"insertion_modulus", c.insertionModulus}, {"belly_modulus", c.bellyModulus},
                       {"origin_end", c.originEnd}, {"belly_start", c.bellyStart},
                       {"insertion_start", c.insertionStart}};
    }
    extra.push_back(m);
  }
  j["muscles"] = {{"library", scene.muscleLibrary},
                  {"use", scene.muscles.empty() ? json("all") : json(scene.muscles)},
                  {"extra", extra}};
  if (!thesis) {
    j["muscles"]["shortening"] = an.coupling.shortening;
    j["skin"] = {{"young_modulus", an.skinYoungModulus}, {"thickness", an.skinThickness},
                 {"damping_mass", an.dampingMass}, {"damping_stiffness", an.dampingStiffness}};
    if (!scene.skinAttachment.empty()) j["skin"]["attachment"] = scene.skinAttachment;
    j["muscle_material"] = materialJson(an.coupling.muscle);
    j["gravity"] = {{"enabled", s.gravity}, {"acceleration", an.gravity}};
    j["contact"] = an.contact ? "on" : "off";
    json drags = json::array();
    for (const DragDesc& d : scene.drags) {
      json dj = {{"name", d.name}, {"radius", d.radius}};
      if (d.landmark.empty()) dj["vertex"] = d.vertex;
      else dj["landmark"] = d.landmark;
      drags.push_back(dj);
    }
    j["drags"] = drags;
    j["numerics"] = {{"dt", an.dt},
                     {"skin_modes", an.skinModes},
                     {"warping", an.warping},
                     {"response", an.response == SkinResponse::Follow ? "follow" : "dynamic"}};
  } else {
    j["skin"] = materialJson(s.skin);
    j["skin"]["damping_mass"] = s.skinDampingMass;
    j["skin"]["damping_stiffness"] = s.skinDampingStiffness;
    j["muscle_material"] = materialJson(s.muscle);
    j["muscle_material"]["damping_ratio"] = s.muscleDampingRatio;
    j["roi_alpha"] = s.roiAlpha;
    j["springs"] = {{"model", s.springModel == SpringModel::Thesis ? "thesis" : "displacement"},
                    {"stiffness", s.springStiffness}};
    j["gravity"] = {{"enabled", s.gravity}, {"acceleration", s.gravityAcceleration}};
    json drags = json::array();
    for (const DragDesc& d : scene.drags) {
      json dj = {{"name", d.name}, {"radius", d.radius}, {"pins", d.pins}, {"pin_landmarks", d.pinLandmarks}};
      if (d.landmark.empty()) dj["vertex"] = d.vertex;
      else dj["landmark"] = d.landmark;
      drags.push_back(dj);
    }
    j["drags"] = drags;
    j["numerics"] = {{"dt", s.dt},
                     {"skin_modes", s.skinModes},
                     {"muscle_modes", s.muscleModes},
                     {"warping", s.warping},
                     {"stepper", s.stepper == ModalStepper::Exact ? "exact" : "semi-implicit"},
                     {"precision", s.precision == ModalPrecision::Float ? "float" : "double"}};
  }
  if (!scene.performance.file.empty()) {
    const PerformanceDesc& p = scene.performance;
    json perf = {{"file", p.file}, {"min_confidence", p.read.minConfidence}, {"face", p.read.face},
                 {"start", p.start},
                 {"filter", {{"enabled", p.filter.enabled}, {"min_cutoff", p.filter.minCutoff},
                             {"beta", p.filter.beta}, {"d_cutoff", p.filter.derivativeCutoff}}}};
    if (p.read.input) perf["input"] = toString(*p.read.input);
    if (p.read.auScale) perf["au_scale"] = *p.read.auScale;
    if (p.read.inputFps) perf["input_fps"] = *p.read.inputFps;
    if (!p.map.empty()) perf["map"] = p.map;
    if (p.end >= 0.0) perf["end"] = p.end;
    if (p.interpolation != Interpolation::Linear) perf["interpolation"] = toString(p.interpolation);
    if (p.read.face < 0) perf.erase("face");
    j["performance"] = perf;
  } else {
    j["duration"] = scene.duration;
    j["fps"] = scene.fps;
  }
  json timeline = json::object();
  json activations = json::object();
  for (const auto& [name, track] : scene.activations) activations[name] = trackJson(track);
  timeline["activations"] = activations;
  if (!scene.gravity.empty()) timeline["gravity"] = trackJson(scene.gravity);
  json dragTracks = json::object();
  for (const auto& [name, track] : scene.dragForces) dragTracks[name] = trackJson(track);
  timeline["drags"] = dragTracks;
  if (!scene.headPose.empty()) timeline["head_pose"] = trackJson(VectorTrack(scene.headPose.keys()));
  if (scene.hasJaw()) {
    json jaw = json::object();
    if (!scene.jawOpen.empty()) jaw["open"] = trackJson(scene.jawOpen);
    if (!scene.jawForward.empty()) jaw["forward"] = trackJson(scene.jawForward);
    if (!scene.jawLateral.empty()) jaw["lateral"] = trackJson(scene.jawLateral);
    timeline["jaw"] = jaw;
  }
  if (scene.hasGaze()) {
    json gaze = json::object();
    const char* eyes[2] = {"right", "left"};
    for (size_t e = 0; e < 2; ++e) {
      if (!scene.gazePitch[e].empty()) gaze[std::string(eyes[e]) + "_pitch"] = trackJson(scene.gazePitch[e]);
      if (!scene.gazeYaw[e].empty()) gaze[std::string(eyes[e]) + "_yaw"] = trackJson(scene.gazeYaw[e]);
    }
    timeline["gaze"] = gaze;
  }
  j["timeline"] = timeline;
  return j.dump(2) + "\n";
}

}  // namespace myo
