// numerics.redistribute_markers: a drop's markers re-spaced evenly when they bunch.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "ehd_capsule/coupling/simulation.h"
#include "ehd_capsule/scene/scene.h"
#include "support/tiny_scene.h"

namespace ehd {
namespace {

// Case A drop in shear and a strong field (the drop_shear_field set-up on a 48^2 grid): the
// tank-treading flow carries the drop's markers, which are not material, toward its tips.
Scene DropInShearAndField(double ratio) {
  return test::TinyScene(2)
      .Name("bunching_drop")
      .Drop()
      .With("Ca", 0.3)
      .With("Re", 0.3)
      .Field(1)
      .Grid(48)
      .With("numerics.electric_every", 100)
      .With("numerics.electric_move_tolerance", 0.02)
      .With("numerics.redistribute_markers", ratio)
      .Build();
}

double SpacingRatio(const Eigen::Matrix2Xd& x) {
  const int n = static_cast<int>(x.cols());
  double lo = 1e300, hi = 0.0;
  for (int k = 0; k < n; ++k) {
    const double l = (x.col((k + 1) % n) - x.col(k)).norm();
    lo = std::min(lo, l);
    hi = std::max(hi, l);
  }
  return hi / lo;
}

TEST(MarkerRedistribution, KeepsADropsMarkersEvenlySpacedWithoutChangingItsShape) {
  // Without redistribution the spacing ratio grows well past 2 by t = 6; with ratio 2 it is
  // re-spaced whenever it passes 2, so after every step it stays within 2 (plus the spline's
  // chord/arc difference). Re-spacing only moves markers along the curve, so D_xy, theta and the
  // enclosed area stay those of the plain run to a fraction of their changes (the field and the
  // flow are re-sampled, not altered).
  Simulation plain((DropInShearAndField(0.0)));
  Simulation even((DropInShearAndField(2.0)));
  EXPECT_NE(even.Pipeline().find("re-spaced evenly"), std::string::npos) << even.Pipeline();
  double plain_ratio = 0.0, even_ratio = 0.0;
  while (even.state().time < 6.0) {
    plain.Step();
    even.Step();
    plain_ratio = std::max(plain_ratio, SpacingRatio(plain.state().markers.topRows<2>()));
    even_ratio = std::max(even_ratio, SpacingRatio(even.state().markers.topRows<2>()));
  }
  EXPECT_GT(plain_ratio, 3.0);
  EXPECT_LT(even_ratio, 2.1);
  EXPECT_GT(even.marker_redistributions(), 0);
  EXPECT_EQ(plain.marker_redistributions(), 0);
  EXPECT_NEAR(even.state().dxy, plain.state().dxy, 0.02 * plain.state().dxy);
  EXPECT_NEAR(even.state().inclination, plain.state().inclination, 0.02);
  EXPECT_LE(std::abs(even.state().area_drift), std::abs(plain.state().area_drift) + 1e-4);
}

TEST(MarkerRedistribution, OnlyForDropsAndOnlyAsARatioAboveOne) {
  const test::TinyScene capsule =
      test::TinyScene(2).Name("c").Grid(48).With("numerics.redistribute_markers", 2);
  try {
    capsule.Build();
    FAIL() << "a capsule accepted numerics.redistribute_markers";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find(
                  "not accepted here: 2D drops only (a capsule's markers are material"),
              std::string::npos)
        << e.what();
  }
  EXPECT_THROW((DropInShearAndField(0.5)), SceneError);
}

}  // namespace
}  // namespace ehd
