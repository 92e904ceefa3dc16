#include "myoshell/face/rig_fit.h"

#include <algorithm>
#include <map>

#include "myoshell/core/errors.h"
#include "myoshell/core/timer.h"
#include "myoshell/face/arkit_names.h"

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

}  // namespace

RigFit fitRig(const AnatomicalSkin& skin, const std::vector<RigTarget>& targets, const FitSettings& settings) {
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

  std::vector<double> cosines, rms;
  out.map.model = "anatomical";
  for (const std::string& name : arkitNames()) {
    auto it = byName.find(name);
    if (it == byName.end()) continue;
    RigShapeFit s = std::move(it->second);
    RetargetShape entry;
    entry.name = name;
    if (const std::optional<std::string> reason = unreachableReason(name)) {
      s.reachable = false;
      s.reason = *reason;
      entry.reachable = false;
      entry.reason = *reason;
    } else {
      // jawOpen comes before mouthClose in ARKit order: fitted already.
      const RigShapeFit* base = nullptr;
      if (name == "mouthClose") {
        s.correctiveOf = "jawOpen";
        base = &*std::find_if(out.shapes.begin(), out.shapes.end(), [](const RigShapeFit& f) { return f.name == "jawOpen"; });
        s.target += base->target;  // the corrective only makes sense on its base
      }
      FitTarget target;
      target.displacement = s.target;
      s.fit = fitActivations(skin, target, settings);
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
    out.shapes.push_back(std::move(s));
  }
  out.medianCosine = median(cosines);
  out.medianRmsMm = median(rms);
  out.seconds = clock.seconds();
  return out;
}

}  // namespace myo
