// `myoshell bench [--json] [--seconds S] [--runs R] [--heads default,ict] [--rows ID,…]`: the
// thesis's performance tables (Tables 2–4) re-measured on the scenes of scenes/thesis/, on the
// default head and the ICT head, beside the thesis's FPS; plus the full-space reference solver's
// time for one implicit-Euler step of the whole skin (docs/PERFORMANCE.md).
//
// Each row: a scene file, optionally only some of its muscles, and a window [t0, t1) of its
// timeline. The model is built once (bases from the cache), then the window is played in a loop
// (ScenePlayer::restart at its start, then ScenePlayer::step: the scene's timeline applied before
// every step, exactly as `myoshell run` does) — first once as warm-up, then in R timed runs of S/R seconds each; a row
// reports the median of the runs' steps per second. Table 2 rows ("muscle only") count only the
// muscle phase of the step (StepTimings::muscles, the thesis's muscle deformation without skin);
// every other row counts whole steps (muscles + springs + skin channels).
//
// Rows `thesis_full` and `anatomical_full` (scenes/bench/, the folder beside --scenes): all eight
// muscles + gravity + one drag with each model (`model: thesis` and `model: anatomical`), side by
// side on each head. Besides steps/s they report the cold precompute (built into an empty basis
// cache of their own), the cached start (built again from it) and the mean phases of a step
// (StepTimings: muscles, springs / force assembly, skin channels) and `read_us`, what an output frame
// pays besides its steps (one skinPositions after a step). Row `whole_face` does the same for
// the anatomical model with the whole face's 40 muscles, 37 of them driven (scenes/bench/whole_face.json);
// `whole_face_follow` the same scene with the follow response (whole_face_follow.json).
//
// Every row also reports, beside steps/s (docs/PERFORMANCE.md, "Ratios"):
//   floor_ratio     its step time over the time to stream once, in this process, the basis data
//                   its step reads when it touches every free vertex: each integrator's stored Φ
//                   (and Ψ when warping) rows in their own precision (ModalWarpingIntegrator::
//                   streamBasis) — the skin's for whole-step rows, the muscles' for muscle-phase
//                   rows; median of 9 passes. Below 1: the step skipped work (idle channels; the
//                   anatomical model with linear modes reads no basis row in a step: its forces
//                   are reduced once and u = Φq is paid when positions are read, `read_us`).
//   reference_ratio its step time over one implicit-Euler step of the full-space reference solver
//                   (verify/reference_solver.h) under the same loads: the world force on the skin
//                   at the end of the row's window, the same pins, masses, damping and (anatomical)
//                   attachment and coupling stiffness, from rest; median of --reference-steps.
//                   null (with reference_note) for muscle-phase rows, rows whose load is zero at
//                   the window's end, and with --no-reference.
// --diagnostics: the thesis channels' load participation (a factorisation per channel; else null).
#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <sstream>
#include <thread>

#include <unistd.h>

#include "job_report.h"
#include "command.h"
#include "common_options.h"
#include "option_checks.h"
#include "myoshell/anatomy/anatomical_face.h"
#include "myoshell/anim/scene_player.h"
#include "myoshell/core/errors.h"
#include "myoshell/core/timer.h"
#include "myoshell/io/basis_cache_file.h"
#include "myoshell/io/head_files.h"
#include "myoshell/io/scene_face.h"
#include "myoshell/thesis/face_model.h"
#include "myoshell/thesis/simulator.h"
#include "myoshell/verify/reference_solver.h"
#include "resources.h"

