#include "myoshell/fit/rig_fit.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>

#include "myoshell/core/check.h"
#include "myoshell/core/errors.h"
#include "myoshell/core/parallel.h"
#include "myoshell/core/timer.h"
#include "myoshell/fit/arkit_names.h"
#include "myoshell/fit/facs_route.h"
#include "myoshell/fit/shape_metric.h"
#include "myoshell/head/jaw.h"

namespace myo {

double median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const size_t k = values.size() / 2;
  return values.size() % 2 ? values[k] : 0.5 * (values[k - 1] + values[k]);
}

namespace {

// Activations above this are written into the map; smaller ones are round-off of the box solve.
constexpr double kSmallestActivation = 1e-9;

NamedValues namedActivations(const AnatomicalSkin& skin, const VecX& a) {
  NamedValues out;
  for (Eigen::Index m = 0; m < a.size(); ++m)
    if (std::abs(a(m)) > kSmallestActivation) out.emplace_back(skin.muscles()[static_cast<size_t>(m)].muscle.def.name, a(m));
  return out;
}

// The jaw's degree of freedom an ARKit jaw shape moves, with the range searched: jawOpen the
// opening (degrees), jawForward the protrusion (cm), jawLeft / jawRight the lateral shift towards
// the subject's left / right (cm). Index 0, 1, 2 of [open, forward, lateral]; −1 for other shapes.
struct JawDof {
  int index = -1;
  double lo = 0.0, hi = 0.0;
};
JawDof jawDofOf(const std::string& arkitName) {
  if (arkitName == "jawOpen") return {0, kJawOpenMinDeg, kJawOpenMaxDeg};
  if (arkitName == "jawForward") return {1, 0.0, kJawForwardMaxCm};
  if (arkitName == "jawLeft") return {2, 0.0, kJawLateralMaxCm};
  if (arkitName == "jawRight") return {2, -kJawLateralMaxCm, 0.0};
  return {};
}

JawPose poseOf(int dof, double value) {
  JawPose pose;
  if (dof == 0) pose.openDeg = value;
  else if (dof == 1) pose.forwardCm = value;
  else pose.lateralCm = value;
  return pose;
}

// A pose's mirror image across the face's midplane (x → −x): the lateral shift to the other side.
JawPose mirroredPose(JawPose pose) {
  if (pose.lateralCm != 0.0) pose.lateralCm = -pose.lateralCm;
  return pose;
}

// The value in [lo, hi] that minimises `misfit`, by golden-section search (the misfit of one jaw
// degree of freedom is smooth and, over the jaw's range, unimodal); the ends are candidates too, so
// a shape that does not move the jaw gets exactly 0 where 0 is an end.
template <class Misfit>
double goldenSection(Misfit misfit, double lo, double hi) {
  const double phi = 0.5 * (std::sqrt(5.0) - 1.0);
  double a = lo, b = hi;
  double c = b - phi * (b - a), d = a + phi * (b - a);
  double fc = misfit(c), fd = misfit(d);
  for (int k = 0; k < 40 && b - a > 1e-4 * (hi - lo); ++k) {
    if (fc < fd) {
      b = d, d = c, fd = fc;
      c = b - phi * (b - a), fc = misfit(c);
    } else {
      a = c, c = d, fc = fd;
      d = a + phi * (b - a), fd = misfit(d);
    }
  }
  double value = 0.5 * (a + b), best = misfit(value);
  for (double end : {lo, hi}) {
    const double f = misfit(end);
    if (f <= best) value = end, best = f;
  }
  return value;
}

// Re-measures a fit whose shape is the jaw's rigid motion plus the muscles' settled displacement
// (the residual is taken in the rest frame: the muscles' part is not turned with the jaw here).
void remeasure(ActivationFit& fit, const MatX3& jawMotion, const MatX3& target, const MatX3& rest, double threshold) {
  fit.displacement += jawMotion;
  fit.target = target;
  fit.metric = compareShapes(fit.displacement, target, rest, ShapeMetricSettings{threshold, 20});
  double sum = 0.0, worst = 0.0;
  int count = 0;
  for (Eigen::Index i = 0; i < target.rows(); ++i)
    if (fit.displacement.row(i).norm() > threshold || target.row(i).norm() > threshold) {
      const double d = (fit.displacement.row(i) - target.row(i)).norm();
      sum += d * d, worst = std::max(worst, d), ++count;
    }
  fit.rmsMm = count ? 10.0 * std::sqrt(sum / count) : 0.0;
  fit.maxMm = 10.0 * worst;
}

}  // namespace

