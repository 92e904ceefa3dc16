#include "myoshell/thesis/face_model.h"

#include <algorithm>
#include <Eigen/SparseCholesky>
#include <cmath>
#include <memory>
#include <optional>

#include "myoshell/core/check.h"
#include "myoshell/core/errors.h"
#include "myoshell/core/parallel.h"
#include "myoshell/core/timer.h"
#include "myoshell/mesh/closest_point.h"
#include "myoshell/mesh/edge_table.h"
#include "myoshell/thesis/simulator.h"

#include "myoshell/reduce/modal_analysis.h"
#include "myoshell/reduce/rotation_operator.h"

namespace myo {

void FaceModelSettings::validate() const {
  skin.validate();
  muscle.validate();
  auto bad = [](const std::string& what) { throw InputError("face model: " + what); };
  if (skinModes < 1) bad("skin modes must be ≥ 1 (got " + std::to_string(skinModes) + ")");
  if (muscleModes < 1) bad("muscle modes must be ≥ 1 (got " + std::to_string(muscleModes) + ")");
  if (!(roiAlpha > 1.0)) bad("ROI α must be > 1 (thesis eq. 19; got " + std::to_string(roiAlpha) + ")");
  if (!(springStiffness > 0.0) || !std::isfinite(springStiffness)) bad("spring stiffness must be > 0");
  if (!(dt > 0.0) || !std::isfinite(dt)) bad("dt must be > 0 (got " + std::to_string(dt) + ")");
  if (!(skinDampingMass >= 0.0) || !(skinDampingStiffness >= 0.0)) bad("skin damping must be ≥ 0");
  if (!(muscleDampingRatio >= 0.0)) bad("muscle damping ratio must be ≥ 0");
  if (!std::isfinite(gravityAcceleration)) bad("gravity is not finite");
}

namespace {

// The activation load pattern of a muscle: a unit force along the contraction direction on each
// central node, as a free f×3 field of `basis`.
MatX3 activationPattern(const Muscle& muscle, const std::vector<int>& fullToFree, int freeCount) {
  MatX3 P = MatX3::Zero(freeCount, 3);
  for (size_t c = 0; c < muscle.centralNodes.size(); ++c) {
    const int row = fullToFree[static_cast<size_t>(muscle.centralNodes[c])];
    if (row >= 0) P.row(row) += muscle.contractDirection.row(static_cast<Eigen::Index>(c));
  }
  return P;
}

// A one-column basis: mode j of `full`.
ModalBasis singleMode(const ModalBasis& full, int j) {
  ModalBasis one;
  one.fullVertexCount = full.fullVertexCount;
  one.freeVertices = full.freeVertices;
  one.freeMass = full.freeMass;
  one.Phi = full.Phi.col(j);
  one.Psi = full.Psi.col(j);
  one.lambda = VecX::Constant(1, full.lambda(j));
  one.solver = full.solver;
  one.fromCache = full.fromCache;
  return one;
}

// The static-shape variant (METHOD.md §8): the muscle's one mode is its static response to the
// activation load, K_FF⁻¹P, mass-normalized; used when none of the low modes carries the load.
ModalBasis staticShapeMode(const ModalBasis& full, const DiscreteShell& shell, const MatX3& P) {
  const SparseMat Kff = restrictToFree(shell.stiffnessAtRest(), full.freeVertices, shell.vertexCount());
  Eigen::SimplicialLDLT<SparseMat> solver(Kff);
  if (solver.info() != Eigen::Success) throw NumericalError("muscle stiffness is singular (origin not pinned?)");
  const VecX x = solver.solve(flat(P));
  VecX m3(x.size());
  for (int i = 0; i < full.freeCount(); ++i) m3.segment<3>(3 * i).setConstant(full.freeMass(i));
  const VecX phi = x / std::sqrt(x.dot(m3.cwiseProduct(x)));
  ModalBasis one;
  one.fullVertexCount = full.fullVertexCount;
  one.freeVertices = full.freeVertices;
  one.freeMass = full.freeMass;
  one.Phi = phi;
  one.lambda = VecX::Constant(1, phi.dot(Kff * phi));
  one.Psi = modalRotationMatrix(shell.rest(), shell.triangles(), full.freeVertices, one.Phi);
  one.solver = "static-shape";
  return one;
}

ModalSettings modalSettings(int modes) {
  ModalSettings s;
  s.modeCount = modes;
  return s;
}

// One basis problem of the build: a shell, its pinned vertices, its mode count.
struct BasisJob {
  const DiscreteShell* shell = nullptr;
  std::vector<int> pins;
  int modes = 0;
  bool sameAs(const BasisJob& o) const { return shell == o.shell && pins == o.pins && modes == o.modes; }
};

// What computeModalBasis sees of the cache while it runs on a worker thread: the entry read for it
// beforehand, and a slot that keeps what it would store until the calling thread stores it.
class PreloadedCache final : public BasisCache {
 public:
  std::optional<ModalBasis> entry;
  std::optional<ModalBasis> toStore;
  std::optional<ModalBasis> load(const BasisKey&) override { return std::move(entry); }
  void store(const BasisKey&, const ModalBasis& basis) override { toStore = basis; }
};

// The bases of `jobs`, solved side by side on parallelThreads() (core/parallel.h). The cache is
// reached from the calling thread only: every entry read in job order first, then the misses solved
// in parallel, then stored in job order. A cache that processes share holds a key's lock from its
// miss to its store (io/basis_cache_file.h), so taking the keys in one order, never while waiting
// for another thread, keeps processes from waiting on each other in a cycle. A job equal to an
// earlier one comes after the store and reads it back, as a serial build would (a cache hit).
std::vector<ModalBasis> solveBases(const std::vector<BasisJob>& jobs, BasisCache* cache, int& hits) {
  std::vector<ModalBasis> out(jobs.size());
  std::vector<size_t> firsts, repeats;
  for (size_t j = 0; j < jobs.size(); ++j)
    (std::any_of(jobs.begin(), jobs.begin() + static_cast<std::ptrdiff_t>(j), [&](const BasisJob& o) { return o.sameAs(jobs[j]); })
         ? repeats
         : firsts)
        .push_back(j);
  auto run = [&](size_t j, BasisCache* c) {
    const BasisJob& job = jobs[j];
    out[j] = computeModalBasis(*job.shell, job.pins, modalSettings(job.modes), c);
  };
  std::vector<PreloadedCache> slots(firsts.size());
  if (cache)
    for (size_t k = 0; k < firsts.size(); ++k) {
      const BasisJob& job = jobs[firsts[k]];
      slots[k].entry = cache->load(modalBasisKey(*job.shell, job.pins, modalSettings(job.modes)));
    }
  parallelFor(static_cast<std::int64_t>(firsts.size()), [&](std::int64_t k) {
    run(firsts[static_cast<size_t>(k)], cache ? &slots[static_cast<size_t>(k)] : nullptr);
  });
  if (cache)
    for (size_t k = 0; k < firsts.size(); ++k)
      if (slots[k].toStore) {
        const BasisJob& job = jobs[firsts[k]];
        cache->store(modalBasisKey(*job.shell, job.pins, modalSettings(job.modes)), *slots[k].toStore);
      }
  for (size_t j : repeats) run(j, cache);
  for (const ModalBasis& b : out) hits += b.fromCache ? 1 : 0;
  return out;
}

}  // namespace

FaceModel::FaceModel(Head head, const std::vector<MuscleDef>& defs, const FaceModelSettings& settings,
                     BasisCache* cache)
    : head_(std::move(head)),
      settings_(settings),
      skin_(head_.mesh.V, head_.mesh.F, buildEdgeTable(head_.mesh.F, head_.mesh.vertexCount()), settings.skin) {
  settings_.validate();
  Stopwatch clock;
  const int n = head_.mesh.vertexCount();
  const MatX3& skinRest = head_.mesh.V;
  int cacheHits = 0;
  auto complement = [n](const std::vector<int>& keep) {
    std::vector<char> in(static_cast<size_t>(n), 0);
    for (int v : keep) in[static_cast<size_t>(v)] = 1;
    std::vector<int> out;
    for (int v = 0; v < n; ++v)
      if (!in[static_cast<size_t>(v)]) out.push_back(v);
    return out;
  };

  for (const MuscleDef& def : defs)
    if (def.isRing())
      throw InputError("muscle '" + def.name + "': a ring muscle (a sphincter) is played by the anatomical model only "
                       "(\"model\": \"anatomical\"); the thesis's muscles are linear");
  // Each muscle's unit (its shell, eigen-solve, stretch mode, springs, ROI) is independent of the
  // others: built side by side, the eigen-solves through solveBases.
  muscles_.resize(defs.size());
  parallelFor(static_cast<std::int64_t>(defs.size()), [&](std::int64_t index) {
    MuscleUnit& unit = muscles_[static_cast<size_t>(index)];
    unit.muscle = buildMuscle(defs[static_cast<size_t>(index)], head_);
    const TriMesh& mm = unit.muscle.mesh;
    unit.shell = std::make_shared<const DiscreteShell>(mm.V, mm.F, buildEdgeTable(mm.F, mm.vertexCount()),
                                                       settings_.muscle);
  });
  // Eq. 11–12: the pinned muscle's d lowest modes; keep the one that carries the activation load.
  std::vector<BasisJob> muscleJobs;
  for (const MuscleUnit& unit : muscles_) {
    const int free = unit.muscle.mesh.vertexCount() - static_cast<int>(unit.muscle.originNodes.size());
    muscleJobs.push_back({unit.shell.get(), unit.muscle.originNodes, std::min(settings_.muscleModes, 3 * free)});
  }
  const std::vector<ModalBasis> muscleBases = solveBases(muscleJobs, cache, cacheHits);
  parallelFor(static_cast<std::int64_t>(defs.size()), [&](std::int64_t index) {
    const MuscleDef& def = defs[static_cast<size_t>(index)];
    MuscleUnit& unit = muscles_[static_cast<size_t>(index)];
    const TriMesh& mm = unit.muscle.mesh;
    const ModalBasis& full = muscleBases[static_cast<size_t>(index)];
    const std::vector<int> toFree = full.fullToFree();
    const MatX3 P = activationPattern(unit.muscle, toFree, full.freeCount());
    const LoadParticipation lp = loadParticipation(full, *unit.shell, P);
    unit.modeParticipation.assign(lp.perMode.data(), lp.perMode.data() + lp.perMode.size());
    for (double& p : unit.modeParticipation) p /= lp.total;
    const Vec3 axis = (unit.muscle.originPoint - unit.muscle.insertionPoint).normalized();
    const auto& insertion = unit.muscle.insertionNodes;
    // Static displacement of the insertion ring along the muscle per dyn of activation force, if
    // the muscle moved only in basis column j of B.
    auto insertionAlongPerDyn = [&](const ModalBasis& B, int j) {
      const double qPerDyn = B.Phi.col(j).dot(flat(P)) / B.lambda(j);
      double along = 0.0;
      for (int v : insertion) {
        const int row = toFree[static_cast<size_t>(v)];
        if (row >= 0) along += B.Phi.col(j).segment<3>(3 * row).dot(axis) * qPerDyn / static_cast<double>(insertion.size());
      }
      return along;
    };
    // The stretch mode: the one carrying most of the activation load's compliance among the modes
    // that pull the insertion towards the origin (a bending mode of a curved muscle can carry load
    // while swinging the insertion sideways or back).
    int best = -1;
    for (int j = 0; j < full.modeCount(); ++j)
      if (insertionAlongPerDyn(full, j) > 0 &&
          (best < 0 || unit.modeParticipation[static_cast<size_t>(j)] > unit.modeParticipation[static_cast<size_t>(best)]))
        best = j;
    ModalBasis one;
    if (best >= 0 && unit.modeParticipation[static_cast<size_t>(best)] >= 0.5) {
      one = singleMode(full, best);
      unit.stretchModeIndex = best;
      unit.stretchParticipation = unit.modeParticipation[static_cast<size_t>(best)];
    } else {
      one = staticShapeMode(full, *unit.shell, P);
      unit.stretchModeIndex = -1;
      unit.stretchParticipation = 1.0;  // the static shape carries all of the static compliance
    }
    // Calibrate the maximum force (eq. 13's "magnitude set manually", made reproducible): at a = 1
    // the static linear response moves the insertion ring by contraction·length along the muscle.
    const double alongPerDyn = insertionAlongPerDyn(one, 0);
    const double qPerDyn = one.Phi.col(0).dot(flat(P)) / one.lambda(0);
    if (!(alongPerDyn > 0.0))
      throw NumericalError("muscle '" + def.name + "': its stretch mode does not move the insertion towards the origin");
    unit.maxForce = def.contraction * unit.muscle.restLength / alongPerDyn;
    unit.fullAmplitude = unit.maxForce * qPerDyn;
    for (int c : unit.muscle.centralNodes) unit.centralFreeRows.push_back(toFree[static_cast<size_t>(c)]);
    unit.basis = std::make_shared<const ModalBasis>(std::move(one));

    // Springs (eq. 14–16) and ROI (eq. 19).
    unit.springStiffness = def.springStiffness > 0 ? def.springStiffness : settings_.springStiffness;
    unit.roiAlpha = def.roiAlpha > 0 ? def.roiAlpha : settings_.roiAlpha;
    std::vector<char> inRoi(static_cast<size_t>(n), 0);
    for (int i = 0; i < mm.vertexCount(); ++i) {
      const Vec3 m = mm.V.row(i);
      MuscleUnit::Spring s;
      s.muscleNode = i;
      s.muscleFreeRow = toFree[static_cast<size_t>(i)];
      s.skinVertex = nearestVertex(skinRest, m);
      s.restVector = m - Vec3(skinRest.row(s.skinVertex));
      const double reach = unit.roiAlpha * s.restVector.norm();
      if (!(s.restVector.norm() > 0))
        throw InputError("muscle '" + def.name + "': node " + std::to_string(i) + " lies on the skin (depth must be > 0)");
      for (int v = 0; v < n; ++v)
        if ((Vec3(skinRest.row(v)) - m).norm() < reach) inRoi[static_cast<size_t>(v)] = 1;
      unit.springs.push_back(s);
    }
    for (int v = 0; v < n; ++v)
      if (inRoi[static_cast<size_t>(v)]) unit.roi.push_back(v);
  });

  // Skin channels: one per muscle (non-ROI pinned), gravity, one per drag (eq. 20–25). The skin's
  // K is assembled once for all the load-participation reports.
  const SparseMat skinK = settings_.measureLoadParticipation ? skin_.stiffnessAtRest() : SparseMat();
  auto participation = [&](const ModalBasis& basis, const MatX3& load) {
    if (!settings_.measureLoadParticipation) return -1.0;
    if (load.squaredNorm() == 0.0) return 0.0;
    return loadParticipation(basis, restrictToFree(skinK, basis.freeVertices, n), load).ratio;
  };
  for (const DragDef& drag : settings_.drags)
    if (drag.vertex < 0 || drag.vertex >= n)
      throw InputError("drag '" + drag.name + "': vertex " + std::to_string(drag.vertex) + " is outside [0, " +
                       std::to_string(n) + ")");
  // Every channel's pins (muscles' ROI complements, gravity's, the drags'), then their bases in parallel.
  std::vector<std::vector<int>> channelPins;
  for (const MuscleUnit& unit : muscles_) channelPins.push_back(complement(unit.roi));
  if (settings_.gravity) channelPins.push_back(gravityPins());
  for (const DragDef& drag : settings_.drags) channelPins.push_back(drag.pins.empty() ? gravityPins() : drag.pins);
  std::vector<BasisJob> channelJobs;
  for (std::vector<int>& pins : channelPins) channelJobs.push_back({&skin_, std::move(pins), settings_.skinModes});
  std::vector<std::shared_ptr<const ModalBasis>> channelBases;
  for (ModalBasis& b : solveBases(channelJobs, cache, cacheHits)) channelBases.push_back(std::make_shared<const ModalBasis>(std::move(b)));
  size_t nextBasis = 0;
  for (size_t m = 0; m < muscles_.size(); ++m) {
    MuscleUnit& unit = muscles_[m];
    SkinChannel ch;
    ch.name = unit.muscle.def.name;
    ch.kind = ChannelKind::Muscle;
    ch.source = static_cast<int>(m);
    ch.basis = channelBases[nextBasis++];
    const std::vector<int> toFree = ch.basis->fullToFree();
    // The typical load: the springs' pull when the muscle sits at its a = 1 static state.
    MatX3 load = MatX3::Zero(ch.basis->freeCount(), 3);
    for (auto& s : unit.springs) {
      s.skinFreeRow = toFree[static_cast<size_t>(s.skinVertex)];
      if (s.muscleFreeRow < 0 || s.skinFreeRow < 0) continue;
      load.row(s.skinFreeRow) +=
          (unit.fullAmplitude * unit.basis->Phi.col(0).segment<3>(3 * s.muscleFreeRow)).transpose();
    }
    ch.loadParticipation = participation(*ch.basis, load);
    unit.skinChannel = static_cast<int>(channels_.size());
    channels_.push_back(std::move(ch));
  }
  if (settings_.gravity) {
    SkinChannel ch;
    ch.name = "gravity";
    ch.kind = ChannelKind::Gravity;
    ch.basis = channelBases[nextBasis++];
    MatX3 load = MatX3::Zero(ch.basis->freeCount(), 3);
    load.col(1) = -settings_.gravityAcceleration * ch.basis->freeMass;
    ch.loadParticipation = participation(*ch.basis, load);
    gravityChannel_ = static_cast<int>(channels_.size());
    channels_.push_back(std::move(ch));
  }
  for (size_t d = 0; d < settings_.drags.size(); ++d) {
    const DragDef& drag = settings_.drags[d];
    SkinChannel ch;
    ch.name = drag.name;
    ch.kind = ChannelKind::Drag;
    ch.source = static_cast<int>(d);
    ch.basis = channelBases[nextBasis++];
    const std::vector<int> toFree = ch.basis->fullToFree();
    const Vec3 centre = skinRest.row(drag.vertex);
    for (int v = 0; v < n; ++v)
      if ((Vec3(skinRest.row(v)) - centre).norm() <= drag.radius && toFree[static_cast<size_t>(v)] >= 0)
        ch.dragRows.push_back(toFree[static_cast<size_t>(v)]);
    if (ch.dragRows.empty())
      throw InputError("drag '" + drag.name + "': no free skin vertex within " + std::to_string(drag.radius) +
                       " cm of vertex " + std::to_string(drag.vertex) + " (is it pinned?)");
    MatX3 load = MatX3::Zero(ch.basis->freeCount(), 3);
    for (int r : ch.dragRows) load.row(r) = head_.frame().axes.col(0).transpose();  // sideways pull
    ch.loadParticipation = participation(*ch.basis, load);
    channels_.push_back(std::move(ch));
  }
  cacheHits_ = cacheHits;
  buildSeconds_ = clock.seconds();
}

std::vector<int> FaceModel::gravityPins() const {
  std::vector<int> pins = head_.gravityPins;
  if (settings_.gravityPinsLandmarks)
    for (const auto& [name, v] : head_.landmarks.resolved()) pins.push_back(v);
  std::sort(pins.begin(), pins.end());
  pins.erase(std::unique(pins.begin(), pins.end()), pins.end());
  return pins;
}

bool addSpringForces(const MuscleUnit& unit, const MatX3& muscleU, SpringModel model, MatX3& channelForce) {
  bool loaded = false;
  for (const auto& s : unit.springs) {
    if (s.muscleFreeRow < 0 || s.skinFreeRow < 0) continue;  // origin nodes never move
    const Vec3 u = muscleU.row(s.muscleFreeRow);
    const double moved = u.norm();
    if (moved < 1e-14) continue;  // eq. 16's direction is undefined at rest: no force
    const double restLength = s.restVector.norm();
    // Thesis eq. 15: k·||S_d| − |S_init||/|S_init| with S_d = S_init + u_m (the skin node at rest);
    // the named variant: k·|u_m|/|S_init|. Both along u_m (eq. 16).
    const double magnitude = model == SpringModel::Thesis
                                 ? unit.springStiffness * std::abs((s.restVector + u).norm() - restLength) / restLength
                                 : unit.springStiffness * moved / restLength;
    channelForce.row(s.skinFreeRow) += (magnitude / moved) * u.transpose();
    loaded = true;
  }
  return loaded;
}

int FaceModel::muscleIndex(const std::string& name) const {
  for (size_t m = 0; m < muscles_.size(); ++m)
    if (muscles_[m].muscle.def.name == name) return static_cast<int>(m);
  std::string known;
  for (const auto& u : muscles_) known += (known.empty() ? "" : ", ") + u.muscle.def.name;
  throw InputError("unknown muscle '" + name + "' (this face has: " + known + ")");
}

}  // namespace myo

namespace myo {

std::vector<std::string> FaceModel::channelNames() const {
  std::vector<std::string> names;
  for (const SkinChannel& c : channels_) names.push_back(c.name);
  return names;
}

std::unique_ptr<FaceStepper> FaceModel::makeStepper(std::shared_ptr<const FaceSystem> self) const {
  auto model = std::dynamic_pointer_cast<const FaceModel>(self);
  MYO_CHECK(model.get() == this, "makeStepper: self must be this face");
  return std::make_unique<Simulator>(std::move(model));
}

}  // namespace myo