namespace myo::cli {
namespace {

namespace fs = std::filesystem;

struct BenchOptions {
  bool json = false;
  int threads = 1;
  double seconds = 1.0;    // timed seconds per row (split over `runs`)
  int runs = 5;
  std::string scenesDir;   // --scenes; "" = the shipped scenes/thesis (resources.h)
  std::string cacheDir;    // --cache; "" = the default basis cache (resources.h)
  std::string dataDir;     // --data; "" = $MYOSHELL_DATA or the build tree's ../shared/data
  std::string heads = "default,ict";
  std::string rows;        // comma-separated row ids; empty = all
  bool reference = true;
  int referenceSteps = 2;
  bool diagnostics = false;  // measure each thesis channel's load participation
};

// One row of the thesis's Tables 2–4.
struct BenchRow {
  std::string table;              // "2", "3", "4"
  std::string id;                 // stable id, e.g. "t3_zygomaticus_right"
  std::string label;              // as the thesis's column says
  std::string scene;              // file in the scenes folder
  std::vector<std::string> use;   // only these muscles of the scene (empty = all of them)
  double t0 = 0.0, t1 = 1.0;      // timeline window played in a loop, s
  bool muscleOnly = false;        // time only the muscle phase (Table 2)
  double thesisFps = 0.0;         // the thesis's number
  std::string folder = "thesis";  // "thesis": --scenes; "bench": scenes/bench beside it
};

// The two models side by side: 8 muscles + gravity + one drag, [0, 1) s of scenes/bench/*; and the
// anatomical model with the whole face's 40 muscles, 37 of them driven (issue 16).
std::vector<BenchRow> fullRows() {
  std::vector<BenchRow> r;
  r.push_back({"full", "thesis_full", "8 muscles + gravity + drag, model: thesis", "full_thesis.json", {}, 0.0, 1.0,
               false, 0, "bench"});
  r.push_back({"full", "anatomical_full", "8 muscles + gravity + drag, model: anatomical", "full_anatomical.json", {},
               0.0, 1.0, false, 0, "bench"});
  r.push_back({"full", "whole_face", "the whole face's 40 muscles (7 rings), 37 at 0.5 (the levators and the lower lip's marginal part rest) + gravity + drag, model: anatomical",
               "whole_face.json", {}, 0.0, 1.0, false, 0, "bench"});
  r.push_back({"full", "whole_face_follow", "whole_face with numerics.response: follow (docs/live.md, \"Lag\")",
               "whole_face_follow.json", {}, 0.0, 1.0, false, 0, "bench"});
  return r;
}

fs::path rowFolder(const BenchOptions& opt, const BenchRow& row) {
  if (row.folder == "thesis") return opt.scenesDir;
  return (fs::path(opt.scenesDir) / ".." / row.folder).lexically_normal();
}

std::vector<BenchRow> thesisRows() {
  const std::string zr = "zygomaticus_major_right", cr = "corrugator_supercilii_right",
                    lr = "depressor_labii_inferioris_right", ar = "depressor_anguli_oris_right";
  std::vector<BenchRow> r;
  // Table 2: muscle deformation alone (fig17_contract, only the named muscle, or all eight).
  r.push_back({"2", "t2_zygomaticus", "Zygomaticus major", "fig17_contract.json", {zr}, 0.0, 1.0, true, 220});
  r.push_back({"2", "t2_corrugator", "Corrugator supercilii", "fig17_contract.json", {cr}, 0.0, 1.0, true, 210});
  r.push_back({"2", "t2_depressor_labii", "Depressor labii inferioris", "fig17_contract.json", {lr}, 0.0, 1.0, true, 210});
  r.push_back({"2", "t2_depressor_anguli", "Depressor anguli oris", "fig17_contract.json", {ar}, 0.0, 1.0, true, 210});
  r.push_back({"2", "t2_all8", "All 8 muscles", "fig17_contract.json", {}, 0.0, 1.0, true, 200});
  // Table 3: skin by each type of muscle, right side only ([0, 1) s of fig18_*: only the right is
  // active) and both sides ([1, 2) s: both active).
  const auto side = [&](const std::string& key, const std::string& name, const std::string& scene, double fr,
                        double fb, std::vector<std::string> rightOnlyUse) {
    r.push_back({"3", "t3_" + key + "_right", name + ", right side only", scene, rightOnlyUse, 0.0, 1.0, false, fr});
    r.push_back({"3", "t3_" + key + "_both", name + ", both sides", scene, {}, 1.0, 2.0, false, fb});
  };
  side("zygomaticus", "Zygomaticus major", "fig18_zygomaticus.json", 95, 90, {});
  // fig20 moves both corrugators together: the right-only row keeps only the right muscle; its
  // contraction is [0, 1) s.
  r.push_back({"3", "t3_corrugator_right", "Corrugator supercilii, right side only", "fig20_corrugator.json", {cr}, 0.0,
               1.0, false, 97});
  r.push_back({"3", "t3_corrugator_both", "Corrugator supercilii, both sides", "fig20_corrugator.json", {}, 0.0, 1.0,
               false, 93});
  side("depressor_labii", "Depressor labii inferioris", "fig18_depressor_labii.json", 95, 90, {});
  side("depressor_anguli", "Depressor anguli oris", "fig18_depressor_anguli.json", 96, 96, {});
  // Table 4.
  r.push_back({"4", "t4_gravity", "Gravity", "fig22_gravity_sweep.json", {}, 0.0, 1.5, false, 85});
  r.push_back({"4", "t4_multiple_muscles", "Multiple muscles (zyg. major + dep. labii inf.)", "fig23_combined.json", {},
               0.0, 1.0, false, 82});
  r.push_back({"4", "t4_muscle_and_drag", "Muscle and external force (zyg. major + drag)", "fig25_drag.json", {}, 0.0,
               1.0, false, 73});
  r.push_back({"4", "t4_transition", "Transition (t0 to t3)", "fig26_transition.json", {}, 0.0, 1.8, false, 80});
  r.push_back({"4", "t4_scal_zygomaticus", "Scalability: zygomaticus major", "fig27_ict_head.json", {}, 0.0, 0.9, false,
               82});
  r.push_back({"4", "t4_scal_depressor_anguli", "Scalability: depressor anguli oris", "fig27_ict_head.json", {}, 0.9,
               1.8, false, 85});
  r.push_back({"4", "t4_scal_zyg_dli", "Scalability: zyg. major + dep. labii inf.", "fig27_ict_head.json", {}, 1.8, 2.4,
               false, 73});
  return r;
}

std::vector<std::string> splitList(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  std::string item;
  while (std::getline(ss, item, ','))
    if (!item.empty()) out.push_back(item);
  return out;
}


// fig27_ict_head.json with its head paths re-rooted at the data folder (resources.h).
// Without a data folder (an installed program, no --data) the paths stay as the scene wrote them.
SceneDesc ictHead(const BenchOptions& opt) {
  SceneDesc s = readScene((fs::path(opt.scenesDir) / "fig27_ict_head.json").string());
  if (const fs::path data = dataDir(opt.dataDir).dir; !data.empty()) useDataDir(s, data);
  return s;
}

// The row's scene on the given head: the ICT head is the one fig27_ict_head.json names (its paths
// are relative to the same folder), the default head the built-in one.
SceneDesc rowScene(const BenchOptions& opt, const BenchRow& row, const std::string& head) {
  SceneDesc scene = readScene((rowFolder(opt, row) / row.scene).string());
  if (head == "default") {
    scene.head = HeadDesc{};
  } else {
    scene.head = ictHead(opt).head;
    // The head's paths as fig27_ict_head.json meant them, whatever folder the row's scene is in.
    for (std::string* p : {&scene.head.obj, &scene.head.landmarks, &scene.head.gravityPins, &scene.head.skull})
      if (!p->empty() && fs::path(*p).is_relative()) *p = (fs::path(opt.scenesDir) / *p).string();
    if (scene.modelKind == FaceModelKind::Anatomical) scene.head.gravityPins.clear();  // held by its tissue
    // Drags name default-head vertex ids: move each to the ICT vertex nearest the same point of
    // the face frame (so the drag still grabs the right cheek).
    if (!scene.drags.empty()) {
      const Head from = loadDefaultHead(defaultHeadOptions(scene.modelKind));
      const Head to = loadHead(scene.head.obj, scene.head.landmarks, scene.head.gravityPins, scene.head.units);
      const FaceFrame ff = from.frame(), tf = to.frame();
      for (DragDesc& d : scene.drags) {
        if (d.vertex < 0) continue;
        const Vec3 target = tf.fromFrame(ff.toFrame(Vec3(from.mesh.V.row(d.vertex).transpose())));
        int best = 0;
        (to.mesh.V.rowwise() - target.transpose()).rowwise().squaredNorm().minCoeff(&best);
        d.vertex = best;
        d.radius *= tf.scale / ff.scale;
      }
    }
  }
  scene.model.measureLoadParticipation = opt.diagnostics;
  if (!row.use.empty()) {
    scene.muscles = row.use;
    for (auto it = scene.activations.begin(); it != scene.activations.end();)
      it = std::find(row.use.begin(), row.use.end(), it->first) == row.use.end() ? scene.activations.erase(it)
                                                                                 : std::next(it);
  }
  return scene;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n == 0 ? 0.0 : (n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]));
}

