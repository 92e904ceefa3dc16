// Fitting activations to a shape: bounded least squares on the settled columns, alternated with an
// alignment of the target, then Gauss–Newton on the warped solve (docs/fitting.md).
#include "myoshell/fit/activation_fit.h"

#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>

#include "myoshell/anatomy/skin_placement.h"
#include "myoshell/core/errors.h"
#include "myoshell/core/timer.h"
#include "myoshell/muscles/muscle_mirror.h"

namespace myo {

const char* toString(FitAlignment a) {
  switch (a) {
    case FitAlignment::None: return "none";
    case FitAlignment::Rigid: return "rigid";
    case FitAlignment::Similarity: return "similarity";
  }
  return "?";
}

void FitSettings::validate() const {
  if (!(lambda >= 0.0 && std::isfinite(lambda)))
    throw InputError("fit: lambda must be a finite number ≥ 0, got " + std::to_string(lambda));
  if (maxAlignmentRounds < 1) throw InputError("fit: maxAlignmentRounds must be ≥ 1");
  if (refineSteps < 0) throw InputError("fit: refineSteps must be ≥ 0");
  if (!(threshold >= 0.0 && std::isfinite(threshold))) throw InputError("fit: threshold must be ≥ 0");
}

MatX3 SimilarityTransform::apply(const MatX3& points) const {
  MatX3 out = (scale * (points * rotation.transpose())).eval();
  out.rowwise() += translation.transpose();
  return out;
}

SimilarityTransform fitSimilarity(const MatX3& from, const MatX3& to, bool withScale) {
  if (from.rows() != to.rows() || from.rows() < 3)
    throw InputError("alignment needs the same number (≥ 3) of points on both sides, got " +
                     std::to_string(from.rows()) + " and " + std::to_string(to.rows()));
  const double k = static_cast<double>(from.rows());
  const Vec3 muF = from.colwise().mean().transpose();
  const Vec3 muT = to.colwise().mean().transpose();
  const MatX3 f = from.rowwise() - muF.transpose();
  const MatX3 t = to.rowwise() - muT.transpose();
  // Umeyama (1991), eqs. 38–42: Σ = (1/k) Σ_i t_i f_iᵀ = U D Vᵀ, R = U S Vᵀ, s = tr(D S)/σ_f².
  const Mat3 sigma = (t.transpose() * f) / k;
  const Eigen::JacobiSVD<Mat3> svd(sigma, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Vec3 S = Vec3::Ones();
  if (svd.matrixU().determinant() * svd.matrixV().determinant() < 0) S(2) = -1.0;
  SimilarityTransform T;
  T.rotation = svd.matrixU() * S.asDiagonal() * svd.matrixV().transpose();
  const double varF = f.squaredNorm() / k;
  if (withScale && varF > 0) T.scale = svd.singularValues().dot(S) / varF;
  T.translation = muT - T.scale * T.rotation * muF;
  return T;
}

BoxQpResult solveBoxQp(const MatX& H, const VecX& c, const VecX& lo, const VecX& hi) {
  const Eigen::Index m = c.size();
  if (H.rows() != m || H.cols() != m || lo.size() != m || hi.size() != m)
    throw CheckError("solveBoxQp: H, c, lo, hi sizes differ");
  if ((lo.array() > hi.array()).any()) throw CheckError("solveBoxQp: lo > hi");
  BoxQpResult r;
  VecX& x = r.x;
  // Start with every variable held at its lower bound (a held variable always sits on a bound).
  x = lo;
  std::vector<bool> freeVar(static_cast<size_t>(m), false);
  // A ridge far below any meaningful curvature keeps the free block solvable when columns coincide.
  const double scale = std::max(H.diagonal().cwiseAbs().maxCoeff(), std::numeric_limits<double>::min());
  const double tol = 1e-12 * (scale * std::max(1.0, (hi - lo).cwiseAbs().maxCoeff()) + c.cwiseAbs().maxCoeff());
  const int maxIterations = 10 * static_cast<int>(m) + 50;
  for (int outer = 0; outer < maxIterations; ++outer) {
    // Multipliers of the held variables: at lo the gradient must not point inwards (g ≥ 0), at hi (g ≤ 0).
    const VecX g = H * x - c;
    Eigen::Index worst = -1;
    double worstViolation = tol;
    for (Eigen::Index i = 0; i < m; ++i) {
      if (freeVar[static_cast<size_t>(i)] || lo(i) == hi(i)) continue;
      const double v = x(i) <= lo(i) ? -g(i) : g(i);
      if (v > worstViolation) worstViolation = v, worst = i;
    }
    if (worst < 0) return r;
    freeVar[static_cast<size_t>(worst)] = true;
    ++r.iterations;
    for (int inner = 0; inner <= m; ++inner) {
      std::vector<Eigen::Index> F;
      for (Eigen::Index i = 0; i < m; ++i)
        if (freeVar[static_cast<size_t>(i)]) F.push_back(i);
      if (F.empty()) break;
      const auto nf = static_cast<Eigen::Index>(F.size());
      MatX Hff(nf, nf);
      VecX rhs(nf);
      for (Eigen::Index a = 0; a < nf; ++a) {
        rhs(a) = c(F[static_cast<size_t>(a)]);
        for (Eigen::Index j = 0; j < m; ++j)
          if (!freeVar[static_cast<size_t>(j)]) rhs(a) -= H(F[static_cast<size_t>(a)], j) * x(j);
        for (Eigen::Index b = 0; b < nf; ++b) Hff(a, b) = H(F[static_cast<size_t>(a)], F[static_cast<size_t>(b)]);
        Hff(a, a) += 1e-14 * scale;
      }
      const VecX z = Hff.ldlt().solve(rhs);
      // The step from x toward z stops at the first bound it crosses (Lawson–Hanson's interpolation);
      // the variable that stops it (and any other that lands on its bound) is held there exactly.
      double alpha = 1.0;
      Eigen::Index stopper = -1;
      for (Eigen::Index k = 0; k < nf; ++k) {
        const Eigen::Index i = F[static_cast<size_t>(k)];
        const double d = z(k) - x(i);
        double t = 1.0;
        if (z(k) < lo(i) && d < 0) t = (lo(i) - x(i)) / d;
        if (z(k) > hi(i) && d > 0) t = (hi(i) - x(i)) / d;
        if (t < alpha) alpha = std::max(t, 0.0), stopper = k;
      }
      bool held = false;
      for (Eigen::Index k = 0; k < nf; ++k) {
        const Eigen::Index i = F[static_cast<size_t>(k)];
        x(i) += alpha * (z(k) - x(i));
        const bool outside = z(k) < lo(i) || z(k) > hi(i);
        const double bound = z(k) < lo(i) ? lo(i) : hi(i);
        if (outside && (k == stopper || std::abs(x(i) - bound) <= 1e-12 * (hi(i) - lo(i) + 1.0))) {
          x(i) = bound;
          freeVar[static_cast<size_t>(i)] = false;
          held = true;
        }
      }
      if (alpha >= 1.0 || !held) break;
    }
    x = x.cwiseMax(lo).cwiseMin(hi);
  }
  r.converged = false;
  return r;
}

std::vector<MatX3> activationColumns(const AnatomicalSkin& skin, const std::vector<int>& muscles) {
  const auto m = static_cast<Eigen::Index>(skin.muscles().size());
  SkinLoads loads;
  loads.activations = VecX::Zero(m);
  loads.gravity = skin.restGravity();  // gravity off: no load relative to the rest pose
  loads.drags.assign(static_cast<size_t>(skin.dragCount()), Vec3::Zero());
  // The rest solve is subtracted so that the columns are exactly the muscles' parts of u(a).
  const MatX3 u0 = skin.settle(loads, false).u;
  std::vector<MatX3> cols;
  for (int k : muscles) {
    loads.activations.setZero();
    loads.activations(k) = 1.0;
    cols.push_back(skin.settle(loads, false).u - u0);
  }
  return cols;
}

namespace {

// The rows of a displacement at the given vertices, flattened (3k).
VecX gatherRows(const MatX3& u, const std::vector<int>& rows) {
  VecX out(3 * static_cast<Eigen::Index>(rows.size()));
  for (size_t r = 0; r < rows.size(); ++r) out.segment<3>(3 * static_cast<Eigen::Index>(r)) = u.row(rows[r]).transpose();
  return out;
}

MatX3 gatherPoints(const MatX3& p, const std::vector<int>& rows) {
  MatX3 out(static_cast<Eigen::Index>(rows.size()), 3);
  for (size_t r = 0; r < rows.size(); ++r) out.row(static_cast<Eigen::Index>(r)) = p.row(rows[r]);
  return out;
}

// The column matrix (3k×f) of the fitted columns at the rows.
MatX columnMatrix(const std::vector<MatX3>& cols, const std::vector<int>& rows) {
  MatX A(3 * static_cast<Eigen::Index>(rows.size()), static_cast<Eigen::Index>(cols.size()));
  for (size_t j = 0; j < cols.size(); ++j) A.col(static_cast<Eigen::Index>(j)) = gatherRows(cols[j], rows);
  return A;
}

double conditionNumber(const MatX& A) {
  if (A.rows() == 0 || A.cols() == 0) return std::numeric_limits<double>::infinity();
  const Eigen::JacobiSVD<MatX> svd(A);
  const VecX& s = svd.singularValues();
  const double smin = s(s.size() - 1);
  if (A.rows() < A.cols() || smin <= 0) return std::numeric_limits<double>::infinity();
  return s(0) / smin;
}

// The shape u placed as every user of the face places it (SkinPlacement::place, the jaw at rest),
// as a displacement from the rest.
MatX3 placed(const SkinPlacement& placement, const MatX3& rest, const MatX3& u, const VecX& activations) {
  MatX3 p;
  placement.place(u, JawPose{}, activations, p);
  return p - rest;
}

}  // namespace

namespace {

// One side of a fit: the target, its weighted vertices and its positions there (in the target's own
// frame), and for each fitted activation j the fitted muscle whose column it drives on this side
// (`twin[j]`, a position in the fitted list: j itself for the shape, j's mirror twin for the mirror
// image of a pair).
struct Side {
  const FitTarget* target = nullptr;
  std::vector<int> rows;
  MatX3 P, restRows;
  std::vector<Eigen::Index> twin;
  Eigen::Index offset = 0;  // this side's first row in the stacked equations
  SimilarityTransform alignment;
  Eigen::Index size() const { return 3 * static_cast<Eigen::Index>(rows.size()); }
};

// The side's weighted vertices and target positions, with the target's errors.
void readTarget(Side& s, const MatX3& rest, const FitSettings& settings) {
  const FitTarget& target = *s.target;
  const Eigen::Index n = rest.rows();
  if (target.isMarkers()) {
    if (target.markerPositions.rows() != static_cast<Eigen::Index>(target.markerVertices.size()))
      throw InputError("fit: " + std::to_string(target.markerVertices.size()) + " marker vertices but " +
                       std::to_string(target.markerPositions.rows()) + " positions");
    std::vector<bool> seen(static_cast<size_t>(n), false);
    for (int v : target.markerVertices) {
      if (v < 0 || v >= n)
        throw InputError("fit: marker vertex " + std::to_string(v) + " is not a vertex of the head (it has " +
                         std::to_string(n) + ")");
      if (seen[static_cast<size_t>(v)]) throw InputError("fit: marker vertex " + std::to_string(v) + " is given twice");
      seen[static_cast<size_t>(v)] = true;
    }
    s.rows = target.markerVertices;
    s.P = target.markerPositions;
  } else {
    if (target.displacement.rows() != n)
      throw InputError("fit: the target has " + std::to_string(target.displacement.rows()) +
                       " vertices, the head " + std::to_string(n));
    s.rows.resize(static_cast<size_t>(n));
    for (Eigen::Index i = 0; i < n; ++i) s.rows[static_cast<size_t>(i)] = static_cast<int>(i);
    s.P = rest + target.displacement;
  }
  if (!s.P.allFinite()) throw InputError("fit: the target has a coordinate that is not a finite number");
  if (settings.alignment != FitAlignment::None && s.rows.size() < 3)
    throw InputError("fit: alignment needs at least 3 markers, got " + std::to_string(s.rows.size()));
  s.restRows = gatherPoints(rest, s.rows);
}

// The fitted activations a as one side sees them, on the fitted muscles' positions: b[twin[j]] = a[j].
VecX asSeenBy(const Side& s, const VecX& a) {
  VecX b(a.size());
  for (size_t j = 0; j < s.twin.size(); ++j) b(s.twin[j]) = a(static_cast<Eigen::Index>(j));
  return b;
}

// The fit of one activation vector to every side's target at once (one side: fitActivations; two:
// a shape and its mirror image, fitMirroredActivations). `mirror` (null for one side) gives each
// muscle's twin. The figures of each side are its own.
std::vector<ActivationFit> fitSides(const AnatomicalSkin& skin, std::vector<Side>& sides, const std::vector<int>* mirror,
                                    const FitSettings& settings, const SkinPlacement* placement,
                                    const std::vector<MatX3>* everyColumn) {
  const Stopwatch clock;
  settings.validate();
  const MatX3& rest = skin.head().mesh.V;
  const Eigen::Index n = rest.rows();
  const auto mAll = static_cast<Eigen::Index>(skin.muscles().size());
  for (Side& s : sides) readTarget(s, rest, settings);

  std::vector<int> fitted;
  if (settings.muscles.empty())
    for (int k = 0; k < mAll; ++k) fitted.push_back(k);
  for (const std::string& name : settings.muscles) {
    const int k = skin.muscleIndex(name);
    if (std::find(fitted.begin(), fitted.end(), k) != fitted.end())
      throw InputError("fit: muscle '" + name + "' is listed twice");
    fitted.push_back(k);
  }
  const auto m = static_cast<Eigen::Index>(fitted.size());
  // Each side's muscle for each activation: the fitted muscle itself, or its twin on a mirror side.
  for (size_t si = 0; si < sides.size(); ++si) {
    Side& s = sides[si];
    s.twin.resize(static_cast<size_t>(m));
    for (Eigen::Index j = 0; j < m; ++j) s.twin[static_cast<size_t>(j)] = j;
    if (si == 0) continue;
    if (!mirror || mirror->size() != static_cast<size_t>(mAll))
      throw CheckError("fitMirroredActivations: the mirror names a twin for each of the " + std::to_string(mAll) + " muscles");
    const std::vector<std::string> names = skin.muscleNames();
    std::vector<bool> taken(static_cast<size_t>(m), false);
    for (Eigen::Index j = 0; j < m; ++j) {
      const int k = fitted[static_cast<size_t>(j)];
      const int t = (*mirror)[static_cast<size_t>(k)];
      const std::string& name = names[static_cast<size_t>(k)];
      if (t < 0)
        throw InputError("fit: muscle '" + name + "' has no mirror twin ('" + mirroredMuscleName(name) +
                         "' is no muscle of the library): a mirror pair is fitted with both sides' muscles");
      const auto at = std::find(fitted.begin(), fitted.end(), t);
      if (at == fitted.end())
        throw InputError("fit: muscle '" + name + "' is fitted and its mirror twin '" + names[static_cast<size_t>(t)] +
                         "' is not: a mirror pair is fitted with both sides' muscles");
      const auto tj = static_cast<Eigen::Index>(at - fitted.begin());
      if (taken[static_cast<size_t>(tj)]) throw CheckError("fitMirroredActivations: two muscles have the twin '" + names[static_cast<size_t>(t)] + "'");
      taken[static_cast<size_t>(tj)] = true;
      s.twin[static_cast<size_t>(j)] = tj;
    }
  }
  if (everyColumn && everyColumn->size() != static_cast<size_t>(mAll))
    throw CheckError("fitActivations: " + std::to_string(everyColumn->size()) + " columns for " + std::to_string(mAll) +
                     " muscles");
  std::vector<MatX3> cols;
  if (everyColumn)
    for (int k : fitted) cols.push_back((*everyColumn)[static_cast<size_t>(k)]);
  else
    cols = activationColumns(skin, fitted);
  // A lid muscle's column is its placed shape at a = 1 (its physics and the lid fully turned): a
  // secant of the lid's rotation, so the bounded least squares stays linear; the fitted shape is
  // then placed exactly (below), and the figures measure that.
  if (!placement) placement = &skin.placement();
  auto allActivations = [&](const VecX& act) {
    VecX full = VecX::Zero(mAll);
    for (Eigen::Index j = 0; j < m; ++j) full(fitted[static_cast<size_t>(j)]) = act(j);
    return full;
  };
  std::vector<MatX3> fitCols = cols;
  for (Eigen::Index j = 0; j < m; ++j)
    if (placement->turnsALid(fitted[static_cast<size_t>(j)]))
      fitCols[static_cast<size_t>(j)] = placed(*placement, rest, cols[static_cast<size_t>(j)], allActivations(VecX::Unit(m, j)));
  // The stacked equations: each side's rows, activation j driving that side's muscle twin[j].
  Eigen::Index stacked = 0;
  for (Side& s : sides) s.offset = stacked, stacked += s.size();
  MatX A(stacked, m);
  for (const Side& s : sides)
    for (Eigen::Index j = 0; j < m; ++j)
      A.block(s.offset, j, s.size(), 1) = gatherRows(fitCols[static_cast<size_t>(s.twin[static_cast<size_t>(j)])], s.rows);
  const MatX H = A.transpose() * A;
  const VecX lo = VecX::Zero(m), hi = VecX::Ones(m);

  // Alternate: align each side's target to its rest + the fitted displacement, fit the aligned targets.
  int iterations = 0, solverIterations = 0;
  VecX a = VecX::Zero(m);
  VecX eRows(stacked);
  double eNorm2 = 0;
  for (int round = 0; round < settings.maxAlignmentRounds; ++round) {
    ++iterations;
    for (Side& s : sides) {
      if (settings.alignment != FitAlignment::None) {
        MatX3 goal = s.restRows;
        flat(goal) += A.middleRows(s.offset, s.size()) * a;
        s.alignment = fitSimilarity(s.P, goal, settings.alignment == FitAlignment::Similarity);
      }
      const MatX3 aligned = s.alignment.apply(s.P) - s.restRows;
      eRows.segment(s.offset, s.size()) = flat(aligned);
    }
    // The sparsity term is scaled by the stacked target's squared norm, so λ keeps its meaning.
    eNorm2 = eRows.squaredNorm();
    // ‖Aa − e‖² + λ‖e‖²Σa = aᵀHa − 2(Aᵀe − ½λ‖e‖²1)ᵀa + const.
    const VecX c = A.transpose() * eRows - VecX::Constant(m, 0.5 * settings.lambda * eNorm2);
    const BoxQpResult qp = solveBoxQp(H, c, lo, hi);
    solverIterations += qp.iterations;
    if (!qp.converged) throw NumericalError("fit: the bounded least-squares solve did not converge");
    const double change = (qp.x - a).cwiseAbs().maxCoeff();
    a = qp.x;
    if (settings.alignment == FitAlignment::None || (round > 0 && change < 1e-10)) break;
  }

  // Each side's shape: its activations' linear shape, placed.
  std::vector<MatX3> us;
  for (const Side& s : sides) {
    const VecX b = asSeenBy(s, a);
    MatX3 u = MatX3::Zero(n, 3);
    for (Eigen::Index j = 0; j < m; ++j) u += b(j) * cols[static_cast<size_t>(j)];
    us.push_back(placed(*placement, rest, u, allActivations(b)));
  }

  // Gauss–Newton on the model's own shape, the alignment kept: r(a) = u(a)|rows − e, where u(a) is
  // nonlinear in a when warping is on (the warped static solve) or the fit turns a lid (the lid's
  // rotation, whose secant the columns above hold; exact at a = 0 and 1 only).
  bool turnsALid = false;
  for (const Side& s : sides)
    for (Eigen::Index j = 0; j < m; ++j)
      turnsALid = turnsALid || (a(j) > 0.0 && placement->turnsALid(fitted[static_cast<size_t>(s.twin[static_cast<size_t>(j)])]));
  const bool warping = skin.settings().warping;
  bool refined = false;
  if ((warping || turnsALid) && settings.refineSteps > 0) {
    refined = true;
    SkinLoads loads;
    loads.activations = VecX::Zero(mAll);
    loads.gravity = skin.restGravity();
    loads.drags.assign(static_cast<size_t>(skin.dragCount()), Vec3::Zero());
    const MatX3 u0 = warping ? skin.settle(loads, true).u : MatX3();
    // The model's shape at these activations (of the fitted muscles): the warped solve, or the placed linear shape.
    auto shapeAt = [&](const VecX& act) {
      if (!warping) {
        MatX3 linear = MatX3::Zero(n, 3);
        for (Eigen::Index j = 0; j < m; ++j)
          if (act(j) != 0.0) linear += act(j) * cols[static_cast<size_t>(j)];
        return placed(*placement, rest, linear, allActivations(act));
      }
      for (Eigen::Index j = 0; j < m; ++j) loads.activations(fitted[static_cast<size_t>(j)]) = act(j);
      const SettledSkin s = skin.settle(loads, true);
      if (!s.converged || !s.u.allFinite())
        throw NumericalError("fit: the warped static solve did not converge (residual " + std::to_string(s.residual) + ")");
      return placed(*placement, rest, MatX3(s.u - u0), allActivations(act));
    };
    // Every side's shape at the activations a, and those shapes at the stacked rows.
    auto shapesAt = [&](const VecX& act) {
      std::vector<MatX3> out;
      for (const Side& s : sides) out.push_back(shapeAt(asSeenBy(s, act)));
      return out;
    };
    auto stackedRows = [&](const std::vector<MatX3>& uu) {
      VecX out(stacked);
      for (size_t si = 0; si < sides.size(); ++si)
        out.segment(sides[si].offset, sides[si].size()) = gatherRows(uu[si], sides[si].rows);
      return out;
    };
    auto objective = [&](const std::vector<MatX3>& uu, const VecX& act) {
      return (stackedRows(uu) - eRows).squaredNorm() + settings.lambda * eNorm2 * act.sum();
    };
    us = shapesAt(a);
    double f = objective(us, a);
    // The warped solve refines every fitted muscle; the lids' turn only the muscles the linear fit
    // uses (a > 0): the others' columns are exact there, and each refined muscle costs a placement
    // per step.
    std::vector<Eigen::Index> free;
    for (Eigen::Index j = 0; j < m; ++j)
      if (warping || a(j) > 0.0) free.push_back(j);
    const auto k = static_cast<Eigen::Index>(free.size());
    for (int step = 0; step < settings.refineSteps; ++step) {
      ++iterations;
      const VecX uRows = stackedRows(us);
      const VecX r = uRows - eRows;
      MatX J(r.size(), k);
      VecX lower(k), upper(k);
      constexpr double h = 1e-3;  // forward difference, backward at the upper bound
      for (Eigen::Index q = 0; q < k; ++q) {
        const Eigen::Index j = free[static_cast<size_t>(q)];
        VecX ah = a;
        const double hj = a(j) + h <= 1.0 ? h : -h;
        ah(j) += hj;
        J.col(q) = (stackedRows(shapesAt(ah)) - uRows) / hj;
        lower(q) = -a(j), upper(q) = 1.0 - a(j);
      }
      const VecX c = -J.transpose() * r - VecX::Constant(k, 0.5 * settings.lambda * eNorm2);
      const BoxQpResult qp = solveBoxQp(J.transpose() * J, c, lower, upper);
      solverIterations += qp.iterations;
      bool improved = false;
      for (double t = 1.0; t >= 1.0 / 16; t *= 0.5) {
        VecX at = a;
        for (Eigen::Index q = 0; q < k; ++q) at(free[static_cast<size_t>(q)]) += t * qp.x(q);
        at = at.cwiseMax(0.0).cwiseMin(1.0);
        std::vector<MatX3> ut = shapesAt(at);
        const double ft = objective(ut, at);
        if (ft < f) {
          a = at, us = std::move(ut), f = ft, improved = true;
          break;
        }
      }
      if (!improved) break;
    }
  }

  // Each side's fit, its figures over its own compared vertices.
  std::vector<ActivationFit> fits;
  for (size_t si = 0; si < sides.size(); ++si) {
    const Side& s = sides[si];
    ActivationFit fit;
    fit.fitted = fitted;
    fit.activations = allActivations(asSeenBy(s, a));
    fit.displacement = std::move(us[si]);
    fit.alignment = s.alignment;
    fit.iterations = iterations;
    fit.solverIterations = solverIterations;
    fit.refined = refined;
    const MatX3& u = fit.displacement;
    fit.target = rows3(VecX(eRows.segment(s.offset, s.size())));
    std::vector<int> compared;
    if (s.target->isMarkers()) {
      const MatX3 uRows = gatherPoints(u, s.rows);
      fit.metric = compareShapes(uRows, fit.target, s.restRows, ShapeMetricSettings{settings.threshold, 20});
      for (size_t r = 0; r < s.rows.size(); ++r) compared.push_back(static_cast<int>(r));
      double sum = 0, worst = 0;
      for (Eigen::Index r = 0; r < uRows.rows(); ++r) {
        const double d = (uRows.row(r) - fit.target.row(r)).norm();
        sum += d * d, worst = std::max(worst, d);
      }
      fit.rmsMm = 10.0 * std::sqrt(sum / std::max<double>(1.0, static_cast<double>(uRows.rows())));
      fit.maxMm = 10.0 * worst;
      fit.conditionNumber = conditionNumber(columnMatrix(fitCols, s.rows));
    } else {
      fit.metric = compareShapes(u, fit.target, rest, ShapeMetricSettings{settings.threshold, 20});
      double sum = 0, worst = 0;
      for (Eigen::Index i = 0; i < n; ++i)
        if (u.row(i).norm() > settings.threshold || fit.target.row(i).norm() > settings.threshold) {
          compared.push_back(static_cast<int>(i));
          const double d = (u.row(i) - fit.target.row(i)).norm();
          sum += d * d, worst = std::max(worst, d);
        }
      fit.rmsMm = compared.empty() ? 0.0 : 10.0 * std::sqrt(sum / static_cast<double>(compared.size()));
      fit.maxMm = 10.0 * worst;
      fit.conditionNumber = conditionNumber(columnMatrix(cols, compared));
    }
    fits.push_back(std::move(fit));
  }
  for (ActivationFit& fit : fits) fit.seconds = clock.seconds();
  return fits;
}

}  // namespace

ActivationFit fitActivations(const AnatomicalSkin& skin, const FitTarget& target, const FitSettings& settings,
                             const SkinPlacement* placement, const std::vector<MatX3>* everyColumn) {
  std::vector<Side> sides(1);
  sides[0].target = &target;
  return std::move(fitSides(skin, sides, nullptr, settings, placement, everyColumn).front());
}

MirroredFit fitMirroredActivations(const AnatomicalSkin& skin, const FitTarget& shape, const FitTarget& mirrorShape,
                                   const std::vector<int>& mirror, const FitSettings& settings,
                                   const SkinPlacement* placement, const std::vector<MatX3>* everyColumn) {
  std::vector<Side> sides(2);
  sides[0].target = &shape;
  sides[1].target = &mirrorShape;
  std::vector<ActivationFit> fits = fitSides(skin, sides, &mirror, settings, placement, everyColumn);
  return {std::move(fits[0]), std::move(fits[1])};
}

std::vector<int> mirroredMuscles(const AnatomicalSkin& skin) {
  const std::vector<std::string> names = skin.muscleNames();
  std::vector<int> twin(names.size(), -1);
  for (size_t k = 0; k < names.size(); ++k) {
    const auto it = std::find(names.begin(), names.end(), mirroredMuscleName(names[k]));
    if (it != names.end()) twin[k] = static_cast<int>(it - names.begin());
  }
  return twin;
}

}  // namespace myo
