// `myoshell pose [--head default|DIR|OBJ --landmarks F] [--units m|mm|cm] [--library face|builtin|FILE] [--scene S]
// [--set NAME=VALUE]… [--gravity on|off] [--head-pose P,Y,R] [--jaw OPEN[,FORWARD[,LATERAL]]]
// [--contact on|off] [--out SHAPE.obj] [--cache DIR] [--json]`:
// the settled shape of the anatomical face under fixed activations and gravity — the static
// equilibrium of its reduced system (AnatomicalSkin::settle; docs/anatomical_model.md), linear or
// warped as the model's settings say — written in the head's own vertex order and units: a head read
// from an OBJ as a copy of that file with its vertex positions replaced (faces, UVs, groups as written).
//
// Without --scene the face is the anatomical model's defaults on the given head (a scene with only a
// head). With --scene it is that scene's face (head, muscles, settings, drags registered but not
// pulled); its timeline is not played. The head options and --scene exclude each other: a scene names
// its own head (key `head`), and a second head would leave its drag vertices meaningless.
// --jaw opens the jaw (degrees), protrudes and shifts it (cm; head/jaw.h, docs/jaw.md): the settled
// displacement is the residual, relative to the jawed rest, and turns with the blended jaw rotation.
// --contact off settles and places without contact (no penalty forces, no projection out of the
// eyeballs and teeth; docs/mouth_contact.md): the shape that passes through, exactly linear in the loads.
// A thesis scene is refused: its face is a sum of channels stepped in time, with no static solve here.
// Every argument is checked before the model is built (~10 s): bad input costs no wait.
#include <fmt/core.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "job_report.h"
#include "command.h"
#include "common_options.h"
#include "head_landmarks.h"
#include "resources.h"
#include "myoshell/anatomy/anatomical_face.h"
#include "myoshell/core/errors.h"
#include "myoshell/core/timer.h"
#include "myoshell/head/head_checks.h"
#include "myoshell/io/head_files.h"
#include "myoshell/io/obj_writer.h"
#include "myoshell/io/output_paths.h"
#include "myoshell/io/scene_face.h"
#include "myoshell/muscles/muscle_def.h"