// Plays the window once; returns (steps, seconds counted). `phases`, when given, sums each whole
// step's StepTimings.
std::pair<long long, double> playWindow(ScenePlayer& player, const BenchRow& row, double budget,
                                        StepTimings* phases = nullptr) {
  const double dt = player.model().dt();
  long long steps = 0;
  double counted = 0.0;
  Stopwatch total;
  // Muscle-only rows count the muscle phase but stop on wall time: the phase is ~1 % of a step.
  while (row.muscleOnly ? total.seconds() < budget : counted < budget) {
    player.restart(row.t0);
    if (row.muscleOnly) {
      // At least one step, however short the budget (a slow build, a sanitizer).
      while (player.time() < row.t1 - 0.5 * dt && (steps == 0 || total.seconds() < budget)) {
        player.step();
        counted += player.simulator().lastTimings().muscles;
        ++steps;
      }
    } else {
      Stopwatch sw;
      long long n = 0;
      while (player.time() < row.t1 - 0.5 * dt) {
        player.step();
        ++n;
        if (phases) {
          const StepTimings& t = player.simulator().lastTimings();
          phases->muscles += t.muscles;
          phases->springs += t.springs;
          phases->channels += t.channels;
          phases->total += t.total;
        }
        if ((n & 15) == 0 && counted + sw.seconds() >= budget) break;
      }
      counted += sw.seconds();
      steps += n;
    }
  }
  return {steps, counted};
}

