// The muscle libraries as documents (JSON or YAML through core/doc_reader.h) and the built-in ones
// embedded in the layer (assets/muscles/*.json): the readers, kept apart from the definitions
// (muscle_def.cpp) so the WebAssembly build takes the muscles without yaml-cpp (docs/web.md).
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <set>
#include <sstream>

#include "myoshell/core/check.h"
#include "myoshell/core/doc_reader.h"
#include "myoshell/core/errors.h"
#include "myoshell/muscles/muscle_def.h"
#include "thesis_muscles_data.h"

namespace myo {

namespace {
MuscleAnchor readAnchor(DocReader r) {
  MuscleAnchor a;
  a.landmark = r.requiredString("landmark");
  a.offset = r.vec3("offset", a.offset);
  a.depth = r.number("depth", a.depth);
  r.requireAbove("depth", a.depth, 0.0);
  r.finish();
  return a;
}

// A muscle's coupling profile: each field defaults to CouplingProfile's (the model's default
// profile); the order of the positions is checked here so the error points at the field.
CouplingProfile readCoupling(DocReader r, const std::string& muscle) {
  CouplingProfile p;
  const std::string in = " in muscle '" + muscle + "'";
  auto number = [&](const char* key, double& value) {
    value = r.number(key, value);
    if (!std::isfinite(value)) r.fail(key, "must be finite" + in);
  };
  number("insertion_modulus", p.insertionModulus);
  if (!(p.insertionModulus > 0)) r.fail("insertion_modulus", "must be > 0 dyn/cm² (got " + r.node("insertion_modulus").Scalar() + ")" + in);
  number("belly_modulus", p.bellyModulus);
  if (!(p.bellyModulus >= 0)) r.fail("belly_modulus", "must be ≥ 0 dyn/cm² (got " + r.node("belly_modulus").Scalar() + ")" + in);
  number("origin_end", p.originEnd);
  number("belly_start", p.bellyStart);
  number("insertion_start", p.insertionStart);
  auto text = [](double v) {
    std::ostringstream os;
    os << v;
    return os.str();
  };
  if (!(p.originEnd >= 0)) r.fail("origin_end", "must be ≥ 0 (got " + text(p.originEnd) + ")" + in);
  if (!(p.originEnd < p.bellyStart))
    r.fail(r.has("origin_end") ? "origin_end" : "belly_start",
           "origin_end (" + text(p.originEnd) + ") must be < belly_start (" + text(p.bellyStart) + ")" + in);
  if (!(p.bellyStart <= p.insertionStart))
    r.fail(r.has("insertion_start") ? "insertion_start" : "belly_start",
           "belly_start (" + text(p.bellyStart) + ") must be ≤ insertion_start (" + text(p.insertionStart) + ")" + in);
  if (!(p.insertionStart < 1.0)) r.fail("insertion_start", "must be < 1 (got " + text(p.insertionStart) + ")" + in);
  r.finish();
  return p;
}
}  // namespace

MuscleDef readMuscleDef(DocReader& r) {
  MuscleDef d;
  d.name = r.requiredString("name");
  d.side = r.string("side", "center");
  if (d.side != "right" && d.side != "left" && d.side != "center")
    r.fail("side", "must be \"right\", \"left\" or \"center\" (got \"" + d.side + "\")");
  d.facs = r.string("facs", "");
  r.string("note", "");  // free text
  d.obj = r.string("obj", "");
  if (d.imported()) {
    // Relative to the file that defines the muscle (a library or a scene).
    const std::filesystem::path file(r.file());
    if (std::filesystem::path(d.obj).is_relative() && !r.file().empty() && r.file().front() != '<')
      d.obj = (file.parent_path() / d.obj).string();
    auto ids = [&](const char* key) {
      std::vector<int> out;
      if (!r.has(key)) {
        r.integer(key, 0);  // marks the key as read
        return out;
      }
      const YAML::Node list = r.node(key);
      if (!list.IsSequence()) r.failAt(list, r.keyPath(key), "must be a list of vertex ids");
      for (size_t i = 0; i < list.size(); ++i) {
        const double v = r.asNumber(list[i], r.keyPath(key) + "[" + std::to_string(i) + "]");
        if (v < 0 || v != std::floor(v)) r.failAt(list[i], r.keyPath(key), "vertex ids must be integers ≥ 0");
        if (v > std::numeric_limits<int>::max())  // (the cast below would be undefined)
          r.failAt(list[i], r.keyPath(key), "vertex id " + list[i].Scalar() + " is too large");
        out.push_back(static_cast<int>(v));
      }
      return out;
    };
    d.originNodes = ids("origin_nodes");
    d.centralNodes = ids("central_nodes");
    d.insertionNodes = ids("insertion_nodes");
    if (d.originNodes.size() < 3) r.fail("origin_nodes", "an imported muscle needs at least 3 origin nodes");
    if (d.centralNodes.empty()) r.fail("central_nodes", "an imported muscle needs central nodes");
  } else if (r.has("ring")) {
    d.kind = MuscleKind::Ring;
    DocReader ring = r.child("ring");
    const YAML::Node path = ring.node("path");
    if (!path.IsSequence() || path.size() < 3) ring.failAt(path, ring.keyPath("path"), "must be a list of at least 3 anchors");
    for (size_t k = 0; k < path.size(); ++k)
      d.ring.path.push_back(readAnchor(DocReader(path[k], r.file(), ring.keyPath("path") + "[" + std::to_string(k) + "]")));
    d.ring.closed = ring.boolean("closed", false);
    const YAML::Node anchors = ring.node("anchors");
    if (!anchors.IsSequence() || anchors.size() != 2)
      ring.failAt(anchors, ring.keyPath("anchors"), "must be the two anchors the ring's centre lies between");
    for (size_t k = 0; k < 2; ++k)
      d.ring.anchors[k] = readAnchor(DocReader(anchors[k], r.file(), ring.keyPath("anchors") + "[" + std::to_string(k) + "]"));
    d.ring.shortening = ring.number("shortening", d.ring.shortening);
    if (!(d.ring.shortening > 0.0 && d.ring.shortening < 1.0)) ring.fail("shortening", "must lie in (0, 1)");
    d.ring.protrusion = ring.number("protrusion", d.ring.protrusion);
    ring.requireAtLeast("protrusion", d.ring.protrusion, 0.0);
    d.ring.centre = ring.number("centre", d.ring.centre);
    if (!(d.ring.centre >= 0.0 && d.ring.centre <= 1.0)) ring.fail("centre", "must lie in [0, 1]");
    d.ring.alongSkin = ring.boolean("along_skin", d.ring.alongSkin);
    d.ring.lipBody = ring.boolean("lip_body", d.ring.lipBody);
    if (ring.has("hoop")) {
      DocReader h = ring.child("hoop");
      MuscleDef::Ring::Hoop hoop;
      hoop.landmark = h.requiredString("landmark");
      hoop.offset = h.vec3("offset", hoop.offset);
      hoop.radius = h.number("radius", hoop.radius);
      h.requireAbove("radius", hoop.radius, 0.0);
      h.finish();
      if (d.ring.closed) ring.fail("hoop", "is for an open ring (a band held at its two ends)");
      d.ring.hoop = hoop;
    }
    ring.finish();
    if (r.has("origin") || r.has("insertion"))
      r.fail(r.has("origin") ? "origin" : "insertion", "a ring muscle has a path and anchors, not an origin and an insertion");
  } else {
    d.origin = readAnchor(r.child("origin"));
    d.insertion = readAnchor(r.child("insertion"));
  }
  d.width = r.number("width", d.width);
  r.requireAbove("width", d.width, 0.0);
  d.thickness = r.number("thickness", d.thickness);
  r.requireAbove("thickness", d.thickness, 0.0);
  d.stations = r.integer("stations", d.stations);
  r.requireAtLeast("stations", d.stations, 3);
  d.ringNodes = r.integer("ring_nodes", d.ringNodes);
  r.requireAtLeast("ring_nodes", d.ringNodes, 4);
  if (d.ringNodes % 2 != 0) r.fail("ring_nodes", "must be even (got " + std::to_string(d.ringNodes) + ")");
  d.contraction = r.number("contraction", d.contraction);
  if (!(d.contraction > 0.0 && d.contraction < 1.0)) r.fail("contraction", "must lie in (0, 1)");
  d.springStiffness = r.number("spring_stiffness", d.springStiffness);
  d.roiAlpha = r.number("roi_alpha", d.roiAlpha);
  if (r.has("roi_alpha")) r.requireAbove("roi_alpha", d.roiAlpha, 1.0);
  if (r.has("coupling")) d.coupling = readCoupling(r.child("coupling"), d.name);
  d.thickens = r.boolean("thickens", d.thickens);
  if (d.thickens && d.isRing()) r.fail("thickens", "is for linear muscles (a ring's bulge is its protrusion)");
  if (r.has("pushes")) {
    if (d.isRing() || d.imported()) r.fail("pushes", "is for generated linear muscles (an origin, an insertion and the anchor the tissue is pushed to)");
    d.pushes = readAnchor(r.child("pushes"));
  }
  if (r.has("continues_into")) {
    if (d.isRing() || d.imported()) r.fail("continues_into", "is for generated linear muscles (an origin, an insertion and the anchor where the muscle in series with it is fixed)");
    d.continuesInto = readAnchor(r.child("continues_into"));
  }
  r.finish();
  d.validate();
  return d;
}

std::vector<MuscleDef> readMuscleLibrary(const YAML::Node& root, const std::string& file) {
  DocReader top(root, file);
  top.string("note", "");
  const YAML::Node list = top.node("muscles");
  if (!list.IsSequence()) top.failAt(list, "muscles", "must be a list of muscles");
  top.finish();
  std::vector<MuscleDef> defs;
  std::set<std::string> names;
  for (size_t i = 0; i < list.size(); ++i) {
    DocReader r(list[i], file, "muscles[" + std::to_string(i) + "]");
    MuscleDef d = readMuscleDef(r);
    if (!names.insert(d.name).second) r.fail("name", "muscle '" + d.name + "' is defined twice");
    defs.push_back(std::move(d));
  }
  return defs;
}

std::vector<MuscleDef> parseMuscleDefs(const std::string& text, const std::string& name) {
  return readMuscleLibrary(loadDocument(text, name), name);
}

const std::string& thesisMuscleJson() {
  static const std::string text(detail::kThesisMusclesJson);
  return text;
}

const std::vector<MuscleDef>& thesisMuscleDefs() {
  static const std::vector<MuscleDef> defs =
      parseMuscleDefs(thesisMuscleJson(), "<embedded assets/muscles/thesis_muscles.json>");
  return defs;
}

namespace detail {
extern const char kFaceMusclesJson[];
}  // namespace detail

const std::vector<MuscleDef>& faceMuscleDefs() {
  static const std::vector<MuscleDef> defs =
      parseMuscleDefs(detail::kFaceMusclesJson, "<embedded assets/muscles/face_muscles.json>");
  return defs;
}

namespace {
// The whole face's entry of that name, or nullptr.
const MuscleDef* faceMuscleNamed(const std::string& name) {
  const std::vector<MuscleDef>& face = faceMuscleDefs();
  const auto it = std::find_if(face.begin(), face.end(), [&](const MuscleDef& d) { return d.name == name; });
  return it != face.end() ? &*it : nullptr;
}
}  // namespace

const std::vector<MuscleDef>& anatomicalEightDefs() {
  static const std::vector<MuscleDef> defs = [] {
    std::vector<MuscleDef> eight;
    for (const MuscleDef& thesis : thesisMuscleDefs()) {
      const MuscleDef* face = faceMuscleNamed(thesis.name);
      eight.push_back(face ? *face : thesis);
    }
    return eight;
  }();
  return defs;
}

const std::vector<MuscleDef>& anatomicalBuiltinDefs() {
  static const std::vector<MuscleDef> defs = [] {
    std::vector<MuscleDef> lib = anatomicalEightDefs();
    for (const char* ring : {"orbicularis_oris_upper", "orbicularis_oris_lower"}) {
      const MuscleDef* face = faceMuscleNamed(ring);
      MYO_CHECK(face, "face_muscles.json has no " << ring);
      lib.push_back(*face);
    }
    return lib;
  }();
  return defs;
}

const std::vector<MuscleDef>* builtinMuscleLibrary(const std::string& name, FaceModelKind model) {
  if (name == "builtin") return model == FaceModelKind::Anatomical ? &anatomicalBuiltinDefs() : &thesisMuscleDefs();
  if (name == "face") return &faceMuscleDefs();
  return nullptr;
}

}  // namespace myo
