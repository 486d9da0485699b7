// The body and the spread stage in both dimensions (typed tests over D, test/support/
// dimensions.h), on the tiny scenes (test/support/tiny_scene.h): the body's force-source
// contract (docs/architecture.md: the sources add up in one place, in list order; a reset zeroes
// velocity and loads and measures the initial shape) and the spread stage's (the sum of the
// sources, times the arc element in 2D and per vertex in 3D, reaches the grid with its total
// unchanged: the cosine delta is a partition of unity; the grid force is cleared each step).
#include <gtest/gtest.h>

#include <cmath>

#include "ehd_capsule/coupling/body.h"
#include "ehd_capsule/coupling/stages/fluid_stage.h"
#include "ehd_capsule/coupling/stages/spread_stage.h"
#include "ehd_capsule/geometry/initial_shapes.h"
#include "ehd_capsule/scene/units.h"
#include "support/dimensions.h"
#include "support/tiny_scene.h"

namespace ehd {
namespace {

// The scene's circle (2D, its M markers) or sphere (3D, its icosphere) of radius a about the
// centre of the box, as the coupled step places it.
template <int D>
void PlaceSphere(const Scene& scene, const LatticeUnits& units, Body<D>& body) {
  if constexpr (D == 2) {
    body.initial = CircleMarkers(scene.M, units.radius, Eigen::Vector2d::Zero());
    body.shape.SetPositions(body.initial);
  } else {
    body.shape.mesh = IcosphereMesh(scene.mesh_subdivisions, units.radius);
    body.initial = body.shape.mesh.vertices();
  }
}

// pi a^2 or (4/3) pi a^3.
template <int D>
double BallMeasure(double a) {
  return D == 2 ? M_PI * a * a : 4.0 / 3.0 * M_PI * a * a * a;
}

// A smooth, not symmetric load per point: every component differs from point to point.
template <int D>
PointsOf<D> SomeLoad(const PointsOf<D>& x, double scale) {
  PointsOf<D> load(D, x.cols());
  for (int k = 0; k < x.cols(); ++k) {
    for (int a = 0; a < D; ++a) load(a, k) = scale * std::sin(0.3 * k + a) + 0.1 * (a + 1);
  }
  return load;
}

template <typename Dim>
class BodyContract : public ::testing::Test {};
TYPED_TEST_SUITE(BodyContract, test::BothDimensions, test::DimensionName);

TYPED_TEST(BodyContract, SourcesAddUpInListOrderAndResetZeroesThem) {
  constexpr int D = TypeParam::value;
  const Scene scene = test::TinyScene(D).Build();
  const LatticeUnits units = DeriveLatticeUnits(scene);
  Body<D> body;
  PlaceSphere<D>(scene, units, body);
  body.ResetTo(body.initial);
  const int n = body.size();
  EXPECT_EQ(n, D == 2 ? 32 : 642);
  // No source: no load.
  body.SumLoads();
  EXPECT_EQ(body.load.cols(), n);
  EXPECT_EQ(body.load.norm(), 0.0);
  // A new source is zero, sized to the body, found by its name.
  ForceSource<D>& membrane = body.AddForceSource("membrane");
  ForceSource<D>& electric = body.AddForceSource("electric");
  EXPECT_EQ(membrane.load.rows(), D);
  EXPECT_EQ(membrane.load.cols(), n);
  EXPECT_EQ(membrane.load.norm(), 0.0);
  EXPECT_EQ(body.FindForceSource("electric"), &electric);
  EXPECT_EQ(body.FindForceSource("bending"), nullptr);
  membrane.load = SomeLoad<D>(body.positions(), 1e-3);
  electric.load = SomeLoad<D>(body.positions(), -2e-4);
  body.SumLoads();
  EXPECT_TRUE((body.load.array() == (membrane.load + electric.load).array()).all());
  EXPECT_EQ(body.DescribeLargestLoads().find("membrane "), 0u) << body.DescribeLargestLoads();
  EXPECT_NE(body.DescribeLargestLoads().find(", electric "), std::string::npos);
  // Reset: back to the positions, no velocity, no loads; the measure of the initial shape is the
  // disc's or the ball's (the spline's or the inscribed mesh's error: < 1 %), positive (the
  // curve turns counter-clockwise, the triangles face outwards).
  body.U.setOnes(D, n);
  body.ResetTo(body.initial);
  EXPECT_EQ(body.U.norm(), 0.0);
  EXPECT_EQ(membrane.load.norm() + electric.load.norm() + body.load.norm() + body.force.norm(),
            0.0);
  EXPECT_TRUE((body.positions().array() == body.initial.array()).all());
  EXPECT_NEAR(body.initial_measure, BallMeasure<D>(units.radius),
              0.01 * BallMeasure<D>(units.radius));
}

template <typename Dim>
class SpreadStageContract : public ::testing::Test {};
TYPED_TEST_SUITE(SpreadStageContract, test::BothDimensions, test::DimensionName);

TYPED_TEST(SpreadStageContract, SpreadsTheSumOfTheSourcesWithItsTotal) {
  constexpr int D = TypeParam::value;
  const Scene scene = test::TinyScene(D).Build();
  const LatticeUnits units = DeriveLatticeUnits(scene);
  SimulationState state;
  StepData<D> data;
  data.state = &state;
  data.bodies.resize(1);
  Body<D>& body = data.bodies.front();
  PlaceSphere<D>(scene, units, body);
  body.ResetTo(body.initial);
  ForceSource<D>& a = body.AddForceSource("membrane");
  ForceSource<D>& b = body.AddForceSource("electric");
  a.load = SomeLoad<D>(body.positions(), 1e-3);
  b.load = SomeLoad<D>(body.positions(), -2e-4);

  FluidStage<D> fluid(scene, units, data);
  std::array<bool, D> periodic{};
  for (int axis = 0; axis < D; ++axis) periodic[axis] = axis != 1;  // shear: walls at y = +-L
  const ImmersedBoundaryTransfer<D> ib(fluid.lattice().grid(), periodic);
  SpreadStage<D> spread(scene, ib, data, fluid.lattice());
  EXPECT_NE(spread.Describe().find("membrane + electric"), std::string::npos) << spread.Describe();

  for (int run = 0; run < 2; ++run) {  // the second run must not add to the first one's force
    spread.Run(run + 1);
    ASSERT_TRUE((body.load.array() == (a.load + b.load).array()).all());
    if constexpr (D == 2) {
      // Force per marker = load dl; the arc elements add up to the perimeter 2 pi a.
      ASSERT_EQ(static_cast<int>(body.dl.size()), body.size());
      double perimeter = 0;
      for (int k = 0; k < body.size(); ++k) {
        EXPECT_DOUBLE_EQ(body.force(0, k), body.load(0, k) * body.dl[k]);
        EXPECT_DOUBLE_EQ(body.force(1, k), body.load(1, k) * body.dl[k]);
        perimeter += body.dl[k];
      }
      EXPECT_NEAR(perimeter, 2 * M_PI * units.radius, 1e-3 * units.radius);
    } else {
      EXPECT_TRUE((body.force.array() == body.load.array()).all());  // per vertex already
    }
    for (int axis = 0; axis < D; ++axis) {
      double on_grid = 0;
      for (double f : fluid.lattice().force(axis)) on_grid += f;
      const double on_points = body.force.row(axis).sum();
      EXPECT_NEAR(on_grid, on_points, 1e-12 * body.force.row(axis).cwiseAbs().sum())
          << "axis " << axis << ", run " << run;
    }
  }
}

}  // namespace
}  // namespace ehd