// The integrators whose stored bases a step of this row reads: the muscles' for a muscle-phase row,
// else the skin's (thesis: every channel, loaded or idle; anatomical: the one skin).
std::vector<const ModalWarpingIntegrator*> streamedIntegrators(const FaceStepper& sim, bool muscleOnly) {
  std::vector<const ModalWarpingIntegrator*> out;
  if (const auto* thesis = dynamic_cast<const Simulator*>(&sim)) {
    for (const auto& i : muscleOnly ? thesis->muscleIntegrators() : thesis->channelIntegrators()) out.push_back(&i);
  } else if (const auto* anatomical = dynamic_cast<const AnatomicalSimulator*>(&sim)) {
    if (!muscleOnly) out.push_back(&anatomical->stepper().integrator());
  }
  return out;
}

// The floor: seconds to stream the integrators' stored bases once (each value read once, summed),
// median of 9 passes after one warm-up; a pass repeats the stream often enough to last ~1 ms when
// the bases are small (a muscle's), and is divided by the repeats.
struct Floor {
  double seconds = 0.0;
  size_t bytes = 0;
};
Floor measureFloor(const std::vector<const ModalWarpingIntegrator*>& integrators) {
  Floor f;
  for (const auto* i : integrators) f.bytes += i->basisBytes();
  if (integrators.empty()) return f;
  volatile double sink = 0.0;
  const auto pass = [&](int repeats) {
    Stopwatch sw;
    for (int r = 0; r < repeats; ++r)
      for (const auto* i : integrators) sink = sink + i->streamBasis();
    return sw.seconds() / repeats;
  };
  const double first = pass(1);
  const int repeats = static_cast<int>(std::clamp(1e-3 / std::max(first, 1e-9), 1.0, 1e5));
  std::vector<double> passes;
  for (int p = 0; p < 9; ++p) passes.push_back(pass(repeats));
  f.seconds = median(passes);
  return f;
}

// What an output frame pays besides its steps: one skinPositions right after a step, median of 9
// (anatomical, linear modes: u = Φq is computed there, not in the step).
double readSeconds(ScenePlayer& player) {
  MatX3 out;
  std::vector<double> secs;
  player.restart(0.0);
  for (int k = 0; k < 9; ++k) {
    player.step();
    Stopwatch sw;
    player.simulator().skinPositions(out);
    secs.push_back(sw.seconds());
  }
  return median(secs);
}

// One full-space reference step (verify/reference_solver.h) under the loads the row's window ends
// with, from rest: the median over --reference-steps steps of their wall time, or a note saying why
// there is none. Leaves the player at the window's end.
struct ReferenceStep {
  std::optional<double> seconds;
  std::string note;
  int newtonIterations = 0;
};
ReferenceStep measureReference(const BenchOptions& opt, const BenchRow& row, ScenePlayer& player) {
  ReferenceStep r;
  if (!opt.reference) return r.note = "--no-reference", r;
  if (row.muscleOnly) return r.note = "muscle-phase row: the skin is not timed, so no skin reference", r;
  const double dt = player.model().dt();
  player.restart(row.t0);
  while (player.time() < row.t1 - 0.5 * dt) player.step();
  MatX3 F;
  std::optional<ImplicitReference> ref;
  if (const auto* thesis = dynamic_cast<const Simulator*>(&player.simulator())) {
    const FaceModel& m = thesis->model();
    F = thesis->skinLoad();
    ref.emplace(m.skin(), m.head().gravityPins, m.settings().skinDampingMass, m.settings().skinDampingStiffness);
  } else if (const auto* anatomical = dynamic_cast<const AnatomicalSimulator*>(&player.simulator())) {
    const auto& face = dynamic_cast<const AnatomicalFace&>(anatomical->face());
    const AnatomicalSkin& skin = face.skin();
    F = skin.worldLoad(anatomical->loads());
    ref.emplace(skin.shell(), std::vector<int>{}, skin.settings().dampingMass, skin.settings().dampingStiffness,
                ImplicitScheme::Euler, ReferenceOptions{}, ReferenceExtras{skin.extraStiffness(), skin.vertexMass()});
  } else {
    return r.note = "no full-space reference for this model", r;
  }
  if (!(F.squaredNorm() > 0.0)) return r.note = "no load on the skin at the window's end", r;
  std::vector<double> secs;
  for (int k = 0; k < opt.referenceSteps; ++k) {
    Stopwatch sw;
    ref->step(dt, F);
    secs.push_back(sw.seconds());
    r.newtonIterations += ref->lastNewtonIterations();
  }
  r.seconds = median(secs);
  return r;
}

