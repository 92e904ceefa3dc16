// The shape metric (docs/shape_metric.md): analytic cases.
#include <gtest/gtest.h>

#include "myoshell/core/errors.h"
#include "myoshell/fit/shape_metric.h"

namespace myo {
namespace {

MatX3 restLine(int n) {
  MatX3 X(n, 3);
  for (int i = 0; i < n; ++i) X.row(i) = Vec3(i, 0.0, 0.0).transpose();
  return X;
}

TEST(ShapeMetric, IdenticalFieldsGiveOneAndOne) {
  const MatX3 X = restLine(50);
  MatX3 e = MatX3::Zero(50, 3);
  for (int i = 0; i < 50; ++i) e.row(i) = Vec3(0.01 * i, 0.02, -0.005 * i).transpose();
  const ShapeComparison c = compareShapes(e, e, X);
  EXPECT_NEAR(c.cosine, 1.0, 1e-14);
  EXPECT_NEAR(c.magnitudeRatio, 1.0, 1e-14);
  EXPECT_EQ(c.resultPeakVertex, 49);
  EXPECT_EQ(c.targetPeakVertex, 49);
  EXPECT_NEAR(c.centroidDistance, 0.0, 1e-14);
  // The 20 largest are vertices 30..49: centroid x = 39.5.
  EXPECT_NEAR(c.resultCentroid.x(), 39.5, 1e-12);
}

TEST(ShapeMetric, ScaledFieldGivesCosineOneAndTheScale) {
  const MatX3 X = restLine(40);
  MatX3 e = MatX3::Zero(40, 3);
  for (int i = 0; i < 40; ++i) e.row(i) = Vec3(0.1, 0.05 * i, 0.0).transpose();
  for (double s : {0.5, 2.0, 3.7}) {
    const ShapeComparison c = compareShapes(s * e, e, X);
    EXPECT_NEAR(c.cosine, 1.0, 1e-14) << s;
    EXPECT_NEAR(c.magnitudeRatio, s, 1e-13) << s;
  }
  const ShapeComparison neg = compareShapes(-e, e, X);
  EXPECT_NEAR(neg.cosine, -1.0, 1e-14);
}

TEST(ShapeMetric, OrthogonalFieldsGiveCosineZero) {
  const MatX3 X = restLine(30);
  MatX3 u = MatX3::Zero(30, 3), e = MatX3::Zero(30, 3);
  u.col(0).setConstant(0.3);
  e.col(1).setConstant(0.6);
  const ShapeComparison c = compareShapes(u, e, X);
  EXPECT_NEAR(c.cosine, 0.0, 1e-15);
  EXPECT_NEAR(c.magnitudeRatio, 0.5, 1e-14);
}

TEST(ShapeMetric, ComparesWhereEitherFieldMovesMoreThanHalfAMillimetre) {
  const MatX3 X = restLine(4);
  MatX3 u = MatX3::Zero(4, 3), e = MatX3::Zero(4, 3);
  e(0, 0) = 1.0;    // target only
  u(1, 1) = 1.0;    // result only
  e(2, 2) = 0.04;   // below the threshold in both: left out
  u(2, 2) = 0.04;
  const ShapeComparison c = compareShapes(u, e, X);
  EXPECT_EQ(c.comparedVertices, 2);
  EXPECT_NEAR(c.cosine, 0.0, 1e-15);
  EXPECT_NEAR(c.magnitudeRatio, 1.0, 1e-15);
}

TEST(ShapeMetric, CentroidsSeparateWhenThePeaksDo) {
  const MatX3 X = restLine(100);
  MatX3 u = MatX3::Zero(100, 3), e = MatX3::Zero(100, 3);
  for (int i = 0; i < 20; ++i) {
    u(i, 0) = 1.0;        // vertices 0..19 move: centroid x = 9.5
    e(80 + i, 0) = 1.0;   // vertices 80..99: centroid x = 89.5
  }
  const ShapeComparison c = compareShapes(u, e, X);
  EXPECT_NEAR(c.centroidDistance, 80.0, 1e-12);
  EXPECT_NEAR(c.peakDistance, 80.0, 1e-12);
}

TEST(ShapeMetric, MismatchedFieldsAreAnError) {
  try {
    compareShapes(MatX3::Zero(3, 3), MatX3::Zero(4, 3), restLine(3));
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              "shape metric: the fields have 3 and 4 rows and the rest mesh 3 (they must be equal and > 0)");
  }
}

}  // namespace
}  // namespace myo
