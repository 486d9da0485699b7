// LeakyDielectricSolver<D> in both dimensions (typed tests over D, test/support/dimensions.h):
// the contracts of electric/leaky_dielectric_solver.h that hold for a curve and for a surface
// alike. A circle or sphere of radius 0.3 in the box [-1, 1]^D (sigma^-/sigma^+ = 1.75,
// eps^-/eps^+ = 3.5, song2019's case A):
//   - non-positive sigma or eps is refused;
//   - the traction is quadratic in E (G is linear in E, the Maxwell stress quadratic in the
//     field), and a new field strength rescales the warm start, so the re-solve starts at the
//     answer (at most 1 GMRES iteration, fewer than the cold solve);
//   - the force is the traction times the marker's or vertex's share (2D: per unit length, the
//     traction itself; 3D: per vertex, the traction times the vertex area);
//   - the potential is linear in E.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "ehd_capsule/electric/leaky_dielectric_solver.h"
#include "ehd_capsule/geometry/initial_shapes.h"
#include "support/dimensions.h"

namespace ehd {
namespace {

// The grid on [-1, 1]^D and the shape of radius 0.3 about the origin, resolved as the coupled
// step resolves its bodies (markers about 1 h apart; mesh edges below 1.5 h).
template <int D>
struct Drop;

template <>
struct Drop<2> {
  static constexpr int kN = 48;
  static Grid<2> MakeGrid() { return Grid<2>{kN, kN, 2.0 / kN, -1, -1}; }
  static ClosedCurve MakeShape() {
    return ClosedCurve(CircleMarkers(48, 0.3, Eigen::Vector2d::Zero()));
  }
  static int size(const ClosedCurve& c) { return c.size(); }
  static std::vector<double> Share(const ClosedCurve& c) {  // force per unit length
    return std::vector<double>(c.size(), 1.0);
  }
};

template <>
struct Drop<3> {
  static constexpr int kN = 24;
  static Grid<3> MakeGrid() { return Grid<3>{kN, kN, kN, 2.0 / kN, -1, -1, -1}; }
  static TriangleMesh MakeShape() { return IcosphereMesh(3, 0.3); }
  static int size(const TriangleMesh& m) { return m.vertex_count(); }
  static std::vector<double> Share(const TriangleMesh& m) {  // force per vertex
    return MeasureSurface(m).vertex_area;
  }
};

template <typename Dim>
class LeakyDielectricContract : public ::testing::Test {};
TYPED_TEST_SUITE(LeakyDielectricContract, test::BothDimensions, test::DimensionName);

TYPED_TEST(LeakyDielectricContract, RejectsNonPositiveProperties) {
  constexpr int D = TypeParam::value;
  const Grid<D> grid = Drop<D>::MakeGrid();
  EXPECT_THROW(LeakyDielectricSolver<D>(grid, 0.0, 1, 1, 1), std::invalid_argument);
  EXPECT_THROW(LeakyDielectricSolver<D>(grid, 1, -1, 1, 1), std::invalid_argument);
  EXPECT_THROW(LeakyDielectricSolver<D>(grid, 1, 1, 0.0, 1), std::invalid_argument);
  EXPECT_THROW(LeakyDielectricSolver<D>(grid, 1, 1, 1, -2), std::invalid_argument);
}

TYPED_TEST(LeakyDielectricContract, TractionIsQuadraticInTheFieldAndTheWarmStartRescales) {
  constexpr int D = TypeParam::value;
  const Grid<D> grid = Drop<D>::MakeGrid();
  const auto shape = Drop<D>::MakeShape();
  const int n = Drop<D>::size(shape);
  LeakyDielectricSolver<D> solver(grid, 1.75, 1.0, 3.5, 1.0);
  const double e = 0.5;
  solver.SetAppliedField(e);
  EXPECT_EQ(solver.applied_field(), e);
  const InterfaceSolveReport cold = solver.Solve(shape, 0.0);
  ASSERT_TRUE(cold.converged);
  ASSERT_EQ(solver.traction().cols(), n);
  ASSERT_EQ(solver.force().cols(), n);
  const auto before = solver.traction();
  EXPECT_GT(before.norm(), 0.0);
  // Force = traction times the point's share.
  const std::vector<double> share = Drop<D>::Share(shape);
  for (int k = 0; k < n; ++k) {
    EXPECT_NEAR((solver.force().col(k) - solver.traction().col(k) * share[k]).norm(), 0.0,
                1e-14 * (1 + before.col(k).norm()))
        << k;
  }
  const std::vector<double> phi = solver.potential();  // a copy: the next solve replaces it
  ASSERT_EQ(phi.size(), grid.size());
  // Doubling E: four times the traction; the rescaled G starts GMRES at the answer.
  solver.SetAppliedField(2 * e);
  const InterfaceSolveReport doubled = solver.Solve(shape, 1.0);
  EXPECT_TRUE(doubled.converged);
  EXPECT_LT((solver.traction() - 4 * before).norm(), 1e-6 * before.norm());
  EXPECT_LE(doubled.iterations, 1);
  EXPECT_GT(cold.iterations, doubled.iterations);
  // The potential is linear in E.
  double worst = 0, scale = 0;
  for (std::size_t c = 0; c < phi.size(); ++c) {
    worst = std::max(worst, std::abs(solver.potential()[c] - 2 * phi[c]));
    scale = std::max(scale, std::abs(phi[c]));
  }
  EXPECT_GT(scale, 0.0);
  EXPECT_LT(worst, 1e-6 * scale);
}

}  // namespace
}  // namespace ehd