// floor_* and reference_* of a row whose median step time is `stepUs` (µs).
void addRatios(nlohmann::json& j, const BenchOptions& opt, const BenchRow& row, ScenePlayer& player, double stepUs) {
  const Floor floor = measureFloor(streamedIntegrators(player.simulator(), row.muscleOnly));
  j["floor_bytes"] = floor.bytes;
  j["floor_us"] = 1e6 * floor.seconds;
  j["floor_ratio"] = floor.seconds > 0 ? nlohmann::json(stepUs / (1e6 * floor.seconds)) : nlohmann::json();
  const ReferenceStep ref = measureReference(opt, row, player);
  if (ref.seconds) {
    j["reference_step_us"] = 1e6 * *ref.seconds;
    j["reference_ratio"] = stepUs / (1e6 * *ref.seconds);
    j["reference_newton_iterations_per_step"] = static_cast<double>(ref.newtonIterations) / opt.referenceSteps;
  } else {
    j["reference_step_us"] = nullptr;
    j["reference_ratio"] = nullptr;
    j["reference_note"] = ref.note;
  }
}

std::string ratioText(const nlohmann::json& v, const char* format) {
  return v.is_null() ? std::string("null") : fmt::format(fmt::runtime(format), v.get<double>());
}

nlohmann::json benchRow(const BenchOptions& opt, const BenchRow& row, const std::string& head, BasisCache& cache) {
  const SceneDesc scene = rowScene(opt, row, head);
  Stopwatch build;
  const auto model = buildThesisFace(scene, &cache);
  const double buildSeconds = build.seconds();
  ScenePlayer player(scene, model);
  // Warm-up: the window once (caches, branch predictors, page faults).
  playWindow(player, row, 0.05);
  std::vector<double> rates, stepUs;
  const double budget = opt.seconds / opt.runs;
  for (int r = 0; r < opt.runs; ++r) {
    const auto [steps, secs] = playWindow(player, row, budget);
    rates.push_back(steps / std::max(secs, 1e-12));
    stepUs.push_back(1e6 * secs / std::max<long long>(steps, 1));
  }
  const double sps = median(rates);
  nlohmann::json j;
  j["table"] = row.table;
  j["id"] = row.id;
  j["label"] = row.label;
  j["head"] = head;
  j["scene"] = row.scene;
  j["window_s"] = {row.t0, row.t1};
  j["timed"] = row.muscleOnly ? "muscle phase" : "whole step";
  j["dt"] = model->settings().dt;
  j["skin_vertices"] = model->skin().vertexCount();
  j["d"] = model->settings().skinModes;
  j["muscles"] = static_cast<int>(model->muscles().size());
  j["precompute_seconds"] = buildSeconds;
  j["cache_hits"] = model->cacheHits();
  j["runs_steps_per_second"] = rates;
  j["steps_per_second"] = sps;
  j["step_us"] = median(stepUs);
  j["thesis_fps"] = row.thesisFps;
  j["ratio"] = sps / row.thesisFps;
  j["meets_10x"] = sps >= 10.0 * row.thesisFps;
  j["realtime_factor"] = sps * model->settings().dt;  // simulated seconds per wall second
  nlohmann::json ch = nlohmann::json::array();
  for (const SkinChannel& c : model->channels())
    ch.push_back({{"name", c.name},
                  {"free_vertices", c.basis->freeCount()},
                  {"modes", c.basis->modeCount()},
                  {"load_participation",
                   c.loadParticipation >= 0 ? nlohmann::json(c.loadParticipation) : nlohmann::json()}});
  j["channels"] = ch;
  addRatios(j, opt, row, player, j["step_us"].get<double>());
  return j;
}

