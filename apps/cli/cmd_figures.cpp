// `myoshell figures --out DIR [--scenes DIR] [--cache DIR] [--only fig18,fig26] [--size PX]`:
// renders the thesis's Figures 17–27 from the scenes of scenes/thesis/ (docs/thesis_experiments.md),
// and `anatomical`: the anatomical model on ICT beside the artist's shapes (docs/anatomical_model.md),
// through the shared face painter (headless OpenGL, or the software rasterizer where OpenGL is not
// available or with --software): one contact sheet per figure, each captioned with
// the thesis's figure number. Deformed skin is coloured by displacement magnitude (viridis, the
// range written on the colour bar); ROI and pin pictures use the thesis's colours (red free,
// blue pinned, yellow fixed feature points).
#include <fmt/core.h>

#include <algorithm>
#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <memory>
#include <set>
#include <sstream>
#include <system_error>

#include "job_report.h"
#include "command.h"
#include "common_options.h"
#include "resources.h"
#include "myoshell/anatomy/anatomical_face.h"
#include "myoshell/anim/scene_player.h"
#include "myoshell/core/errors.h"
#include "myoshell/fit/shape_metric.h"
#include "myoshell/io/head_files.h"
#include "myoshell/io/output_paths.h"
#include "myoshell/io/scene_face.h"
#include "myoshell/mesh/obj_reader.h"
#include "myoshell/muscles/muscle_def.h"
#include "myoshell/render/contact_sheet.h"
#include "myoshell/render/face_picture.h"
#include "myoshell/render/image.h"
#include "myoshell/render/png.h"
#include "option_checks.h"
#include "scene_runner.h"

namespace myo::cli {
namespace {

namespace fs = std::filesystem;

struct FigureOptions {
  std::string outDir = "docs/figures";
  std::string scenesDir;  // --scenes; "" = the shipped scenes/thesis (resources.h)
  std::string cacheDir;   // --cache; "" = the default basis cache (resources.h)
  std::string dataDir;    // --data; "" = $MYOSHELL_DATA or the build tree's ../shared/data
  std::string only;  // comma-separated figure keys (fig17, fig18, …); empty = all
  int size = 360;    // tile width and height, pixels
  bool software = false;
  bool json = false;  // the files written (and the figures skipped) as JSON, not line by line
};

struct Loaded {
  SceneDesc scene;
  std::shared_ptr<const FaceModel> model;
};

class Figures {
 public:
  explicit Figures(const FigureOptions& opt)
      : opt_(opt), cache_(openBasisCache(opt.cacheDir)), painter_(makePainter(opt.software)) {}

  Loaded load(const std::string& name, const std::function<void(SceneDesc&)>& edit = {}) {
    Loaded l;
    l.scene = readScene((fs::path(opt_.scenesDir) / (name + ".json")).string());
    if (const fs::path data = dataDir(opt_.dataDir).dir; !data.empty()) useDataDir(l.scene, data);
    if (edit) edit(l.scene);
    l.model = buildThesisFace(l.scene, cache_.get());
    return l;
  }

  // The default head framed whole; a whole head (ICT) framed on its face.
  Camera camera(const FaceSystem& model, ViewPreset preset) const {
    return faceCamera(model, preset, opt_.size, opt_.size,
                      model.head().name == "default" ? FaceFraming::all : FaceFraming::face);
  }

  // One tile: the face picture of `state` with `overlays`.
  Image tile(const FaceSystem& model, const Camera& cam, const FaceFrameState& state, const FaceOverlays& overlays) const {
    return painter_->paint(faceScene(model, state, cam, opt_.size, opt_.size, overlays));
  }

  void save(const std::string& file, const std::vector<Image>& tiles, const std::vector<std::string>& captions,
            int columns, const std::string& title) {
    ContactSheetStyle st;
    st.columns = columns;
    st.captionScale = 1;
    st.background = Rgb(1, 1, 1);
    Image sheet = contactSheet(tiles, captions, st);
    sheet = withCaption(sheet, title, 2);
    const fs::path path = fs::path(opt_.outDir) / file;
    writePng(path.string(), sheet);
    written_.push_back(path.string());
    if (!opt_.json) fmt::print("wrote {}\n", path.string());
  }

  // A figure left out, and why (its data is absent).
  void skip(const std::string& figure, const std::string& reason) {
    skipped_.push_back({{"figure", figure}, {"reason", reason}});
    if (!opt_.json) fmt::print("{} skipped: {}\n", figure, reason);
  }

