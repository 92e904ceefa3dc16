#include "myoshell/mesh/closest_point.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace myo {

Vec3 closestPointBarycentric(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  // Voronoi regions of the triangle's vertices, edges and face, in that order.
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return {1, 0, 0};
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return {0, 1, 0};
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    const double v = d1 / (d1 - d3);
    return {1 - v, v, 0};
  }
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return {0, 0, 1};
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    const double w = d2 / (d2 - d6);
    return {1 - w, 0, w};
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return {0, 1 - w, w};
  }
  const double denom = 1.0 / (va + vb + vc);
  const double v = vb * denom, w = vc * denom;
  return {1 - v - w, v, w};
}

namespace {

// Triangle t's closest point q to p and its squared distance: the one evaluation both the brute
// force and the locator make, so that they agree bit for bit.
struct Candidate {
  Vec3 bary, q;
  double sq;
};

inline Candidate candidate(const MatX3& V, const MatX3i& F, Eigen::Index t, const Vec3& p) {
  const Vec3 a = V.row(F(t, 0)), b = V.row(F(t, 1)), c = V.row(F(t, 2));
  Candidate k;
  k.bary = closestPointBarycentric(p, a, b, c);
  k.q = k.bary(0) * a + k.bary(1) * b + k.bary(2) * c;
  k.sq = (k.q - p).squaredNorm();
  return k;
}

void finish(const MatX3i& F, const MatX3& vertexNormals, double bestSq, SurfacePoint& best) {
  if (best.triangle < 0) return;
  Vec3 n = Vec3::Zero();
  for (int k = 0; k < 3; ++k) n += best.barycentric(k) * vertexNormals.row(F(best.triangle, k)).transpose();
  if (n.norm() > 0) best.normal = n.normalized();
  best.distance = std::sqrt(bestSq);
}

}  // namespace

SurfacePoint closestSurfacePoint(const MatX3& V, const MatX3i& F, const MatX3& vertexNormals, const Vec3& p) {
  SurfacePoint best;
  double bestSq = std::numeric_limits<double>::infinity();
  for (Eigen::Index t = 0; t < F.rows(); ++t) {
    const Candidate k = candidate(V, F, t, p);
    if (k.sq < bestSq) {
      bestSq = k.sq;
      best.point = k.q;
      best.triangle = static_cast<int>(t);
      best.barycentric = k.bary;
    }
  }
  finish(F, vertexNormals, bestSq, best);
  return best;
}

SurfaceLocator::SurfaceLocator(MatX3 V, MatX3i F, MatX3 vertexNormals)
    : V_(std::move(V)), F_(std::move(F)), N_(std::move(vertexNormals)) {
  const int m = static_cast<int>(F_.rows());
  order_.resize(static_cast<size_t>(m));
  for (int t = 0; t < m; ++t) order_[static_cast<size_t>(t)] = t;
  slack_ = 1e-9 * (1.0 + (V_.size() ? V_.cwiseAbs().maxCoeff() : 0.0));
  nodes_.reserve(static_cast<size_t>(2 * (m / 4 + 1)));
  if (m > 0) build(0, m);
}

int SurfaceLocator::build(int first, int count) {
  const int id = static_cast<int>(nodes_.size());
  nodes_.emplace_back();
  Eigen::AlignedBox3d box, centres;
  for (int k = first; k < first + count; ++k) {
    const int t = order_[static_cast<size_t>(k)];
    Vec3 c = Vec3::Zero();
    for (int j = 0; j < 3; ++j) {
      const Vec3 v = V_.row(F_(t, j));
      box.extend(v);
      c += v;
    }
    centres.extend(c / 3.0);
  }
  nodes_[static_cast<size_t>(id)].box = box;
  constexpr int kLeaf = 8;
  if (count <= kLeaf) {
    nodes_[static_cast<size_t>(id)].first = first;
    nodes_[static_cast<size_t>(id)].count = count;
    return id;
  }
  int axis = 0;
  centres.sizes().maxCoeff(&axis);
  const auto centre = [&](int t) {
    return V_(F_(t, 0), axis) + V_(F_(t, 1), axis) + V_(F_(t, 2), axis);
  };
  const int half = count / 2;
  std::nth_element(order_.begin() + first, order_.begin() + first + half, order_.begin() + first + count,
                   [&](int a, int b) { return centre(a) < centre(b) || (centre(a) == centre(b) && a < b); });
  const int left = build(first, half);
  const int right = build(first + half, count - half);
  nodes_[static_cast<size_t>(id)].left = left;
  nodes_[static_cast<size_t>(id)].right = right;
  return id;
}

SurfacePoint SurfaceLocator::closest(const Vec3& p) const {
  SurfacePoint best;
  double bestSq = std::numeric_limits<double>::infinity();
  if (nodes_.empty()) return best;
  // Depth first, the nearer child first; a box is skipped only when its distance exceeds the best
  // distance by more than the slack, so every triangle that could tie or win is evaluated, and
  // ties go to the lowest index as in the brute force.
  const auto boxDistance = [&](const Node& n) { return std::sqrt(n.box.squaredExteriorDistance(p)); };
  const auto farther = [&](double boxDist) { return boxDist > std::sqrt(bestSq) + slack_; };
  int stack[128];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& n = nodes_[static_cast<size_t>(stack[--top])];
    if (farther(boxDistance(n))) continue;
    if (n.left < 0) {
      for (int k = n.first; k < n.first + n.count; ++k) {
        const int t = order_[static_cast<size_t>(k)];
        const Candidate c = candidate(V_, F_, t, p);
        if (c.sq < bestSq || (c.sq == bestSq && t < best.triangle)) {
          bestSq = c.sq;
          best.point = c.q;
          best.triangle = t;
          best.barycentric = c.bary;
        }
      }
      continue;
    }
    const Node& l = nodes_[static_cast<size_t>(n.left)];
    const Node& r = nodes_[static_cast<size_t>(n.right)];
    const bool leftFirst = l.box.squaredExteriorDistance(p) <= r.box.squaredExteriorDistance(p);
    stack[top++] = leftFirst ? n.right : n.left;  // popped last
    stack[top++] = leftFirst ? n.left : n.right;
  }
  finish(F_, N_, bestSq, best);
  return best;
}

int nearestVertex(const MatX3& V, const Vec3& p) {
  Eigen::Index best = 0;
  (V.rowwise() - p.transpose()).rowwise().squaredNorm().minCoeff(&best);
  return static_cast<int>(best);
}

}  // namespace myo