// A row of the two models side by side: cold precompute into an empty cache of its own, cached start
// from it, then steps/s as benchRow, with the mean phases of a step.
nlohmann::json benchFullRow(const BenchOptions& opt, const BenchRow& row, const std::string& head) {
  const SceneDesc scene = rowScene(opt, row, head);
  const fs::path dir = fs::temp_directory_path() / fmt::format("myoshell_bench_{}_{}_{}", ::getpid(), row.id, head);
  std::error_code ec;
  fs::remove_all(dir, ec);
  double cold = 0.0, cached = 0.0;
  int coldHits = 0;
  std::shared_ptr<const FaceSystem> model;
  {
    FileBasisCache fresh(dir);
    Stopwatch sw;
    coldHits = buildSceneFace(scene, &fresh)->cacheHits();
    cold = sw.seconds();
    sw = Stopwatch();
    model = buildSceneFace(scene, &fresh);
    cached = sw.seconds();
  }
  fs::remove_all(dir, ec);
  ScenePlayer player(scene, model);
  playWindow(player, row, 0.05);
  std::vector<double> rates, stepUs;
  StepTimings phases;
  long long counted = 0;
  const double budget = opt.seconds / opt.runs;
  for (int r = 0; r < opt.runs; ++r) {
    const auto [steps, secs] = playWindow(player, row, budget, &phases);
    rates.push_back(steps / std::max(secs, 1e-12));
    stepUs.push_back(1e6 * secs / std::max<long long>(steps, 1));
    counted += steps;
  }
  const double perStep = 1e6 / static_cast<double>(std::max<long long>(counted, 1));
  nlohmann::json j;
  j["table"] = row.table;
  j["id"] = row.id;
  j["label"] = row.label;
  j["head"] = head;
  j["scene"] = "bench/" + row.scene;
  j["model"] = toString(model->kind());
  j["window_s"] = {row.t0, row.t1};
  j["timed"] = "whole step";
  j["dt"] = model->dt();
  j["skin_vertices"] = model->head().mesh.vertexCount();
  j["muscles"] = model->muscleCount();
  j["drags"] = static_cast<int>(model->drags().size());
  j["gravity"] = model->hasGravity();
  nlohmann::json ch = nlohmann::json::array();
  if (const auto* thesis = dynamic_cast<const FaceModel*>(model.get())) {
    j["d"] = thesis->settings().skinModes;
    for (const SkinChannel& c : thesis->channels())
      ch.push_back({{"name", c.name}, {"free_vertices", c.basis->freeCount()}, {"modes", c.basis->modeCount()}});
  } else if (const auto* anatomical = dynamic_cast<const AnatomicalFace*>(model.get())) {
    const auto basis = anatomical->skin().basis();
    j["d"] = anatomical->skin().settings().skinModes;
    ch.push_back({{"name", "skin"}, {"free_vertices", basis->freeCount()}, {"modes", basis->modeCount()}});
  }
  j["channels"] = ch;
  j["cold_precompute_seconds"] = cold;
  j["cold_cache_hits"] = coldHits;
  j["cached_start_seconds"] = cached;
  j["cache_hits"] = model->cacheHits();
  j["runs_steps_per_second"] = rates;
  j["steps_per_second"] = median(rates);
  j["step_us"] = median(stepUs);
  j["phase_us"] = {{"muscles", perStep * phases.muscles},
                   {"springs", perStep * phases.springs},
                   {"channels", perStep * phases.channels},
                   {"total", perStep * phases.total}};
  j["realtime_factor"] = median(rates) * model->dt();
  j["read_us"] = 1e6 * readSeconds(player);
  addRatios(j, opt, row, player, j["step_us"].get<double>());
  return j;
}