  const std::vector<std::string>& written() const { return written_; }
  const nlohmann::ordered_json& skipped() const { return skipped_; }

 private:
  FigureOptions opt_;
  std::unique_ptr<BasisCache> cache_;
  std::unique_ptr<FacePainter> painter_;
  std::vector<std::string> written_;
  nlohmann::ordered_json skipped_ = nlohmann::ordered_json::array();
};

// The player's face at time t (s): skin, displacement and muscles.
FaceFrameState frameAt(ScenePlayer& player, double t) {
  player.playTo(t);
  const FrameSnapshot& s = player.snapshot();
  return {s.positions, s.displacement, s.muscles};
}

double maxNorm(const MatX3& U) { return U.rows() ? U.rowwise().norm().maxCoeff() : 0.0; }

// Overlays: the muscles through a faint skin; displacement on [0, maxU] cm; free (red) and pinned
// (blue) vertices with feature points (yellow).
FaceOverlays musclesThrough() {
  FaceOverlays o;
  o.muscles = true;
  o.skinOpacityOverMuscles = 0.25;
  return o;
}
FaceOverlays displacementOn(double maxU, bool bar = true) {
  FaceOverlays o;
  o.displacement = true;
  o.displacementScale = std::max(maxU, 1e-9);
  o.colorBar = bar;
  return o;
}
FaceOverlays constraints(std::vector<int> freeVertices, std::vector<int> features = {}, double radius = 4.0) {
  FaceOverlays o;
  o.freeVertices = std::move(freeVertices);
  o.features = std::move(features);
  o.featureRadius = radius;
  return o;
}

std::string fmtTime(double t) { return fmt::format("t = {:.2f} s", t); }

// Fig. 17: the eight muscles alone, contraction (a) and relaxation (b), skin translucent over them.
void fig17(Figures& F) {
  std::vector<Image> tiles;
  std::vector<std::string> caps;
  for (const char* name : {"fig17_contract", "fig17_relax"}) {
    const Loaded l = F.load(name);
    const Camera cam = F.camera(*l.model, ViewPreset::front);
    ScenePlayer player(l.scene, l.model);
    const bool contract = name == std::string("fig17_contract");
    for (double t : {0.0, 0.15, 0.6}) {
      FaceFrameState state = frameAt(player, t);
      state.skin = l.model->head().mesh.V;  // the muscles alone move: the skin stays at rest
      tiles.push_back(F.tile(*l.model, cam, state, musclesThrough()));
      caps.push_back(fmt::format("({}) {} {}", contract ? "a" : "b", contract ? "contraction" : "relaxation", fmtTime(t)));
    }
  }
  F.save("fig17_muscles.png", tiles, caps, 3,
         "Fig. 17: muscle deformation by tangential force, origin rings pinned (a) contraction (b) relaxation");
}

// Fig. 18: per muscle type: muscle, ROI (red free, blue pinned), right side only, both sides.
void fig18(Figures& F) {
  std::vector<Image> tiles;
  std::vector<std::string> caps;
  const std::vector<std::pair<std::string, std::string>> rows = {
      {"fig18_zygomaticus", "zygomaticus_major"},
      {"fig18_depressor_labii", "depressor_labii_inferioris"},
      {"fig18_depressor_anguli", "depressor_anguli_oris"}};
  const char* letter[] = {"a", "b", "c"};
  for (size_t r = 0; r < rows.size(); ++r) {
    const Loaded l = F.load(rows[r].first);
    const FaceModel& model = *l.model;
    const Camera cam = F.camera(model, ViewPreset::front);
    const int mr = model.muscleIndex(rows[r].second + "_right");
    const FaceFrameState rest = restFrameState(model);
    tiles.push_back(F.tile(model, cam, rest, musclesThrough()));
    caps.push_back(fmt::format("({}) {}", letter[r], rows[r].second));
    tiles.push_back(F.tile(model, cam, rest, constraints(model.muscles()[mr].roi)));
    caps.push_back(fmt::format("ROI, {} free vertices", model.muscles()[mr].roi.size()));
    ScenePlayer player(l.scene, l.model);
    const FaceFrameState right = frameAt(player, 0.95), both = frameAt(player, 2.0);
    const double maxU = std::max(maxNorm(right.displacement), maxNorm(both.displacement));
    tiles.push_back(F.tile(model, cam, right, displacementOn(maxU)));
    caps.push_back("right side only");
    tiles.push_back(F.tile(model, cam, both, displacementOn(maxU)));
    caps.push_back("both sides");
  }
  F.save("fig18_roi_right_both.png", tiles, caps, 4,
         "Fig. 18: muscle, its ROI, skin by the right muscle only and by both (a) zyg. major (b) dep. labii inf. (c) dep. anguli oris");
}

// Fig. 19 and 20: the corrugators, their ROI; contraction | neutral | relaxation.
void fig19_20(Figures& F) {
  const Loaded l = F.load("fig20_corrugator");
  const FaceModel& model = *l.model;
  const Camera cam = F.camera(model, ViewPreset::front);
  const int mr = model.muscleIndex("corrugator_supercilii_right");
  const int ml = model.muscleIndex("corrugator_supercilii_left");
  std::vector<int> roi = model.muscles()[mr].roi;
  roi.insert(roi.end(), model.muscles()[ml].roi.begin(), model.muscles()[ml].roi.end());
  const FaceFrameState rest = restFrameState(model);
  F.save("fig19_corrugator_roi.png",
         {F.tile(model, cam, rest, musclesThrough()), F.tile(model, cam, rest, constraints(roi))},
         {"(a) corrugator supercilii", "(b) ROI of (a): red free, blue pinned"}, 2,
         "Fig. 19: insertion and ROI of corrugator supercilii");
  ScenePlayer player(l.scene, l.model);
  const FaceFrameState contracted = frameAt(player, 0.95), relaxed = frameAt(player, 2.0);
  const double maxU = std::max(maxNorm(contracted.displacement), maxNorm(relaxed.displacement));
  F.save("fig20_corrugator.png",
         {F.tile(model, cam, contracted, displacementOn(maxU)), F.tile(model, cam, rest, displacementOn(maxU, false)),
          F.tile(model, cam, relaxed, displacementOn(maxU))},
         {"contraction (a = 1)", "neutral", "relaxation (a = -1)"}, 3,
         "Fig. 20: corrugator supercilii, contraction (left) and relaxation (right) from the neutral face");
}

// Fig. 21 and 22: gravity pins; the sag with the skin stiffness scaled by 1, 0.5, 0.25.
void fig21_22(Figures& F) {
  std::vector<Image> tiles;
  std::vector<std::string> caps;
  {
    const Loaded l = F.load("fig22_gravity_sweep");
    const FaceModel& model = *l.model;
    const Camera cam = F.camera(model, ViewPreset::threeQuarter);
    std::vector<int> freeV;
    std::vector<bool> pinned(static_cast<size_t>(model.skin().vertexCount()), false);
    for (int v : model.head().gravityPins) pinned[static_cast<size_t>(v)] = true;
    for (int v = 0; v < model.skin().vertexCount(); ++v)
      if (!pinned[static_cast<size_t>(v)]) freeV.push_back(v);
    std::vector<int> features;
    for (const auto& [name, v] : model.head().landmarks.resolved())
      if (pinned[static_cast<size_t>(v)]) features.push_back(v);
    const std::string caption = fmt::format("{} pinned (blue), {} free (red), fixed feature points yellow",
                                            model.head().gravityPins.size(), freeV.size());
    F.save("fig21_gravity_pins.png", {F.tile(model, cam, restFrameState(model), constraints(freeV, features))},
           {caption}, 1, "Fig. 21: static constraints of the skin for the gravity load");
  }
  std::vector<FaceFrameState> states;
  std::vector<std::shared_ptr<const FaceModel>> models;
  const std::vector<double> scales = {1.0, 0.5, 0.25};
  for (double s : scales) {
    const Loaded l = F.load("fig22_gravity_sweep", [s](SceneDesc& d) {
      d.model.skin.kA *= s;
      d.model.skin.kL *= s;
      d.model.skin.kB *= s;
    });
    ScenePlayer player(l.scene, l.model);
    states.push_back(frameAt(player, l.scene.duration));
    models.push_back(l.model);
  }
  double maxU = 0.0;
  for (const FaceFrameState& st : states) maxU = std::max(maxU, maxNorm(st.displacement));
  for (size_t i = 0; i < scales.size(); ++i) {
    const Camera cam = F.camera(*models[i], ViewPreset::threeQuarter);
    tiles.push_back(F.tile(*models[i], cam, states[i], displacementOn(maxU)));
    caps.push_back(fmt::format("k_A, k_L, k_B x {:.2f}: max sag {:.2f} cm", scales[i], maxNorm(states[i].displacement)));
  }
  F.save("fig22_gravity_sweep.png", tiles, caps, 3,
         "Fig. 22: gravity load for skin with decreasing element stiffnesses");
}

// Fig. 23: zygomaticus major + depressor labii inferioris, frame by frame; (b) the muscles.
void fig23(Figures& F) {
  const Loaded l = F.load("fig23_combined");
  const FaceModel& model = *l.model;
  const Camera cam = F.camera(model, ViewPreset::front);
  ScenePlayer player(l.scene, l.model);
  const std::vector<double> times = {0.0, 0.1, 0.2, 0.3, 1.0};
  std::vector<FaceFrameState> states;
  double maxU = 0.0;
  for (double t : times) {
    states.push_back(frameAt(player, t));
    maxU = std::max(maxU, maxNorm(states.back().displacement));
  }
  std::vector<Image> tiles;
  std::vector<std::string> caps;
  for (size_t i = 0; i < times.size(); ++i) {
    tiles.push_back(F.tile(model, cam, states[i], displacementOn(maxU)));
    caps.push_back("(a) skin, " + fmtTime(times[i]));
  }
  for (size_t i = 0; i < times.size(); ++i) {
    tiles.push_back(F.tile(model, cam, states[i], musclesThrough()));
    caps.push_back("(b) muscles, " + fmtTime(times[i]));
  }
  F.save("fig23_combined.png", tiles, caps, 5,
         "Fig. 23: zygomaticus major + depressor labii inferioris, combined displacement fields frame by frame");
}

// Fig. 24 and 25: the drag's pins and its own displacement field; drag + zygomaticus major.
void fig24_25(Figures& F) {
  const Loaded l = F.load("fig25_drag");
  const FaceModel& model = *l.model;
  const Camera cam = F.camera(model, ViewPreset::threeQuarter);
  int drag = -1;
  for (size_t c = 0; c < model.channels().size(); ++c)
    if (model.channels()[c].kind == ChannelKind::Drag) drag = static_cast<int>(c);
  if (drag < 0) throw InputError("fig25_drag has no drag channel");
  const SkinChannel& ch = model.channels()[static_cast<size_t>(drag)];
  std::vector<int> gripped;
  for (int row : ch.dragRows) gripped.push_back(ch.basis->freeVertices[static_cast<size_t>(row)]);
  ScenePlayer player(l.scene, l.model);
  const FaceFrameState end = frameAt(player, l.scene.duration);
  FaceFrameState dragOnly;
  dragOnly.displacement = player.simulator().channelDisplacement(drag);
  dragOnly.skin = model.head().mesh.V + dragOnly.displacement;
  const FaceFrameState rest = restFrameState(model);
  F.save("fig24_drag.png",
         {F.tile(model, cam, rest, constraints(ch.basis->freeVertices, gripped, 2.5)),
          F.tile(model, cam, dragOnly, displacementOn(maxNorm(dragOnly.displacement)))},
         {"(a) static points (blue), dragged region (yellow)", "(b) displacement field u_ext of the drag alone"}, 2,
         "Fig. 24: static constraints and displacement field of the drag force F_ext_s1 on the right cheek");
  F.save("fig25_drag_and_zygomaticus.png",
         {F.tile(model, cam, rest, FaceOverlays{}), F.tile(model, cam, end, displacementOn(maxNorm(end.displacement)))},
         {"neutral", "drag on the right cheek + zygomaticus major"}, 2,
         "Fig. 25: skin deformation by the drag F_ext_s1 and the zygomaticus major together");
}

// A row of frames of one scene at the given times, coloured by displacement on one shared scale.
// withTimes appends each key's time to its caption.
void timelineStrip(Figures& F, const std::string& scene, const std::vector<std::pair<double, std::string>>& keys,
                   bool withTimes, const std::string& file, const std::string& title) {
  const Loaded l = F.load(scene);
  const FaceModel& model = *l.model;
  const Camera cam = F.camera(model, ViewPreset::front);
  ScenePlayer player(l.scene, l.model);
  std::vector<FaceFrameState> states;
  double maxU = 0.0;
  for (const auto& k : keys) {
    states.push_back(frameAt(player, k.first));
    maxU = std::max(maxU, maxNorm(states.back().displacement));
  }
  std::vector<Image> tiles;
  std::vector<std::string> caps;
  for (size_t i = 0; i < keys.size(); ++i) {
    tiles.push_back(F.tile(model, cam, states[i], displacementOn(maxU)));
    caps.push_back(withTimes ? fmt::format("{} ({})", keys[i].second, fmtTime(keys[i].first)) : keys[i].second);
  }
  F.save(file, tiles, caps, static_cast<int>(keys.size()), title);
}

// Fig. 26: t0 neutral, t1 lifted, t2 neutral again, t3 pulled down.
void fig26(Figures& F) {
  timelineStrip(F, "fig26_transition",
                {{0.0, "t0 neutral"}, {0.6, "t1 zyg. major contracted"}, {1.2, "t2 relaxed"}, {1.8, "t3 dep. anguli oris"}},
                true, "fig26_transition.png", "Fig. 26: transition from the lifted to the pulled-down lip, t0 to t3");
}

// Fig. 27: the ICT head (a user-specific mesh).
void fig27(Figures& F, const FigureOptions& opt) {
  SceneDesc probe = readScene((fs::path(opt.scenesDir) / "fig27_ict_head.json").string());
  if (const fs::path data = dataDir(opt.dataDir).dir; !data.empty()) useDataDir(probe, data);
  const fs::path obj = fs::path(opt.scenesDir) / probe.head.obj;  // the head path if absolute
  if (!fs::exists(obj)) {
    F.skip("fig27", "the ICT head (" + obj.string() + ") is absent (give --data DIR or set MYOSHELL_DATA)");
    return;
  }
  timelineStrip(F, "fig27_ict_head",
                {{0.0, "neutral"}, {0.6, "zygomaticus major"}, {1.5, "depressor anguli oris"}, {2.4, "zyg. major + dep. labii inf."}},
                false, "fig27_ict_head.png", "Fig. 27: facial animation with a user-specific mesh (ICT-FaceKit head)");
}

// The anatomical model on the ICT head (docs/anatomical_model.md): each muscle alone at a = 1,
// settled, beside the artist's shape it is compared with (one colour scale per row), and gravity
// face-down and face-up, no pins. ICT's shapes only: skipped when the data is absent.
void anatomicalFigure(Figures& F, const FigureOptions& opt) {
  const fs::path ict = dataDir(opt.dataDir).dir / "ict";
  if (dataDir(opt.dataDir).dir.empty() || !fs::exists(ict / "head_skin.obj")) {
    F.skip("anatomical", "the ICT head (" + (ict / "head_skin.obj").string() + ") is absent (give --data DIR or set MYOSHELL_DATA)");
    return;
  }
  const Head head = loadHead((ict / "head_skin.obj").string(), (ict / "landmarks_multipie68.json").string());
  const auto face = std::make_shared<const AnatomicalFace>(head, anatomicalBuiltinDefs(), AnatomicalSettings{}, std::vector<DragDef>{});
  const AnatomicalSkin& skin = face->skin();
  const Camera cam = faceCamera(*face, ViewPreset::front, opt.size, opt.size, FaceFraming::face);
  auto loads = [&](const std::string& muscle, const Vec3& pose) {
    SkinLoads l;
    l.activations = VecX::Zero(face->muscleCount());
    if (!muscle.empty()) l.activations(skin.muscleIndex(muscle)) = 1.0;
    l.gravity = gravityForPose(head.frame(), pose, skin.settings().gravity);
    return l;
  };
  auto state = [&](const MatX3& u) {
    FaceFrameState s = restFrameState(*face);
    s.skin = head.mesh.V + u;
    s.displacement = u;
    return s;
  };
  std::vector<Image> tiles;
  std::vector<std::string> caps;
  for (const auto& [muscle, shape] : {std::pair<std::string, std::string>{"zygomaticus_major_left", "expression_mouthSmile_L"},
                                      {"depressor_anguli_oris_left", "expression_mouthFrown_L"}}) {
    const MatX3 u = skin.settle(loads(muscle, Vec3::Zero()), skin.settings().warping).u;
    const MatX3 e = readObjLike((ict / (shape + ".obj")).string(), head.mesh).V - head.mesh.V;
    const ShapeComparison c = compareShapes(u, e, head.mesh.V);
    const double maxU = std::max(maxNorm(u), maxNorm(e));
    tiles.push_back(F.tile(*face, cam, state(u), displacementOn(maxU)));
    caps.push_back(fmt::format("{}, a = 1 (cos {:.2f}, ratio {:.2f})", muscle, c.cosine, c.magnitudeRatio));
    tiles.push_back(F.tile(*face, cam, state(e), displacementOn(maxU)));
    caps.push_back("artist: " + shape);
  }
  for (const auto& [name, pose] : {std::pair<std::string, Vec3>{"face-down (pitch +90)", Vec3(90, 0, 0)}, {"face-up (pitch -90)", Vec3(-90, 0, 0)}}) {
    const MatX3 u = skin.settle(loads("", pose), skin.settings().warping).u;
    tiles.push_back(F.tile(*face, cam, state(u), displacementOn(maxNorm(u))));
    caps.push_back("gravity " + name + ", no pins");
  }
  F.save("anatomical_ict.png", tiles, caps, 2,
         "Anatomical model, ICT head, settled: each muscle beside the artist's shape; gravity relative to the upright rest");
}

int runFigures(FigureOptions opt) {
  opt.scenesDir = thesisScenesDir(opt.scenesDir).dir.string();
  const std::vector<std::pair<std::string, std::function<void(Figures&)>>> all = {
      {"fig17", [](Figures& F) { fig17(F); }},    {"fig18", [](Figures& F) { fig18(F); }},
      {"fig20", [](Figures& F) { fig19_20(F); }}, {"fig22", [](Figures& F) { fig21_22(F); }},
      {"fig23", [](Figures& F) { fig23(F); }},    {"fig25", [](Figures& F) { fig24_25(F); }},
      {"fig26", [](Figures& F) { fig26(F); }},    {"fig27", [&](Figures& F) { fig27(F, opt); }},
      {"anatomical", [&](Figures& F) { anatomicalFigure(F, opt); }}};
  std::set<std::string> want;
  std::stringstream ss(opt.only);
  std::string item;
  while (std::getline(ss, item, ','))
    if (!item.empty()) {
      if (std::none_of(all.begin(), all.end(), [&](const auto& p) { return p.first == item; }))
        throw InputError("unknown figure '" + item + "' (fig17 fig18 fig20 fig22 fig23 fig25 fig26 fig27 anatomical)");
      want.insert(item);
    }
  if (!fs::exists(fs::path(opt.scenesDir) / "fig17_contract.json"))
    throw InputError("no thesis scenes here (give --scenes DIR, the folder of fig17_contract.json)", opt.scenesDir);
  checkOutputFolder(opt.outDir, "--out");
  std::error_code ec;
  fs::create_directories(opt.outDir, ec);  // only once the arguments are known good
  if (ec) throw InputError("cannot create the output folder (" + ec.message() + ")", opt.outDir);
  Figures F(opt);  // opens the basis cache: after every check
  for (const auto& [key, fn] : all)
    if (want.empty() || want.count(key)) fn(F);
  if (opt.json) {
    nlohmann::ordered_json j;
    j["out"] = opt.outDir;
    j["written"] = F.written();
    j["skipped"] = F.skipped();
    printJsonReport(j);
  }
  return kExitOk;
}

const CommandRegistrar figuresRegistrar("figures", [](CLI::App& app) {
  auto opt = std::make_shared<FigureOptions>();
  CLI::App* sub = app.add_subcommand("figures", "Render the thesis's Figures 17-27 from scenes/thesis, and the anatomical model's picture on ICT, into PNGs");
  sub->add_option("--out", opt->outDir, "Output folder")->capture_default_str();
  addScenesOption(*sub, opt->scenesDir);
  addCacheOption(*sub, opt->cacheDir);
  addDataOption(*sub, opt->dataDir);
  sub->add_option("--only", opt->only, "Only these figures (comma-separated: fig17, fig18, fig20, fig22, fig23, fig25, fig26, fig27, anatomical; default: all)");
  sub->add_option("--size", opt->size, "Tile size, pixels")->check(wholeIn(64, 2048))->capture_default_str();
  sub->add_flag("--software", opt->software, "Draw with the software renderer even where OpenGL is available");
  addJsonFlag(*sub, opt->json);
  return std::function<int()>([opt] { return runFigures(*opt); });
});

}  // namespace
}  // namespace myo::cli