RigFit fitRig(const AnatomicalSkin& skin, const std::vector<RigTarget>& targets, const FitSettings& settings,
              const FacsMap& facs) {
  const Stopwatch clock;
  const Eigen::Index n = skin.head().mesh.vertexCount();
  RigFit out;

  // Gather the targets under their ARKit names (ICT halves summed).
  std::map<std::string, RigShapeFit> byName;
  std::map<std::string, std::string> spellingOf;  // ARKit name → first rig name seen, for errors
  for (const RigTarget& t : targets) {
    const std::optional<std::string> arkit = findArkitName(t.name);
    if (!arkit) {
      out.skipped.push_back(t.name);
      continue;
    }
    if (t.displacement.rows() != n)
      throw InputError("fit-rig: shape '" + t.name + "' has " + std::to_string(t.displacement.rows()) +
                       " vertices, the head " + std::to_string(n));
    if (!t.displacement.allFinite())
      throw InputError("fit-rig: shape '" + t.name + "' has a coordinate that is not a finite number");
    RigShapeFit& s = byName[*arkit];
    // Twice: the same name again, another spelling of a one-shape name, or the ARKit whole beside a half.
    const bool whole = t.name == *arkit || std::find(s.sources.begin(), s.sources.end(), *arkit) != s.sources.end();
    if (!s.sources.empty() && (ictNamesOf(*arkit).size() == 1 || whole ||
                               std::find(s.sources.begin(), s.sources.end(), t.name) != s.sources.end()))
      throw InputError("fit-rig: the rig names " + *arkit + " twice ('" + s.sources.front() + "' and '" + t.name + "')");
    s.name = *arkit;
    if (s.sources.empty()) s.target = MatX3::Zero(n, 3);
    s.target += t.displacement;
    s.sources.push_back(t.name);
  }
  if (byName.empty()) {
    std::string names;
    for (const RigTarget& t : targets) names += (names.empty() ? "" : ", ") + t.name;
    throw InputError("fit-rig: the rig has no shape with an ARKit name (it has: " + (names.empty() ? "none" : names) +
                     "); docs/rigs.md lists the names in both spellings");
  }
  if (byName.count("mouthClose") && !byName.count("jawOpen"))
    throw InputError("fit-rig: mouthClose is a corrective on jawOpen (it closes the lips of an open jaw), and the rig "
                     "has no jawOpen");

  // The jaw, when the head has the 68-point jaw line (head/jaw.h): jaw shapes fit its degree of
  // freedom first, then the muscles on what the jaw leaves.
  const MatX3& rest = skin.head().mesh.V;
  // Every fit places its shape with the skin's one placement (anatomy/skin_placement.h).
  const SkinPlacement& placement = skin.placement();
  const JawRig* jaw = placement.jaw();
  // Every muscle's settled column, once: each fit below (and each jaw value a jaw shape's search
  // tries) reuses them instead of solving them again.
  std::vector<int> everyMuscle(skin.muscles().size());
  for (size_t k = 0; k < everyMuscle.size(); ++k) everyMuscle[k] = static_cast<int>(k);
  const std::vector<MatX3> columns = activationColumns(skin, everyMuscle);

  // The shapes the rig has, in ARKit order; a corrective (mouthClose) is fitted on its base's target.
  std::vector<RigShapeFit> shapes;
  for (const std::string& name : arkitNames()) {
    auto it = byName.find(name);
    if (it == byName.end()) continue;
    // A shape that turns the eyes (eyeLook*) or holds air in the mouth (cheekPuff) is derived from
    // its definition even where the rig has it: muscles alone cannot make it, and the artist's shape
    // is only compared (docs/eyelids.md, docs/anatomical_model.md "Air in the mouth").
    if (const FacsDrive d = facsDriveOfArkitName(facs, name); d.turnsEyes() || d.mouthPressureKpa > 0.0) continue;
    RigShapeFit s = std::move(it->second);
    if (const std::optional<std::string> reason = unreachableReason(name)) {
      s.reachable = false;
      s.reason = *reason;
    } else if (name == "mouthClose") {
      s.correctiveOf = "jawOpen";
    }
    shapes.push_back(std::move(s));
  }
  auto indexOf = [&](const std::string& name) {
    return static_cast<size_t>(std::find_if(shapes.begin(), shapes.end(), [&](const RigShapeFit& f) { return f.name == name; }) -
                               shapes.begin());
  };

  // One shape's fit, or a left/right pair's (`mirror` the right shape, fitted with the left's
  // activations by twin: fitMirroredActivations). A jaw shape: its jaw degree of freedom and the
  // muscles together — for each value the muscles are fitted to what the jaw's rigid motion leaves,
  // and the value with the smallest total misfit wins (a pair's right jaw is the left's mirror
  // image). A corrective rides on its base's jaw (`basePose`).
  const std::vector<int> twins = mirroredMuscles(skin);
  // `symmetric`: a shape without sides (jawOpen, mouthPucker, browInnerUp, mouthClose...) is its own
  // mirror image by definition, so it is fitted as a pair with itself — A a against it and A_twin a
  // against it again. The objective is then unchanged by a → twin(a), and its minimiser (unique where
  // the columns are independent) is its own mirror: the entry drives each muscle as its twin, and an
  // asymmetry of the head (ICT's lower ring) cannot tip a midline shape onto one side's muscles.
  auto fitShape = [&](RigShapeFit& s, RigShapeFit* mirror, const JawPose* basePose, bool symmetric) {
    auto motionOf = [&](const JawPose& p) { return p.isZero() ? MatX3::Zero(n, 3) : MatX3(jawedRest(*jaw, p, rest) - rest); };
    // The fit (and its mirror's) with the jaw in pose p (at rest on a head without the jaw).
    auto fitWithJaw = [&](const JawPose& p) {
      const MatX3 motion = jaw ? motionOf(p) : MatX3::Zero(n, 3);
      FitTarget t;
      t.displacement = s.target - motion;
      MirroredFit f;
      if (mirror) {
        const JawPose q = mirroredPose(p);
        const MatX3 mirrorMotion = jaw ? motionOf(q) : MatX3::Zero(n, 3);
        FitTarget tm;
        tm.displacement = mirror->target - mirrorMotion;
        f = fitMirroredActivations(skin, t, tm, twins, settings, &placement, &columns);
        if (!q.isZero()) remeasure(f.mirrorFit, mirrorMotion, mirror->target, rest, settings.threshold);
      } else if (symmetric) {
        f.fit = std::move(fitMirroredActivations(skin, t, t, twins, settings, &placement, &columns).fit);
      } else {
        f.fit = fitActivations(skin, t, settings, &placement, &columns);
      }
      if (!p.isZero()) remeasure(f.fit, motion, s.target, rest, settings.threshold);
      return f;
    };
    auto misfit = [&](const MirroredFit& f) {  // summed over the pair
      double sum = (f.fit.displacement - s.target).squaredNorm();
      if (mirror) sum += (f.mirrorFit.displacement - mirror->target).squaredNorm();
      return sum;
    };
    JawPose pose;
    const JawDof dof = jawDofOf(s.name);
    if (jaw && dof.index >= 0)
      pose = poseOf(dof.index, goldenSection([&](double v) { return misfit(fitWithJaw(poseOf(dof.index, v))); }, dof.lo, dof.hi));
    if (jaw && basePose) pose = *basePose;
    MirroredFit f = fitWithJaw(pose);
    s.fit = std::move(f.fit);
    if (mirror) mirror->fit = std::move(f.mirrorFit);
    return pose;
  };
  // Each left/right pair the rig has both sides of (mirroredArkitName: mouthSmileLeft and
  // mouthSmileRight, mouthLeft and mouthRight, jawLeft and jawRight) is one fit, the right shape's
  // entry exactly the mirror of the left's, when every fitted muscle has its twin; other shapes alone.
  // A side whose target is zero is a name the rig does not make (a rig written for all 52 names
  // holds zeros for the others): its twin is fitted alone, not pulled towards nothing.
  bool twinned = true;  // every fitted muscle's twin is fitted too
  {
    std::vector<int> fitted;
    for (const std::string& name : settings.muscles) fitted.push_back(skin.muscleIndex(name));
    if (settings.muscles.empty())
      for (size_t k = 0; k < twins.size(); ++k) fitted.push_back(static_cast<int>(k));
    for (const int k : fitted)
      twinned = twinned && twins[static_cast<size_t>(k)] >= 0 &&
                std::find(fitted.begin(), fitted.end(), twins[static_cast<size_t>(k)]) != fitted.end();
  }
  std::vector<size_t> mirrorOf(shapes.size(), shapes.size());  // the right shape fitted with shape i
  std::vector<bool> fittedByItsTwin(shapes.size(), false);
  for (size_t i = 0; twinned && i < shapes.size(); ++i) {
    const std::optional<std::string> twin = mirroredArkitName(shapes[i].name);
    if (!twin || !shapes[i].name.ends_with("Left") || !shapes[i].reachable || !shapes[i].correctiveOf.empty()) continue;
    const size_t j = indexOf(*twin);
    if (j == shapes.size() || !shapes[j].reachable || !shapes[j].correctiveOf.empty()) continue;
    if (shapes[i].target.isZero(0.0) || shapes[j].target.isZero(0.0)) continue;
    mirrorOf[i] = j;
    fittedByItsTwin[j] = true;
    shapes[i].pairedWith = shapes[j].name;
    shapes[j].pairedWith = shapes[i].name;
  }
  // The shapes and pairs are independent of each other (the skin is read only): side by side on
  // parallelThreads(), each into its own slots; then the corrective on its fitted base.
  std::vector<JawPose> poses(shapes.size());
  parallelFor(static_cast<std::int64_t>(shapes.size()), [&](std::int64_t i) {
    const auto k = static_cast<size_t>(i);
    RigShapeFit& s = shapes[k];
    if (!s.reachable || !s.correctiveOf.empty() || fittedByItsTwin[k]) return;
    const size_t j = mirrorOf[k];
    poses[k] = fitShape(s, j < shapes.size() ? &shapes[j] : nullptr, nullptr, twinned && !mirroredArkitName(s.name));
    if (j < shapes.size()) poses[j] = mirroredPose(poses[k]);
  });
  for (size_t i = 0; i < shapes.size(); ++i) {
    RigShapeFit& s = shapes[i];
    if (!s.reachable || s.correctiveOf.empty()) continue;
    const size_t base = indexOf(s.correctiveOf);
    s.target += shapes[base].target;  // the corrective only makes sense on its base
    poses[i] = fitShape(s, nullptr, &poses[base], twinned && !mirroredArkitName(s.name));
  }

  std::vector<double> cosines, rms;
  // One fitted shape's entry (shapes[i]), with its figures counted for the medians.
  auto fittedEntry = [&](size_t i) {
    RigShapeFit& s = shapes[i];
    RetargetShape entry;
    entry.name = s.name;
    if (!s.reachable) {
      entry.reachable = false;
      entry.reason = s.reason;
    } else {
      const RigShapeFit* base = s.correctiveOf.empty() ? nullptr : &shapes[indexOf(s.correctiveOf)];
      const JawPose& pose = poses[i];
      if (!base) {  // a corrective's jaw is its base's: it adds none
        if (pose.openDeg != 0.0) entry.jaw.emplace_back("open", pose.openDeg);
        if (pose.forwardCm != 0.0) entry.jaw.emplace_back("forward", pose.forwardCm);
        if (pose.lateralCm != 0.0) entry.jaw.emplace_back("lateral", pose.lateralCm);
      }
      entry.correctiveOf = s.correctiveOf;
      VecX a = s.fit->activations;
      if (base) a -= base->fit->activations;
      entry.activations = namedActivations(skin, a);
      // The cosine clamped: round-off can put a perfect fit at 1 + 1e-16.
      entry.fit = RetargetFitFigures{std::clamp(s.fit->metric.cosine, -1.0, 1.0), s.fit->metric.magnitudeRatio, s.fit->rmsMm,
                                     s.fit->maxMm};
      if (s.fit->metric.comparedVertices > 0) {  // a shape that moves nothing has no figures to count
        cosines.push_back(s.fit->metric.cosine);
        rms.push_back(s.fit->rmsMm);
      }
    }
    out.map.shapes.push_back(std::move(entry));
  };
  out.map.model = "anatomical";
  // Every ARKit name in ARKit's order: the rig's shapes fitted, the others unreachable with their
  // reason or derived from their FACS units (facs_route.h).
  const std::vector<std::string> muscleNames = skin.muscleNames();
  size_t next = 0;  // the next fitted shape (shapes are in ARKit order)
  for (const std::string& name : arkitNames()) {
    if (next < shapes.size() && shapes[next].name == name) {
      fittedEntry(next++);
      continue;
    }
    if (const std::optional<std::string> reason = unreachableReason(name)) {
      RetargetShape entry;
      entry.name = name;
      entry.reachable = false;
      entry.reason = *reason;
      out.map.shapes.push_back(std::move(entry));
    } else if (std::optional<RetargetShape> derived = derivedRetargetShape(facs, name, muscleNames)) {
      out.map.shapes.push_back(std::move(*derived));
      out.derived.push_back(name);
    }
  }
  MYO_CHECK(next == shapes.size(), "fitRig: the fitted shapes are not in ARKit order");
  out.shapes = std::move(shapes);
  out.medianCosine = median(cosines);
  out.medianRmsMm = median(rms);
  out.seconds = clock.seconds();
  return out;
}

}  // namespace myo