// One implicit-Euler step of the full skin (all free vertices, the head's gravity pins) under
// gravity with the full-space Newton reference solver, from rest.
nlohmann::json benchReference(const BenchOptions& opt, const std::string& head, BasisCache& cache) {
  BenchRow row{"4", "reference", "reference", "fig22_gravity_sweep.json", {}, 0.0, 1.0, false, 0};
  const SceneDesc scene = rowScene(opt, row, head);
  const auto model = buildThesisFace(scene, &cache);
  const DiscreteShell& skin = model->skin();
  const FaceModelSettings& s = model->settings();
  const int n = skin.vertexCount();
  MatX3 F = MatX3::Zero(n, 3);
  F.col(1) = -s.gravityAcceleration * skin.lumpedMass();
  ImplicitReference ref(skin, model->head().gravityPins, s.skinDampingMass, s.skinDampingStiffness);
  ref.setState(skin.rest(), MatX3::Zero(n, 3));
  std::vector<double> secs;
  int iterations = 0;
  for (int k = 0; k < opt.referenceSteps; ++k) {
    Stopwatch sw;
    ref.step(s.dt, F);
    secs.push_back(sw.seconds());
    iterations += ref.lastNewtonIterations();
  }
  nlohmann::json j;
  j["head"] = head;
  j["skin_vertices"] = n;
  j["free_vertices"] = n - static_cast<int>(model->head().gravityPins.size());
  j["load"] = "gravity (981 cm/s^2), from rest";
  j["dt"] = s.dt;
  j["steps"] = opt.referenceSteps;
  j["step_seconds_median"] = median(secs);
  j["steps_per_second"] = 1.0 / std::max(median(secs), 1e-12);
  j["newton_iterations_per_step"] = static_cast<double>(iterations) / std::max(opt.referenceSteps, 1);
  return j;
}

std::string machineName() {
  std::ifstream f("/proc/cpuinfo");
  std::string line;
  while (std::getline(f, line))
    if (line.rfind("model name", 0) == 0) {
      const auto p = line.find(':');
      return p == std::string::npos ? line : line.substr(p + 2);
    }
  return "unknown";
}

int runBench(BenchOptions opt) {
  if (opt.seconds <= 0.0) throw InputError("--seconds must be > 0");
  if (opt.runs < 1) throw InputError("--runs must be >= 1");
  opt.scenesDir = thesisScenesDir(opt.scenesDir).dir.string();
  if (!fs::exists(fs::path(opt.scenesDir) / "fig17_contract.json"))
    throw InputError("no thesis scenes here (give --scenes DIR, the folder of fig17_contract.json)", opt.scenesDir);
  std::vector<BenchRow> rows = thesisRows();
  for (BenchRow& r : fullRows()) rows.push_back(std::move(r));
  if (!opt.rows.empty()) {
    const auto want = splitList(opt.rows);
    std::vector<BenchRow> keep;
    for (const std::string& id : want) {
      auto it = std::find_if(rows.begin(), rows.end(), [&](const BenchRow& r) { return r.id == id; });
      if (it == rows.end()) throw InputError("unknown bench row '" + id + "'");
      keep.push_back(*it);
    }
    rows = keep;
  }
  std::vector<std::string> heads = splitList(opt.heads);
  for (const std::string& h : heads)
    if (h != "default" && h != "ict") throw InputError("unknown head '" + h + "' (default, ict)");
  nlohmann::json notes = nlohmann::json::array();
  if (opt.threads != 1)
    notes.push_back(fmt::format("--threads {}: the simulator is single-threaded; measured with 1 thread", opt.threads));
  const auto cache = openBasisCache(opt.cacheDir);

  nlohmann::json out;
  out["machine"] = {{"cpu", machineName()}, {"hardware_threads", std::thread::hardware_concurrency()}};
  out["threads"] = 1;
  out["seconds_per_row"] = opt.seconds;
  out["runs"] = opt.runs;
  nlohmann::json results = nlohmann::json::array();
  nlohmann::json references = nlohmann::json::array();
  for (const std::string& head : heads) {
    if (head == "ict") {
      std::string obj = (fs::path(opt.scenesDir) / "fig27_ict_head.json").string();
      try {
        obj = (fs::path(opt.scenesDir) / ictHead(opt).head.obj).string();  // the head path if absolute
      } catch (const InputError&) {
      }
      if (!fs::exists(obj)) {
        const std::string note = "ICT head skipped: " + obj + " not found (give --data DIR or set MYOSHELL_DATA)";
        notes.push_back(note);
        if (!opt.json) fmt::print("{}\n", note);
        continue;
      }
    }
    for (const BenchRow& row : rows) {
      if (row.table == "full") {
        nlohmann::json j = benchFullRow(opt, row, head);
        if (!opt.json) {
          const auto& p = j["phase_us"];
          fmt::print("{:7} {:<51} {:>10.0f} steps/s  {:>2} muscles  floor x{}  reference x{}  cold {:.1f} s, cached start "
                     "{:.2f} s; step {:.0f} us (muscles {:.0f}, springs/forces {:.0f}, skin {:.0f}); read {:.0f} us\n",
                     head, row.label, j["steps_per_second"].get<double>(), j["muscles"].get<int>(),
                     ratioText(j["floor_ratio"], "{:.2f}"), ratioText(j["reference_ratio"], "{:.2e}"),
                     j["cold_precompute_seconds"].get<double>(), j["cached_start_seconds"].get<double>(),
                     p["total"].get<double>(), p["muscles"].get<double>(), p["springs"].get<double>(),
                     p["channels"].get<double>(), j["read_us"].get<double>());
        }
        results.push_back(std::move(j));
        continue;
      }
      nlohmann::json j = benchRow(opt, row, head, *cache);
      if (!opt.json)
        fmt::print("{:7} T{} {:<48} {:>10.0f} steps/s  thesis {:>4.0f}  x{:>6.1f}{}  {} muscles  floor x{}  reference x{}\n",
                   head, row.table, row.label, j["steps_per_second"].get<double>(), row.thesisFps,
                   j["ratio"].get<double>(), j["meets_10x"].get<bool>() ? "" : "  (< 10x)", j["muscles"].get<int>(),
                   ratioText(j["floor_ratio"], "{:.2f}"), ratioText(j["reference_ratio"], "{:.2e}"));
      results.push_back(std::move(j));
    }
    if (opt.reference) {
      nlohmann::json r = benchReference(opt, head, *cache);
      if (!opt.json)
        fmt::print("{:7} reference: one implicit-Euler step of the full skin ({} free vertices, gravity): {:.3f} s "
                   "({:.1f} Newton iterations)\n",
                   head, r["free_vertices"].get<int>(), r["step_seconds_median"].get<double>(),
                   r["newton_iterations_per_step"].get<double>());
      references.push_back(std::move(r));
    }
  }
  // Reduced vs reference: how many reduced steps fit in one full-space step.
  for (auto& j : results)
    for (const auto& r : references)
      if (r["head"] == j["head"])
        j["speedup_vs_reference"] = j["steps_per_second"].get<double>() * r["step_seconds_median"].get<double>();
  // The two models side by side: anatomical steps/s over thesis steps/s, per head.
  nlohmann::json sideBySide = nlohmann::json::array();
  for (const std::string& head : heads) {
    const nlohmann::json *t = nullptr, *a = nullptr;
    for (const auto& j : results)
      if (j["head"] == head) {
        if (j["id"] == "thesis_full") t = &j;
        if (j["id"] == "anatomical_full") a = &j;
      }
    if (!t || !a) continue;
    const double ratio = (*a)["steps_per_second"].get<double>() / (*t)["steps_per_second"].get<double>();
    sideBySide.push_back({{"head", head}, {"anatomical_over_thesis", ratio}});
    if (!opt.json) fmt::print("{:7} anatomical / thesis steps per second: {:.2f}\n", head, ratio);
  }
  out["rows"] = results;
  out["full_side_by_side"] = sideBySide;
  out["reference"] = references;
  out["notes"] = notes;
  if (opt.json) printJsonReport(out);
  return kExitOk;
}

