// CurveSegments evaluates the same splines as ClosedCurve without the knot search: values,
// derivatives, segment arc lengths and marker frames must agree with ClosedCurve to rounding.
#include "ehd_capsule/geometry/curve_segments.h"

#include <gtest/gtest.h>

#include "ehd_capsule/geometry/initial_shapes.h"

namespace ehd {
namespace {

TEST(CurveSegments, AgreesWithClosedCurve) {
  for (bool reverse : {false, true}) {
    Eigen::Matrix2Xd x = BiconcaveMarkers(70, {3.0}, Eigen::Vector2d(1.0, -2.0), 0.3,
                                          MarkerSpacing::kUniformParameter);
    if (reverse) x = x.rowwise().reverse().eval();
    const ClosedCurve c(x);
    CurveSegments seg;
    seg.Update(c);
    EXPECT_EQ(seg.orientation(), c.orientation());
    for (int k = 0; k < c.size(); ++k) {
      EXPECT_NEAR(seg.SegmentArcLength(k), c.SegmentArcLength(k), 1e-13);
      const CurvePoint a = seg.AtMarker(k), b = c.AtMarker(k);
      EXPECT_NEAR((a.position - b.position).norm(), 0.0, 1e-13);
      EXPECT_NEAR((a.tangent - b.tangent).norm(), 0.0, 1e-12);
      EXPECT_NEAR((a.normal - b.normal).norm(), 0.0, 1e-12);
      EXPECT_NEAR(a.curvature, b.curvature, 1e-11);
      const double t = 0.37 * seg.segment_parameter_length(k);
      const SplineDerivatives d = seg.Evaluate(k, t);
      const double s = c.knot(k) + t;
      EXPECT_NEAR(d.x, c.x_spline().Value(s), 1e-13);
      EXPECT_NEAR(d.dy, c.y_spline().Derivative(s), 1e-12);
      EXPECT_NEAR(d.ddx, c.x_spline().SecondDerivative(s), 1e-11);
    }
  }
}

}  // namespace
}  // namespace ehd
