#include "myoshell/anatomy/anatomical_skin.h"

#include <Eigen/Dense>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <optional>
#include "myoshell/core/check.h"
#include "myoshell/core/errors.h"
#include "myoshell/core/timer.h"
#include "myoshell/mesh/closest_point.h"
#include "myoshell/mesh/edge_table.h"
#include "myoshell/mesh/geometry.h"
#include "myoshell/reduce/modal_analysis.h"
#include "myoshell/reduce/rotation_operator.h"

namespace myo {

namespace {

Mat3 skew(const Vec3& v) {
  Mat3 S;
  S << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return S;
}

double meanEdgeLength(const MatX3& V, const MatX3i& F) {
  double sum = 0.0;
  for (Eigen::Index t = 0; t < F.rows(); ++t)
    for (int k = 0; k < 3; ++k) sum += (V.row(F(t, k)) - V.row(F(t, (k + 1) % 3))).norm();
  return sum / (3.0 * static_cast<double>(F.rows()));
}

}  // namespace

AnatomicalSkin::AnatomicalSkin(const Head& head, const std::vector<MuscleDef>& defs, const AnatomicalSettings& settings)
    : AnatomicalSkin(head, defs, settings, {}, nullptr) {}

AnatomicalSkin::AnatomicalSkin(const Head& head, const std::vector<MuscleDef>& defs, const AnatomicalSettings& settings,
                               const std::vector<DragSite>& dragSites, BasisCache* cache)
    : head_(head), settings_(settings) {
  settings_.validate();
  const MatX3& V = head_.mesh.V;
  const MatX3i& F = head_.mesh.F;
  const int n = head_.mesh.vertexCount();
  shell_ = std::make_unique<DiscreteShell>(V, F, buildEdgeTable(F, n),
                                           anatomicalSkinMaterial(settings_, meanEdgeLength(V, F)));
  tissue_ = tissueMap(head_, settings_.attachment);
  applyAttachmentOverrides(tissue_, settings_.attachmentOverrides);
  mass_ = tissue_.vertexMass();
  for (int i = 0; i < n; ++i)  // a vertex in no triangle carries nothing: give it a tiny mass
    if (!(mass_(i) > 0)) mass_(i) = 1e-12;

  std::vector<Triplet> trip;
  // One closest-point locator over the skin for every muscle's placement and couplings.
  const std::optional<SurfaceLocator> skinSurface =
      defs.empty() ? std::nullopt : std::optional<SurfaceLocator>(std::in_place, V, F, vertexNormals(V, F));
  for (const MuscleDef& def : defs) {
    for (const CoupledMuscle& m : muscles_)
      if (m.muscle.def.name == def.name) throw InputError("anatomical model: muscle '" + def.name + "' is defined twice");
    muscles_.push_back(coupleMuscle(def, head_, settings_.coupling, &*skinSurface));
    addCouplingStiffness(muscles_.back(), trip);
    couplingLoads_.push_back(couplingLoad(muscles_.back(), n));
  }
  muscleLoads_ = couplingLoads_;
  SparseMat Kc(3 * n, 3 * n);
  Kc.setFromTriplets(trip.begin(), trip.end());
  // K_att, the forehead column's volume (docs/muscles.md, "The forehead's column keeps its volume")
  // and the couplings.
  Kextra_ = tissue_.stiffness() + foreheadColumnStiffness(head_, tissue_, settings_.attachment.foreheadColumnStiffness) + Kc;
  for (int i = 0; i < n; ++i)  // isolated vertices: hold them so K̂ stays positive definite
    if (!(tissue_.area(i) > 0))
      for (int c = 0; c < 3; ++c) Kextra_.coeffRef(3 * i + c, 3 * i + c) += 1.0;
  Khat_ = shell_->stiffnessAtRest() + Kextra_;
  Khat_.makeCompressed();
  gRest_ = Vec3(0.0, -settings_.gravity, 0.0);
  for (const DragSite& site : dragSites) drags_.push_back({dragVertices(site.vertex, site.radius)});

  ritz_.modes.modeCount = std::min(settings_.skinModes, 3 * n);
  buildReleaseColumns();
  // The placement (jaw, lids, contact) and the contact's load patterns, whose static responses join
  // the basis (docs/mouth_contact.md, "Penalty forces"). The switch does not change the basis.
  std::vector<std::string> names;
  for (const CoupledMuscle& m : muscles_) names.push_back(m.muscle.def.name);
  placement_ = std::make_shared<const SkinPlacement>(head_, names, settings_.contact);
  contactLoads_ = contactLoadPatterns(*placement_, V, mass_);
  buildModiolusPatterns();
  // The build sequence (the basis depends on it): muscle loads, gravity x, y, z, the extra columns
  // of the release, diagonalise; then per drag its x, y, z patterns and diagonalise (as addDrag).
  // Bump when the sequence changes.
  constexpr int kSequenceVersion = 2;
  KeyHasher h;
  h.str("myoshell.anatomical_skin_basis").pod(kModalBasisFormatVersion).pod(kSequenceVersion);
  const int64_t nv = n, nt = F.rows();
  h.pod(nv).bytes(V.data(), sizeof(double) * static_cast<size_t>(V.size()));
  h.pod(nt).bytes(F.data(), sizeof(int) * static_cast<size_t>(F.size()));
  const int64_t nnz = Khat_.nonZeros();
  h.pod(nnz).bytes(Khat_.outerIndexPtr(), sizeof(SparseMat::StorageIndex) * static_cast<size_t>(Khat_.outerSize() + 1));
  h.bytes(Khat_.innerIndexPtr(), sizeof(SparseMat::StorageIndex) * static_cast<size_t>(nnz));
  h.bytes(Khat_.valuePtr(), sizeof(double) * static_cast<size_t>(nnz));
  h.bytes(mass_.data(), sizeof(double) * static_cast<size_t>(n));
  const ModalSettings& ms = ritz_.modes;
  h.pod(ms.modeCount).pod(static_cast<int>(ms.solver)).pod(ms.denseMaxDofs).pod(ms.shift).pod(ms.tolerance);
  h.pod(ms.maxIterations).pod(ms.ncvMin).pod(ritz_.deflationTolerance);
  h.pod(static_cast<int64_t>(muscleLoads_.size()));
  for (const MatX3& f : muscleLoads_) h.bytes(f.data(), sizeof(double) * static_cast<size_t>(f.size()));
  h.pod(static_cast<int64_t>(drags_.size()));  // gravity's patterns are M·ê_a (the masses are in)
  for (const Drag& d : drags_)
    h.pod(static_cast<int64_t>(d.vertices.size())).bytes(d.vertices.data(), sizeof(int) * d.vertices.size());
  h.pod(static_cast<int64_t>(extraReleaseColumns_));
  for (int j = 0; j < extraReleaseColumns_; ++j) {
    const VecX col = releaseColumns_.col(releaseColumns_.cols() - extraReleaseColumns_ + j);
    h.bytes(col.data(), sizeof(double) * static_cast<size_t>(col.size()));
  }
  for (size_t m = 0; m < muscles_.size(); ++m)  // the release columns along another shape (buildHeldBasis)
    if (muscles_[m].releaseShape.rows() > 0 && releaseColumns_.cols() > 0) {
      const VecX col = releaseColumns_.col(static_cast<Eigen::Index>(m));
      h.str("release shape").pod(static_cast<int64_t>(m)).bytes(col.data(), sizeof(double) * static_cast<size_t>(col.size()));
    }
  if (!contactLoads_.empty()) {  // absent (a head with nothing to touch): the key as before contact
    h.str("contact").pod(static_cast<int64_t>(contactLoads_.size()));
    for (const MatX3& f : contactLoads_) h.bytes(f.data(), sizeof(double) * static_cast<size_t>(f.size()));
  }
  if (!modiolusLoads_.empty()) {  // absent (no hoop band): the key as before
    h.str("modioli").pod(static_cast<int64_t>(modiolusLoads_.size()));
    for (const MatX3& f : modiolusLoads_) h.bytes(f.data(), sizeof(double) * static_cast<size_t>(f.size()));
  }
  key_ = h.key();

  // The cache keeps two bases: the held one (key_: what a drag grabbed later and the full-space
  // response build on) and the released one the model steps in (releasedKey_), so that a warm start
  // reads only the smaller one; the held one is read (or rebuilt) when something needs it.
  const bool released = releaseColumns_.cols() > 0;
  if (released) {
    constexpr int kReleaseVersion = 2;  // bump when releaseRelaxedMuscles changes what it computes
    KeyHasher r;
    r.str("myoshell.anatomical_skin_released").pod(kReleaseVersion).pod(key_.words[0]).pod(key_.words[1]);
    r.pod(settings_.relaxedMuscleModulus).pod(static_cast<int>(settings_.releaseAcross)).pod(static_cast<int>(settings_.releaseRingHalves));
    releasedKey_ = r.key();
  }
  if (cache && released)
    if (std::optional<ModalBasis> hit = cache->load(releasedKey_); hit && fitsSkin(*hit)) {
      hit->fromCache = true;
      hit->solveSeconds = 0.0;
      basis_ = std::make_shared<const ModalBasis>(std::move(*hit));
      fromCache_ = true;
      heldReader_ = cache->reader();
      setMuscleStrengths();
      makeContactPenalty();
      return;
    }
  if (cache)
    if (std::optional<ModalBasis> hit = cache->load(key_); hit && fitsSkin(*hit)) {
      hit->fromCache = true;
      hit->solveSeconds = 0.0;
      heldBasis_ = std::make_shared<const ModalBasis>(std::move(*hit));
      fromCache_ = true;
    }
  if (!heldBasis_) {
    heldBasis_ = std::make_shared<const ModalBasis>(buildHeldBasis());
    if (cache && heldBasis_->modeCount() > 0) cache->store(key_, *heldBasis_);
  }
  releaseRelaxedMuscles();
  if (cache && released && basis_->modeCount() > 0) cache->store(releasedKey_, *basis_);
}

bool AnatomicalSkin::fitsSkin(const ModalBasis& b) const {
  // A stored copy that does not fit this skin is a miss (the key makes that ~impossible).
  const int n = head_.mesh.vertexCount();
  const Eigen::Index d = b.lambda.size();
  return b.fullVertexCount == n && b.freeCount() == n && b.Phi.rows() == 3 * n && b.Phi.cols() == d &&
         b.Psi.rows() == 3 * n && b.Psi.cols() == d && b.freeMass.size() == n && b.freeMass == mass_;
}

// The held basis from scratch, in the build sequence the key names: muscle loads, gravity x, y, z,
// the extra release columns, the release columns along another shape than the muscle's, diagonalise; then per build-time drag its x, y, z and diagonalise.
ModalBasis AnatomicalSkin::buildHeldBasis() const {
  Stopwatch clock;
  builder_ = std::make_unique<RitzBasisBuilder>(Khat_, mass_, head_.mesh.V, head_.mesh.F, ritz_);
  std::vector<MatX3> loads = couplingLoads_;
  for (int a = 0; a < 3; ++a) loads.push_back(gravityPattern(a));  // gravity along x, y, z: M·ê_a
  // The extra release columns' responses, so that the release stays exact in the basis (Woodbury).
  for (int j = 0; j < extraReleaseColumns_; ++j)
    loads.push_back(rows3(VecX(releaseColumns_.col(releaseColumns_.cols() - extraReleaseColumns_ + j))));
  // A muscle released along another shape than its own (a lip's ring: CoupledMuscle::releaseShape)
  // has a first release column its load does not span: its response too.
  for (size_t m = 0; m < muscles_.size(); ++m)
    if (muscles_[m].releaseShape.rows() > 0 && releaseColumns_.cols() > 0)
      loads.push_back(rows3(VecX(releaseColumns_.col(static_cast<Eigen::Index>(m)))));
  // The contact's normal loads (after everything else, so a head without contact builds as before).
  loads.insert(loads.end(), contactLoads_.begin(), contactLoads_.end());
  loads.insert(loads.end(), modiolusLoads_.begin(), modiolusLoads_.end());  // the held band ends' reactions
  builder_->addLoads(loads);
  builder_->diagonalize();
  for (const Drag& d : drags_) {
    builder_->addLoads({dragPattern(d.vertices, 0), dragPattern(d.vertices, 1), dragPattern(d.vertices, 2)});
    builder_->diagonalize();
  }
  ModalBasis b = builder_->basis();
  b.solveSeconds = clock.seconds();
  return b;
}

void AnatomicalSkin::ensureHeldBasis() const {
  if (heldBasis_) return;
  if (heldReader_)
    if (std::optional<ModalBasis> b = heldReader_(key_); b && fitsSkin(*b)) {
      b->fromCache = true;
      b->solveSeconds = 0.0;
      heldBasis_ = std::make_shared<const ModalBasis>(std::move(*b));
      return;
    }
  heldBasis_ = std::make_shared<const ModalBasis>(buildHeldBasis());
}

// F_m, from the basis the skin is stepped in (so a cached basis gives the same bits): c_mᵀK⁻¹c_m =
// Σ (Φᵀc_m)²/λ exactly, K⁻¹c_m lying in the basis. SkinFollows: α_m = s_m/c_mᵀK⁻¹c_m (the skin tied
// to the muscle moves c_mᵀu/s_m = 1 at a_m = 1); MuscleShortens: α_m = 1/(1 + γ_m c_mᵀK⁻¹c_m) (the
// muscle's coordinate q_m = 1), 1 when muscles are held.
void AnatomicalSkin::setMuscleStrengths() {
  muscleLoads_ = couplingLoads_;
  strength_ = VecX::Ones(static_cast<Eigen::Index>(muscles_.size()));
  const ModalBasis& B = *basis_;
  const bool released = releaseColumns_.cols() > 0;
  if (B.modeCount() == 0 || muscles_.empty() || (!released && settings_.strength == StrengthRule::MuscleShortens)) return;
  const MatX P = (couplingColumns_.transpose() * B.Phi).transpose();  // d × M
  for (size_t m = 0; m < muscles_.size(); ++m) {
    const auto mi = static_cast<Eigen::Index>(m);
    const double cKc = (P.col(mi).array().square() / B.lambda.array()).sum();
    if (!(cKc > 0)) continue;
    if (modiolusFirst_[m] >= 0) {  // a hoop band held at the modioli
      setHeldBandLoad(m, P.col(mi));
      continue;
    }
    const double alpha = settings_.strength == StrengthRule::SkinFollows ? shapeEnergy_(mi) / cKc
                                                                         : 1.0 / (1.0 + release_(mi) * cKc);
    muscleLoads_[m] = alpha * couplingLoads_[m];
    strength_(mi) = alpha;
  }
}

// The modioli's reaction patterns (docs/muscles.md, "The band's ends are held at the modioli"):
// for each hoop ring, the skin within kModiolusRadius of each of its two anchors (the modioli, on
// the skin), weighted (1 − (d/R)²)² and normalised to 1, along x, y and z: a pattern's dot product
// with a displacement is the patch's weighted mean motion along that axis.
void AnatomicalSkin::buildModiolusPatterns() {
  constexpr double kModiolusRadius = 0.06;  // face-frame units (≈ 5 mm on ICT): the modiolus, ≈ 1 cm across
  const MatX3& V = head_.mesh.V;
  const int n = head_.mesh.vertexCount();
  const double R = kModiolusRadius * head_.frame().scale;
  modiolusFirst_.assign(muscles_.size(), -1);
  for (size_t m = 0; m < muscles_.size(); ++m) {
    const Muscle& mu = muscles_[m].muscle;
    if (!mu.def.isRing() || !mu.def.ring.hoop) continue;
    modiolusFirst_[m] = static_cast<int>(modiolusLoads_.size());
    for (const Vec3& end : mu.hoopEnds) {
      VecX w = VecX::Zero(n);
      for (int i = 0; i < n; ++i) {
        const double s = (Vec3(V.row(i)) - end).norm() / R;
        if (s < 1.0) w(i) = (1.0 - s * s) * (1.0 - s * s);
      }
      if (!(w.sum() > 0.0))
        throw InputError("muscle '" + mu.def.name + "': no skin lies within " + std::to_string(R) +
                         " cm of its band's end (the modiolus) on this head");
      w /= w.sum();
      for (int a = 0; a < 3; ++a) {
        MatX3 g = MatX3::Zero(n, 3);
        g.col(a) = w;
        modiolusLoads_.push_back(std::move(g));
      }
    }
  }
}

// A hoop band's load with its ends held at the modioli: ℓ = c_m − G r, G the muscle's six modiolus
// patterns, r = (GᵀK⁻¹G)⁻¹GᵀK⁻¹c_m the reaction the modioli give (the muscles that meet there hold
// them), so that each patch's mean motion Gᵀu is zero; K⁻¹ of every pattern lies in the basis
// (Woodbury), so this is exact there. The strength rule is kept on ℓ: α = s_m / c_mᵀK⁻¹ℓ (the skin
// tied to the band follows it by σ), or 1/(1 + γ_m c_mᵀK⁻¹ℓ).
void AnatomicalSkin::setHeldBandLoad(size_t m, const VecX& Pc) {
  const ModalBasis& B = *basis_;
  const auto mi = static_cast<Eigen::Index>(m);
  const int n = head_.mesh.vertexCount();
  MatX G(3 * n, 6);
  for (int j = 0; j < 6; ++j) G.col(j) = flat(modiolusLoads_[static_cast<size_t>(modiolusFirst_[m] + j)]);
  const MatX PG = B.Phi.transpose() * G;  // d × 6
  const VecX inv = B.lambda.cwiseInverse();
  const MatX GKG = PG.transpose() * inv.asDiagonal() * PG;
  const VecX r = GKG.ldlt().solve(PG.transpose() * inv.asDiagonal() * Pc);
  const VecX Pl = Pc - PG * r;
  const double cKl = (Pc.array() * Pl.array() * inv.array()).sum();
  if (!(cKl > 0)) throw NumericalError("muscle '" + muscles_[m].muscle.def.name + "': held at the modioli, its band moves nothing");
  const double alpha = settings_.strength == StrengthRule::SkinFollows ? shapeEnergy_(mi) / cKl
                                                                       : 1.0 / (1.0 + release_(mi) * cKl);
  VecX load = flat(couplingLoads_[m]) - G * r;
  muscleLoads_[m] = alpha * rows3(load);
  strength_(mi) = alpha;
}

MatX3 AnatomicalSkin::gravityPattern(int axis) const {
  MatX3 g = MatX3::Zero(head_.mesh.vertexCount(), 3);
  g.col(axis) = mass_;
  return g;
}

// The skin's load patterns as one sparse 3n × (M + 3 + 3·drags) matrix (a muscle's pull and a drag
// touch few vertices): each muscle's coupling pull c_m (its load at strength 1), M·ê_x, M·ê_y, M·ê_z,
// each drag's ê_x, ê_y, ê_z spread over its vertices.
SparseMat AnatomicalSkin::loadPatternColumns() const {
  const int n = head_.mesh.vertexCount();
  const Eigen::Index M = couplingColumns_.cols();
  std::vector<Triplet> trip;
  for (Eigen::Index m = 0; m < M; ++m)
    for (SparseMat::InnerIterator it(couplingColumns_, m); it; ++it) trip.emplace_back(it.row(), static_cast<int>(m), it.value());
  for (int i = 0; i < n; ++i)
    for (int a = 0; a < 3; ++a) trip.emplace_back(3 * i + a, static_cast<int>(M) + a, mass_(i));
  for (size_t k = 0; k < drags_.size(); ++k) {
    const auto& vs = drags_[k].vertices;
    for (int v : vs)
      for (int a = 0; a < 3; ++a)
        trip.emplace_back(3 * v + a, static_cast<int>(M + 3 + 3 * static_cast<Eigen::Index>(k)) + a,
                          1.0 / static_cast<double>(vs.size()));
  }
  SparseMat S(3 * n, M + 3 + 3 * static_cast<Eigen::Index>(drags_.size()));
  S.setFromTriplets(trip.begin(), trip.end());
  return S;
}

SparseMat AnatomicalSkin::cutBackPatternColumns() const {
  SparseMat S = loadPatternColumns();
  if (contactLoads_.empty() && modiolusLoads_.empty()) return S;
  std::vector<MatX3> extra = contactLoads_;
  extra.insert(extra.end(), modiolusLoads_.begin(), modiolusLoads_.end());
  std::vector<Triplet> trip;
  for (Eigen::Index c = 0; c < S.outerSize(); ++c)
    for (SparseMat::InnerIterator it(S, c); it; ++it) trip.emplace_back(it.row(), it.col(), it.value());
  const Eigen::Index first = S.cols();
  for (size_t k = 0; k < extra.size(); ++k) {
    const MatX3& f = extra[k];
    for (Eigen::Index i = 0; i < f.rows(); ++i)
      for (int a = 0; a < 3; ++a)
        if (f(i, a) != 0.0) trip.emplace_back(static_cast<int>(3 * i + a), static_cast<int>(first + static_cast<Eigen::Index>(k)), f(i, a));
  }
  SparseMat out(S.rows(), first + static_cast<Eigen::Index>(extra.size()));
  out.setFromTriplets(trip.begin(), trip.end());
  return out;
}

void AnatomicalSkin::makeContactPenalty() {
  penalty_.reset();
  if (!settings_.contact || !placement_->hasContact() || basis_->modeCount() == 0) return;
  penalty_ = std::make_shared<const ContactPenalty>(*placement_, head_.mesh.V, mass_, *basis_, settings_.contactStiffness);
}

MatX AnatomicalSkin::modalLoadPatterns(const ModalBasis& basis) const {
  MatX P = (loadPatternColumns().transpose() * basis.Phi).transpose();
  for (Eigen::Index m = 0; m < strength_.size(); ++m) P.col(m) *= strength_(m);  // F_m = α_m c_m
  for (size_t m = 0; m < modiolusFirst_.size(); ++m)  // a held band: F_m = α_m (c_m − G r)
    if (modiolusFirst_[m] >= 0) P.col(static_cast<Eigen::Index>(m)) = basis.Phi.transpose() * flat(muscleLoads_[m]);
  return P;
}

MatX3 AnatomicalSkin::dragPattern(const std::vector<int>& vertices, int axis) const {
  MatX3 f = MatX3::Zero(head_.mesh.vertexCount(), 3);
  for (int v : vertices) f(v, axis) = 1.0 / static_cast<double>(vertices.size());
  return f;
}

std::vector<int> AnatomicalSkin::dragVertices(int vertex, double radius) const {
  const MatX3& V = head_.mesh.V;
  const int n = head_.mesh.vertexCount();
  if (vertex < 0 || vertex >= n)
    throw InputError("drag: vertex " + std::to_string(vertex) + " is outside [0, " + std::to_string(n) + ")");
  std::vector<int> out;
  for (int v = 0; v < n; ++v)
    if ((V.row(v) - V.row(vertex)).norm() <= radius) out.push_back(v);
  return out;
}

std::vector<std::string> AnatomicalSkin::muscleNames() const {
  std::vector<std::string> names;
  for (const CoupledMuscle& m : muscles_) names.push_back(m.muscle.def.name);
  return names;
}

int AnatomicalSkin::muscleIndex(const std::string& name) const {
  for (size_t m = 0; m < muscles_.size(); ++m)
    if (muscles_[m].muscle.def.name == name) return static_cast<int>(m);
  throw InputError("anatomical model: unknown muscle '" + name + "'");
}

int AnatomicalSkin::addDrag(int vertex, double radius, double* seconds) {
  Stopwatch clock;
  Drag d{dragVertices(vertex, radius)};
  RitzBasisBuilder& b = builder();
  b.addLoads({dragPattern(d.vertices, 0), dragPattern(d.vertices, 1), dragPattern(d.vertices, 2)});
  b.diagonalize();
  heldBasis_ = std::make_shared<const ModalBasis>(b.basis());
  releaseSolve_.reset();  // made from the held basis, which just grew
  drags_.push_back(std::move(d));  // before the release: its cut-back basis keeps the drag's responses
  releaseRelaxedMuscles();
  if (seconds) *seconds = clock.seconds();
  return static_cast<int>(drags_.size()) - 1;
}

void AnatomicalSkin::validateLoads(const SkinLoads& loads) const {
  if (loads.activations.size() != static_cast<Eigen::Index>(muscles_.size()))
    throw InputError("anatomical model: " + std::to_string(loads.activations.size()) + " activations for " +
                     std::to_string(muscles_.size()) + " muscles");
  for (size_t m = 0; m < muscles_.size(); ++m) {
    const double a = loads.activations(static_cast<Eigen::Index>(m));
    if (!(a >= 0.0 && a <= 1.0))
      throw InputError("muscle '" + muscles_[m].muscle.def.name + "': activation " + std::to_string(a) +
                       " is outside [0, 1] (model: anatomical; relaxing (a < 0) is model: thesis only)");
  }
  if (loads.drags.size() > drags_.size()) throw InputError("anatomical model: more drag forces than drags");
}

MatX3 AnatomicalSkin::worldLoad(const SkinLoads& loads) const {
  validateLoads(loads);
  const int n = head_.mesh.vertexCount();
  MatX3 f = MatX3::Zero(n, 3);
  for (size_t m = 0; m < muscles_.size(); ++m) {
    const double a = loads.activations(static_cast<Eigen::Index>(m));
    if (a != 0.0) f += a * muscleLoads_[m];
  }
  const Vec3 dg = loads.gravity - gRest_;
  if (dg.squaredNorm() > 0)
    for (int i = 0; i < n; ++i) f.row(i) += mass_(i) * dg.transpose();
  for (size_t k = 0; k < loads.drags.size(); ++k) {
    const auto& vs = drags_[k].vertices;
    for (int v : vs) f.row(v) += loads.drags[k].transpose() / static_cast<double>(vs.size());
  }
  return f;
}

MatX3 AnatomicalSkin::linearFullResponse(const SkinLoads& loads) const { return linearFullResponse(worldLoad(loads)); }

MatX3 AnatomicalSkin::linearFullResponse(const MatX3& load) const {
  RitzBasisBuilder& b = builder();
  const MatX3 y = b.staticResponse(load);
  const Eigen::Index R = releaseColumns_.cols();
  if (R == 0) return y;
  const int n = head_.mesh.vertexCount();
  {  // made once, under the lock: a const skin is shared across threads (filled, it is only read)
    std::lock_guard<std::mutex> lock(builderMutex_);
    if (heldCouplingResponses_.empty())
      for (Eigen::Index j = 0; j < R; ++j) heldCouplingResponses_.push_back(b.staticResponse(rows3(VecX(releaseColumns_.col(j)))));
  }
  // Woodbury: K⁻¹F = y + K̂⁻¹C (Ρ⁻¹ − CᵀK̂⁻¹C)⁻¹ Cᵀy, written with S = Ρ^½ as
  // y + K̂⁻¹C S (I − S CᵀK̂⁻¹C S)⁻¹ S Cᵀy so that a column with ρ = 0 (a muscle without springs
  // lets go of nothing) drops out instead of making Ρ⁻¹ infinite.
  MatX KhC(3 * n, R);
  for (Eigen::Index j = 0; j < R; ++j) KhC.col(j) = flat(heldCouplingResponses_[static_cast<size_t>(j)]);
  const VecX S = releaseRho_.cwiseSqrt();
  MatX D = -(S.asDiagonal() * (releaseColumns_.transpose() * KhC) * S.asDiagonal());
  D.diagonal().array() += 1.0;
  const VecX SCy = S.cwiseProduct(releaseColumns_.transpose() * flat(y));
  const VecX z = S.cwiseProduct(VecX(D.ldlt().solve(SCy)));
  MatX3 out = y;
  flat(out) += KhC * z;
  return out;
}

SparseMat AnatomicalSkin::releaseStiffness() const {
  const Eigen::Index n3 = Khat_.rows();
  if (releaseColumns_.cols() == 0) return SparseMat(n3, n3);
  const SparseMat weighted = releaseColumns_ * releaseRho_.asDiagonal();
  return SparseMat(weighted * releaseColumns_.transpose());
}

SettledSkin AnatomicalSkin::settle(const SkinLoads& loads, bool warped) const {
  const ModalBasis& B = *basis_;
  const int n = B.fullVertexCount;
  const Eigen::Index d = B.modeCount();
  MatX3 F = worldLoad(loads);
  VecX c = VecX::Zero(d);
  if (settings_.gravityReading == GravityReading::RotatedPrestress) {
    // (a): the world force holds M g(t); the rest pre-stress −Φᵀ M g_rest is a constant modal term.
    MatX3 gr(n, 3);
    for (int i = 0; i < n; ++i) gr.row(i) = mass_(i) * gRest_.transpose();
    F += gr;
    c = -(B.Phi.transpose() * flat(gr));
  }
  SettledSkin out;
  VecX f0 = B.Phi.transpose() * flat(F) + c;
  if (loads.modalForce.size() != 0) {
    MYO_CHECK(loads.modalForce.size() == d, "settle: a modal force of " << loads.modalForce.size() << " for " << d << " modes");
    f0 += loads.modalForce;
  }
  out.q = (f0.array() / B.lambda.array()).matrix();
  double scale = std::max(f0.norm(), 1e-300);
  // The contact penalty (contact_penalty.h): E_c(q) joins the reduced energy; with nothing touching
  // at the linear solution it adds nothing and the result is the linear one bit for bit.
  const ContactPenalty* pen = loads.contact ? penalty_.get() : nullptr;
  if (pen && !loads.jaw.isZero()) validateJawPose(loads.jaw);
  LidPose lids = placement_->lidPose(loads.activations);
  lids.gaze = loads.gaze;
  std::optional<ContactPenalty::Workspace> ws;
  if (pen) {
    ws.emplace(pen->workspace());
    VecX fc = VecX::Zero(d);
    if (pen->evaluate(out.q, loads.jaw, lids, *ws, &fc) == 0.0 && !warped) pen = nullptr;  // nothing touches
    else scale = std::max(scale, fc.norm());
  }
  if (pen && !warped) {
    // Newton (Gauss–Newton for the penalty) on Π(q) = ½ qᵀΛq − f0ᵀq + E_c(q), with a backtracking
    // line search on Π: the active set settles in a few iterations (d unknowns).
    auto energy = [&](const VecX& q, VecX* g, MatX* H) {
      VecX fc;
      if (g) fc = VecX::Zero(d);
      const double E = pen->evaluate(q, loads.jaw, lids, *ws, g ? &fc : nullptr, H);
      if (g) *g = (B.lambda.array() * q.array()).matrix() - f0 - fc;
      if (H) H->diagonal() += B.lambda;
      return 0.5 * q.dot(B.lambda.cwiseProduct(q)) - f0.dot(q) + E;
    };
    // The merit is the residual's norm, not Π (the force is −∇E, also with a lid closing since it
    // follows the turn's chain, but the residual is what `converged` asks of).
    VecX g, gt;
    MatX H = MatX::Zero(d, d);
    energy(out.q, &g, &H);
    // Where the Gauss–Newton direction gives no decrease (a lid closing on skin the contact pushes:
    // the constraints' curvature Gauss–Newton drops matters), the residual's Jacobian by central
    // differences, d residuals more, whose Newton direction −J⁻¹g always descends on ‖g‖.
    auto differencedJacobian = [&](const VecX& q) {
      MatX J(d, d);
      VecX gp, gm;
      const double h = 1e-6 * std::max(q.cwiseAbs().maxCoeff(), 1e-6);
      for (Eigen::Index j = 0; j < d; ++j) {
        VecX qp = q, qm = q;
        qp(j) += h;
        qm(j) -= h;
        energy(qp, &gp, nullptr);
        energy(qm, &gm, nullptr);
        J.col(j) = (gp - gm) / (2.0 * h);
      }
      return J;
    };
    auto lineSearch = [&](const VecX& step, VecX& qt) {
      double alpha = 1.0;
      for (int ls = 0; ls < 30; ++ls, alpha *= 0.5) {
        qt = out.q + alpha * step;
        energy(qt, &gt, nullptr);
        if (gt.norm() < (1.0 - 1e-4 * alpha) * g.norm()) return true;
      }
      return false;
    };
    for (int it = 0; it < 50 && g.norm() > 1e-10 * scale; ++it) {
      VecX qt = out.q;
      bool decreased = lineSearch(H.ldlt().solve(-g), qt);
      if (!decreased) decreased = lineSearch(differencedJacobian(out.q).partialPivLu().solve(-g), qt);
      if (!decreased) break;  // no decrease left at round-off
      out.q = qt;
      H.setZero();
      energy(out.q, &g, &H);
      out.contactIterations = it + 1;
    }
    out.residual = g.norm() / scale;
    out.converged = out.residual <= 1e-6;
  }
  if (warped) {
    auto residual = [&](const VecX& q, MatX* J) {
      VecX r = (B.lambda.array() * q.array()).matrix() - c;
      if (J) *J = B.lambda.asDiagonal();
      if (pen) {  // the penalty on the linear displacement Φq of the candidates
        VecX fc = VecX::Zero(d);
        pen->evaluate(q, loads.jaw, lids, *ws, &fc, J);
        r -= fc;
      }
      for (int i = 0; i < n; ++i) {
        const Vec3 Fi = F.row(i);
        if (Fi.squaredNorm() == 0.0) continue;
        const auto Phi_i = B.Phi.middleRows(3 * i, 3);
        const auto Psi_i = B.Psi.middleRows(3 * i, 3);
        const Vec3 w = Psi_i * q;
        const Mat3 R = rotationFromVector(w);
        r.noalias() -= Phi_i.transpose() * (R.transpose() * Fi);
        if (J) J->noalias() -= Phi_i.transpose() * ((R.transpose() * skew(Fi) * warpMatrix(w)) * Psi_i);
      }
      return r;
    };
    MatX J;
    VecX r = residual(out.q, &J);
    for (int it = 0; it < 50 && r.norm() > 1e-12 * scale; ++it) {
      const VecX step = J.partialPivLu().solve(-r);
      double alpha = 1.0;
      VecX qt, rt;
      for (int ls = 0; ls < 30; ++ls, alpha *= 0.5) {
        qt = out.q + alpha * step;
        rt = residual(qt, nullptr);
        if (rt.norm() < (1.0 - 1e-4 * alpha) * r.norm()) break;
      }
      out.q = qt;
      r = residual(out.q, &J);
      out.iterations = it + 1;
      if (pen) out.contactIterations = it + 1;
    }
    out.residual = r.norm() / scale;
    out.converged = out.residual <= 1e-8;
    out.u = warpedDisplacement(B, out.q);
  } else {
    out.u = linearDisplacement(B, out.q);
  }
  if (pen) pen->evaluate(out.q, loads.jaw, lids, *ws, nullptr, nullptr, &out.contactDepth);
  return out;
}
}  // namespace myo