const CommandRegistrar benchRegistrar("bench", [](CLI::App& app) {
  auto opt = std::make_shared<BenchOptions>();
  CLI::App* sub = app.add_subcommand("bench", "Re-measure the thesis's Tables 2-4 (steps per second) on the thesis scenes, and both models side by side");
  addJsonFlag(*sub, opt->json);
  addThreadsOption(*sub, opt->threads, "Threads (the simulator is single-threaded: 1 is used, and another value noted; default 1)");
  sub->add_option("--seconds", opt->seconds, "Timed seconds per row (split over --runs)")->capture_default_str();
  sub->add_option("--runs", opt->runs, "Timed runs per row (the median is reported)")->capture_default_str();
  addScenesOption(*sub, opt->scenesDir);
  addCacheOption(*sub, opt->cacheDir);
  addDataOption(*sub, opt->dataDir);
  sub->add_option("--heads", opt->heads, "Heads to run: default, ict (comma-separated)")->capture_default_str();
  sub->add_option("--rows", opt->rows, "Only these row ids (comma-separated; see --json output; default: all)");
  sub->add_option("--reference-steps", opt->referenceSteps, "Implicit-Euler steps timed for the reference solver")
      ->check(wholeAtLeast(1))
      ->capture_default_str();
  auto flag = std::make_shared<bool>(false);
  sub->add_flag("--no-reference", *flag, "Skip the full-space reference solver (reference_ratio null)");
  sub->add_flag("--diagnostics", opt->diagnostics,
                "Also measure each thesis channel's load participation (a sparse factorisation per channel)");
  return std::function<int()>([opt, flag] {
    opt->reference = !*flag;
    return runBench(*opt);
  });
});

}  // namespace
}  // namespace myo::cli