namespace myo::cli {
namespace {

namespace fs = std::filesystem;

struct PoseArgs {
  HeadOptions head;
  std::string library = defaultMuscleLibrary();  // --library: the muscles without --scene
  CLI::Option* libraryOption = nullptr;
  std::string scene;
  std::vector<std::string> sets;  // NAME=VALUE, in the order given
  std::string gravity;            // "on", "off", or "" (on; a scene's own switch with --scene)
  std::string headPose = "0,0,0";
  std::string jaw;                // OPEN[,FORWARD[,LATERAL]], "" = closed
  std::string contact;            // "on", "off", or "" (on; a scene's own switch with --scene)
  std::string out;
  std::string cacheDir;           // --cache; "" = the default (resources.h)
  bool json = false;
};

// The whole text as a finite number, or nothing ("abc", "1x", "nan", "").
bool parseNumber(const std::string& text, double& value) {
  if (text.empty()) return false;
  char* end = nullptr;
  value = std::strtod(text.c_str(), &end);
  return end == text.c_str() + text.size() && std::isfinite(value);
}

// P,Y,R in degrees: exactly three finite numbers.
Vec3 parseHeadPose(const std::string& text) {
  std::vector<std::string> parts(1);
  for (char c : text) {
    if (c == ',') parts.emplace_back();
    else parts.back() += c;
  }
  Vec3 pose;
  const std::string expected = "--head-pose '" + text + "': expected three angles P,Y,R in degrees (pitch, yaw, roll)";
  if (parts.size() != 3) throw InputError(expected + ", got " + std::to_string(parts.size()));
  for (int i = 0; i < 3; ++i)
    if (!parseNumber(parts[static_cast<size_t>(i)], pose(i)))
      throw InputError(expected + ": '" + parts[static_cast<size_t>(i)] + "' is not a number");
  return pose;
}

// OPEN_DEG[,FORWARD_CM[,LATERAL_CM]]: one to three finite numbers within the jaw's ranges.
JawPose parseJaw(const std::string& text) {
  JawPose pose;
  if (text.empty()) return pose;
  std::vector<std::string> parts(1);
  for (char c : text) {
    if (c == ',') parts.emplace_back();
    else parts.back() += c;
  }
  const std::string expected = "--jaw '" + text + "': expected OPEN_DEG[,FORWARD_CM[,LATERAL_CM]]";
  if (parts.size() > 3) throw InputError(expected + ", got " + std::to_string(parts.size()) + " values");
  double* fields[3] = {&pose.openDeg, &pose.forwardCm, &pose.lateralCm};
  for (size_t i = 0; i < parts.size(); ++i)
    if (!parseNumber(parts[i], *fields[i])) throw InputError(expected + ": '" + parts[i] + "' is not a number");
  validateJawPose(pose, "--jaw");
  return pose;
}

struct Setting {
  std::string name;
  double value = 0.0;
};

// --set NAME=VALUE, syntax only (names and ranges need the model).
std::vector<Setting> parseSets(const std::vector<std::string>& sets) {
  std::vector<Setting> out;
  for (const std::string& s : sets) {
    const size_t eq = s.find('=');
    if (eq == std::string::npos || eq == 0) throw InputError("--set '" + s + "': expected NAME=VALUE");
    Setting st;
    st.name = s.substr(0, eq);
    const std::string value = s.substr(eq + 1);
    if (!parseNumber(value, st.value)) throw InputError("--set " + s + ": '" + value + "' is not a number");
    out.push_back(st);
  }
  return out;
}

// The scene to settle: the given scene file, or the anatomical defaults on the given head.
SceneDesc poseScene(const PoseArgs& a) {
  if (!a.scene.empty()) {
    if (a.head.anyGiven())
      throw InputError("--head, --landmarks and --units choose the head without --scene; the scene names its own "
                       "head (keys head.obj, head.landmarks, head.units)");
    if (a.libraryOption && a.libraryOption->count() > 0)
      throw InputError("--library chooses the muscles without --scene; the scene names its own (key muscles.library)");
    SceneDesc scene = readScene(a.scene);
    resolveSceneLandmarks(scene, a.cacheDir);
    if (scene.modelKind != FaceModelKind::Anatomical)
      throw InputError("pose settles the anatomical model; this scene's model is " +
                           std::string(toString(scene.modelKind)) + " (play it with `myoshell run`)",
                       a.scene);
    return scene;
  }
  const HeadFiles files = headFiles(a.head);
  SceneDesc scene;
  scene.name = "pose";
  scene.head.obj = files.obj;
  scene.head.landmarks = files.landmarks;
  scene.head.units = files.unit;
  scene.muscleLibrary = sceneMuscleLibrary(a.library);
  return scene;
}

// The activations, one per muscle of the model in its order: every --set name one of the muscles,
// every value in [0, 1] (the anatomical model), no muscle set twice.
VecX activations(const std::vector<Setting>& sets, const std::vector<MuscleDef>& muscles) {
  VecX a = VecX::Zero(static_cast<Eigen::Index>(muscles.size()));
  std::vector<bool> given(muscles.size(), false);
  for (const Setting& s : sets) {
    size_t m = 0;
    while (m < muscles.size() && muscles[m].name != s.name) ++m;
    if (m == muscles.size()) {
      std::string names;
      for (const MuscleDef& d : muscles) names += (names.empty() ? "" : ", ") + d.name;
      throw InputError("--set: unknown muscle '" + s.name + "' (the anatomical model's muscles: " + names + ")");
    }
    if (given[m]) throw InputError("--set: muscle '" + s.name + "' is set twice");
    if (!(s.value >= 0.0 && s.value <= 1.0))
      throw InputError(fmt::format("--set {}={}: an activation must lie in [0, 1] under the anatomical model",
                                   s.name, s.value));
    given[m] = true;
    a(static_cast<Eigen::Index>(m)) = s.value;
  }
  return a;
}

int runPose(const PoseArgs& a) {
  const Stopwatch total;
  // Arguments first, then the scene and the head (read and checked), then the model (~10 s).
  if (!a.gravity.empty() && a.gravity != "on" && a.gravity != "off")
    throw InputError("--gravity: '" + a.gravity + "' is neither on nor off");
  if (!a.contact.empty() && a.contact != "on" && a.contact != "off")
    throw InputError("--contact: '" + a.contact + "' is neither on nor off");
  const Vec3 headPose = parseHeadPose(a.headPose);
  const JawPose jaw = parseJaw(a.jaw);
  const std::vector<Setting> sets = parseSets(a.sets);
  checkOutputFile(a.out, "--out", "OBJ file");
  SceneDesc scene = poseScene(a);
  if (!a.contact.empty()) scene.anatomical.contact = a.contact == "on";
  const SceneInputs inputs = readSceneInputs(scene);
  const VecX act = activations(sets, inputs.muscles);
  if (!jaw.isZero() && inputs.head.landmarks.multipie68.size() != 68)
    throw InputError("--jaw: this head has no jaw: its landmarks have no 68-point jaw line (docs/jaw.md)",
                     inputs.head.landmarks.sourcePath);
  const bool gravity = a.gravity.empty() ? inputs.settings.gravity : a.gravity == "on";

  const Stopwatch buildClock;
  const auto cache = openBasisCache(a.cacheDir);
  const std::shared_ptr<const FaceSystem> system = buildSceneFace(scene, cache.get());
  const auto* face = dynamic_cast<const AnatomicalFace*>(system.get());
  if (!face) throw CheckError("pose: the scene did not build an anatomical face");
  const double buildSeconds = buildClock.seconds();
  const AnatomicalSkin& skin = face->skin();
  const Head& head = skin.head();

  // Gravity as the playing face reads it (AnatomicalSimulator): upright it is exactly the rest
  // gravity (no load); turned, gravityForPose; off, the rest gravity whatever the pose.
  SkinLoads loads;
  loads.activations = act;
  loads.drags.assign(static_cast<size_t>(skin.dragCount()), Vec3::Zero());
  loads.gravity = gravity && !headPose.isZero() ? gravityForPose(head.frame(), headPose, skin.settings().gravity)
                                                : skin.restGravity();
  const Stopwatch settleClock;
  const bool warped = skin.settings().warping;
  loads.jaw = jaw;
  loads.contact = skin.settings().contact;  // the penalty forces (when the head has proxies)
  const SettledSkin settled = skin.settle(loads, warped);
  const double settleSeconds = settleClock.seconds();
  if (!settled.converged || !settled.u.allFinite())
    throw NumericalError(fmt::format("pose: the static solve did not converge (residual {:.3g} after {} "
                                     "iterations)",
                                     settled.residual, settled.iterations));

  // The shape: rest + u, or with the jaw the jawed rest + u turned with it (head/jaw.h), then the
  // lids and the eyeball contact (anatomy/eyelids.h).
  MatX3 positions;
  const ContactReport contact = face->placeSkin(settled.u, jaw, act, positions);
  Eigen::Index peakVertex = 0;
  const double peak = (positions - head.mesh.V).rowwise().norm().maxCoeff(&peakVertex);
  if (!a.out.empty()) {
    // Back in the head file's unit: positions / (cm per unit); in cm the division is exact.
    // A head read from a file is written as a copy of that file with new positions (its seam UVs,
    // quads, groups kept); the built-in head as its mesh.
    const MatX3 shape = positions / centimetresPer(scene.head.units);
    if (scene.head.obj.empty() || !writeObjLikeFile(a.out, head.mesh.sourcePath, shape))
      writeObj(a.out, head.mesh, &shape);
  }
  const double seconds = total.seconds();

  if (a.json) {
    nlohmann::ordered_json j;
    j["model"] = "anatomical";
    j["head"] = head.name;
    j["units"] = lengthUnitName(scene.head.units);
    j["vertices"] = head.mesh.vertexCount();
    j["activations"] = nlohmann::ordered_json::object();
    for (int m = 0; m < face->muscleCount(); ++m) j["activations"][face->muscleName(m)] = act(m);
    j["gravity"] = gravity ? "on" : "off";
    j["head_pose_deg"] = {headPose.x(), headPose.y(), headPose.z()};
    j["gravity_cm_s2"] = {loads.gravity.x(), loads.gravity.y(), loads.gravity.z()};
    if (jaw.isZero()) {
      j["jaw"] = nullptr;
    } else {
      const JawRig& rig = *face->jawRig();
      nlohmann::ordered_json jj;
      jj["open_deg"] = jaw.openDeg;
      jj["forward_cm"] = jaw.forwardCm;
      jj["lateral_cm"] = jaw.lateralCm;
      jj["pivot_cm"] = {rig.pivot.x(), rig.pivot.y(), rig.pivot.z()};
      jj["axis"] = {rig.axis.x(), rig.axis.y(), rig.axis.z()};
      jj["jaw_weighted_vertices"] = (rig.weights.array() > 0.0).count();
      jj["max_residual_cm"] = settled.u.rowwise().norm().maxCoeff();
      j["jaw"] = jj;
    }
    if (const LidRig* lids = face->lidRig()) {
      const LidPose lp = face->lidPose(act);
      nlohmann::ordered_json lj;
      for (int eye = 0; eye < 2; ++eye) {
        const EyeLids& e = lids->eyes[static_cast<size_t>(eye)];
        lj[e.side] = {{"close", lp.close[static_cast<size_t>(eye)]},
                      {"raise", lp.raise[static_cast<size_t>(eye)]},
                      {"gap_rest_cm", lidGap(*lids, eye, head.mesh.V)},
                      {"gap_cm", lidGap(*lids, eye, positions)},
                      {"eyeball_centre_cm", {e.centre.x(), e.centre.y(), e.centre.z()}},
                      {"eyeball_radius_cm", e.radius},
                      {"contact_radius_cm", e.contactRadius}};
      }
      j["lids"] = lj;
    } else {
      j["lids"] = nullptr;
    }
    if (const MouthContact* mouth = face->mouthContact()) {
      j["mouth"] = {{"teeth_shrink", mouth->shrink},
                    {"tested_vertices", mouth->vertices.size()},
                    {"lip_pairs", mouth->lipPairs.size()}};
    } else {
      j["mouth"] = nullptr;
    }
    j["contact"] = {{"max_penetration_before_cm", contact.maxPenetrationBefore},
                    {"max_penetration_after_cm", contact.maxPenetrationAfter},
                    {"projected_vertices", contact.projected},
                    {"enabled", skin.settings().contact},
                    {"penalty_iterations", settled.contactIterations},
                    {"stiffness_per_mass_s2", skin.settings().contactStiffness},
                    {"basis_patterns", skin.contactPatternCount()}};
    j["warped"] = warped;
    j["iterations"] = settled.iterations;
    j["max_displacement_cm"] = peak;
    j["max_displacement_vertex"] = static_cast<int>(peakVertex);
    j["out"] = a.out.empty() ? nlohmann::ordered_json() : nlohmann::ordered_json(a.out);
    j["build_seconds"] = buildSeconds;
    j["settle_seconds"] = settleSeconds;
    j["seconds"] = seconds;
    printJsonReport(j);
    return kExitOk;
  }
  std::string set;
  for (const Setting& s : sets) set += fmt::format("{}{}={}", set.empty() ? "" : ", ", s.name, s.value);
  fmt::print("pose of {} ({} muscles{}, gravity {}{}{}): max displacement {:.4f} cm at vertex {} ({:.1f} s)\n",
             head.name, face->muscleCount(), set.empty() ? std::string(", none active") : ": " + set, gravity ? "on" : "off",
             gravity && !headPose.isZero()
                 ? fmt::format(", head pose {:g},{:g},{:g}°", headPose.x(), headPose.y(), headPose.z())
                 : std::string(),
             jaw.isZero() ? std::string()
                          : fmt::format(", jaw {:g}° {:g} cm forward {:g} cm lateral", jaw.openDeg, jaw.forwardCm,
                                        jaw.lateralCm),
             peak, peakVertex, seconds);
  if (!a.out.empty()) fmt::print("wrote {}\n", a.out);
  return kExitOk;
}

static CommandRegistrar registerPose("pose", [](CLI::App& app) -> std::function<int()> {
  auto args = std::make_shared<PoseArgs>();
  CLI::App* sub = app.add_subcommand(
      "pose", "Settle the anatomical face under fixed activations and gravity (its static equilibrium) and "
              "write the shape as OBJ in the head's vertex order and units");
  addHeadOptions(*sub, args->head);
  addLibraryOption(*sub, args->library);
  args->libraryOption = sub->get_option("--library");
  sub->add_option("--scene", args->scene, "a scene file: its head, muscles and settings (not with the head options)");
  sub->add_option("--set", args->sets, "NAME=VALUE: a muscle's activation in [0, 1] (repeatable)")
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  sub->add_option("--gravity", args->gravity, "on or off (default on; with --scene, the scene's)");
  sub->add_option("--contact", args->contact, "on or off: the lids and lips kept out of the eyeballs, teeth and each "
                                              "other by penalty forces and projection (default on; with --scene, the scene's)");
  sub->add_option("--head-pose", args->headPose, "P,Y,R: pitch, yaw, roll in degrees about the face frame's x, y, "
                                                  "z (face-down: 90,0,0; default upright)");
  sub->add_option("--jaw", args->jaw, "OPEN_DEG[,FORWARD_CM[,LATERAL_CM]]: the jaw's opening (degrees, [0, 40]), "
                                      "protrusion ([-0.5, 1.5] cm) and lateral shift ([-1.5, 1.5] cm, + subject's left)");
  sub->add_option("--out", args->out, "write the settled shape as OBJ (its folder must exist)");
  addCacheOption(*sub, args->cacheDir);
  addJsonFlag(*sub, args->json);
  addThreadsOption(*sub);
  return [args] {
    if (args->scene.empty()) resolveHeadLandmarks(args->head, args->cacheDir);
    return runPose(*args);
  };
});

}  // namespace
}  // namespace myo::cli
