// The guarantees of the fast immersed interface method that now hold in both dimensions
// (electric/interface_guarantees.h, InterfaceSolverOptions; issue #43 item 1): the inner-ratio
// cap, the cubic/quadratic fit agreement, the point-scale oscillation of [phi_n], the thin-part
// check and the warm-start refresh. Each guarantee refuses a case it must refuse, by the option's
// name, and accepts resolved cases of the solvers' own tests (which all run with every check on);
// typed over the dimension: the curve solver in 2D, the surface solver in 3D.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <type_traits>
#include <vector>

#include "ehd_capsule/electric/fast_iim_solver.h"
#include "ehd_capsule/electric/fast_iim_solver_3d.h"
#include "ehd_capsule/geometry/initial_shapes.h"
#include "ehd_capsule/geometry/triangle_mesh.h"
#include "support/dimensions.h"
#include "support/interface_case.h"

namespace ehd {
namespace {

// One solve in dimension D: what the guarantees measured, or the refusal.
struct Outcome {
  bool refused = false;
  std::string what;
  double fit_disagreement = 0, oscillation = 0;
  int poisson_solves = 0;
};

template <typename Solver, typename Interface, typename Problem>
Outcome SolveWith(Solver& solver, const Interface& interface, const Problem& problem,
                  std::vector<double>& g) {
  std::vector<double> phi;
  Outcome out;
  try {
    solver.Solve(interface, problem, g, phi);
  } catch (const SolverError& e) {
    out.refused = true;
    out.what = e.what();
    return out;
  }
  out.fit_disagreement = solver.fit_disagreement();
  if constexpr (std::is_same_v<Solver, FastIimSolver>) {
    out.oscillation = solver.marker_oscillation();
  } else {
    out.oscillation = solver.point_oscillation();
  }
  out.poisson_solves = solver.poisson_solves();
  return out;
}

template <int D>
struct Iim;

template <>
struct Iim<2> {
  using Options = FastIimOptions;
  // A resolved case and an unresolved one of the shared examples (test/support/interface_case.h).
  static Outcome Solve(const std::string& name, int n, double sigma_minus, double sigma_plus,
                       const Options& options = Options()) {
    const test::InterfaceCase c(name, n, sigma_minus, sigma_plus);
    FastIimSolver solver(c.grid, PoissonBoundaries{}, options);
    std::vector<double> g;
    return SolveWith(solver, c.curve, c.problem, g);
  }
  // The biconcave shape with a centre thinner than h (c0 = 0.05, radius 0.45: about 0.55 h thick
  // on N = 32), the grid-scale curvature resolved.
  static Outcome SolveThinBiconcave(const BiconcaveParameters& shape) {
    const InterfaceExample e = MakeInterfaceExample("biconcave", 1.0, 10.0);
    const test::InterfaceCase c(e, 32, BiconcaveMarkers(120, shape));
    FastIimSolver solver(c.grid, PoissonBoundaries{});
    std::vector<double> g;
    return SolveWith(solver, c.curve, c.problem, g);
  }
  // Cold solve, then a warm one from its answer, with warm_start_refresh = refresh.
  static Outcome WarmSolve(int refresh) {
    const test::InterfaceCase c("ellipse", 48, 1.0, 10.0);
    Options options;
    options.warm_start_refresh = refresh;
    FastIimSolver solver(c.grid, PoissonBoundaries{}, options);
    std::vector<double> g;
    SolveWith(solver, c.curve, c.problem, g);
    return SolveWith(solver, c.curve, c.problem, g);
  }
  // The case each check must refuse: the potential near the five-petal star on N = 20 (troughs
  // of grid-scale curvature radius ~1 h) varies on the grid scale; at 1000:1 on N = 24 [phi_n]
  // spikes at a trough (test FastIimSolver.UnresolvedTipIsRefusedNotSolvedWrong).
  static Outcome UnresolvedPotential() { return Solve("star", 20, 1.0, 1.0); }
  static Outcome UnresolvedTip() { return Solve("star", 24, 1000.0, 1.0); }
  static constexpr const char* kResolved[2] = {"ellipse", "star"};
  static constexpr int kResolvedN = 40;
};

template <>
struct Iim<3> {
  using Options = FastIim3DOptions;
  static Outcome Solve(const std::string& name, int n, double sigma_minus, double sigma_plus,
                       const Options& options = Options()) {
    const test::InterfaceCase3D c(name, n, sigma_minus, sigma_plus);
    FastIimSolver3D solver(c.grid, c.example.boundaries, options);
    std::vector<double> g;
    return SolveWith(solver, c.mesh, c.problem, g);
  }
  // The cell with c0 = 0.05, radius 0.45: a dimple 0.03 thick on h = 0.0625 (N = 32).
  static Outcome SolveThinBiconcave(const BiconcaveParameters& shape) {
    const InterfaceExample3D e = MakeInterfaceExample3D("biconcave", 1.0, 10.0);
    const test::InterfaceCase3D c(e, 32, BiconcaveMesh(4, shape));
    FastIimSolver3D solver(c.grid, e.boundaries);
    std::vector<double> g;
    return SolveWith(solver, c.mesh, c.problem, g);
  }
  static Outcome WarmSolve(int refresh) {
    const test::InterfaceCase3D c("ellipsoid", 24, 1.0, 10.0);
    Options options;
    options.warm_start_refresh = refresh;
    FastIimSolver3D solver(c.grid, c.example.boundaries, options);
    std::vector<double> g;
    SolveWith(solver, c.mesh, c.problem, g);
    return SolveWith(solver, c.mesh, c.problem, g);
  }
  // The shipped red cell on N = 16: the potential near the dimple is not resolved (test
  // FastIimSolver3D.RefusesADimpleThinnerThanTheGrid). No 3D case with a vertex-scale spike of
  // [phi_n] that passes the other checks is known (the vertex values at 1000:1 on a mesh finer
  // than the grid stall GMRES first), so the oscillation check is shown on its threshold only.
  static Outcome UnresolvedPotential() { return Solve("biconcave", 16, 1.0, 10.0); }
  static constexpr const char* kResolved[2] = {"sphere", "biconcave"};
  static constexpr int kResolvedN = 24;
};

bool Names(const Outcome& o, const std::string& text) {
  return o.what.find(text) != std::string::npos;
}

template <typename Dim>
class InterfaceGuarantees : public ::testing::Test {};
TYPED_TEST_SUITE(InterfaceGuarantees, test::BothDimensions, test::DimensionName);

TYPED_TEST(InterfaceGuarantees, InnerRatioAboveTheCapIsRefused) {
  constexpr int D = TypeParam::value;
  const std::string shape = D == 2 ? "ellipse" : "sphere";
  const int n = D == 2 ? 80 : 24;
  const Outcome at_cap = Iim<D>::Solve(shape, n, 1000.0, 1.0);
  EXPECT_FALSE(at_cap.refused) << at_cap.what;
  const Outcome above = Iim<D>::Solve(shape, n, 2000.0, 1.0);
  EXPECT_TRUE(above.refused);
  EXPECT_TRUE(Names(above, "max_inner_ratio")) << above.what;
  EXPECT_TRUE(Names(above, "sigma^-/sigma^+ = 2000")) << above.what;
  // The option is honoured (not a constant).
  typename Iim<D>::Options low;
  low.max_inner_ratio = 5.0;
  EXPECT_TRUE(Names(Iim<D>::Solve(shape, n, 10.0, 1.0, low), "max_inner_ratio = 5"));
}

TYPED_TEST(InterfaceGuarantees, FitDisagreementRefusesAnUnresolvedPotential) {
  constexpr int D = TypeParam::value;
  const Outcome bad = Iim<D>::UnresolvedPotential();
  EXPECT_TRUE(bad.refused);
  EXPECT_TRUE(Names(bad, "max_fit_disagreement")) << bad.what;
  EXPECT_TRUE(Names(bad, "refine the grid")) << bad.what;
  // Resolved cases are accepted with the disagreement measured (0.01-0.07 on these; the most
  // measured on a resolved case: 0.07, the 2D star on N = 40 at 1:10, the 3D cell on N = 24).
  for (const char* name : Iim<D>::kResolved) {
    const Outcome ok = Iim<D>::Solve(name, Iim<D>::kResolvedN, 1.0, 2.0);
    EXPECT_FALSE(ok.refused) << name << ": " << ok.what;
    EXPECT_GT(ok.fit_disagreement, 0.0) << name;
    EXPECT_LT(ok.fit_disagreement, 0.08) << name;
  }
}

TYPED_TEST(InterfaceGuarantees, PointScaleOscillationIsRefused) {
  constexpr int D = TypeParam::value;
  if constexpr (D == 2) {
    const Outcome tip = Iim<2>::UnresolvedTip();
    EXPECT_TRUE(tip.refused);
    EXPECT_TRUE(Names(tip, "max_marker_oscillation")) << tip.what;
    EXPECT_TRUE(Names(tip, "oscillates at the marker scale")) << tip.what;
  }
  // Resolved cases stay far below the threshold (2D <= 0.08 at N = 40, 3D <= 0.03 on the
  // sphere, ellipsoid and cell from N = 24 at 1:10 to 1000:1), and the threshold is honoured.
  const std::string shape = Iim<D>::kResolved[0];
  const Outcome ok = Iim<D>::Solve(shape, Iim<D>::kResolvedN, 1.0, 2.0);
  EXPECT_FALSE(ok.refused) << ok.what;
  EXPECT_GT(ok.oscillation, 0.0);
  EXPECT_LT(ok.oscillation, 0.03);
  typename Iim<D>::Options strict;
  strict.max_marker_oscillation = 0.5 * ok.oscillation;
  const Outcome refused = Iim<D>::Solve(shape, Iim<D>::kResolvedN, 1.0, 2.0, strict);
  EXPECT_TRUE(Names(refused, "max_marker_oscillation")) << refused.what;
  EXPECT_TRUE(Names(refused, D == 2 ? "marker scale" : "vertex scale")) << refused.what;
  // Equal conductivities: G = v / sigma is data, not checked.
  EXPECT_EQ(Iim<D>::Solve(shape, Iim<D>::kResolvedN, 1.0, 1.0, strict).oscillation, 0.0);
}

TYPED_TEST(InterfaceGuarantees, APartThinnerThanTheGridIsRefused) {
  constexpr int D = TypeParam::value;
  BiconcaveParameters thin;
  thin.radius = 0.45;
  thin.c0 = 0.05;
  const Outcome bad = Iim<D>::SolveThinBiconcave(thin);
  EXPECT_TRUE(bad.refused);
  EXPECT_TRUE(Names(bad, "thinner than the grid spacing")) << bad.what;
  EXPECT_TRUE(Names(bad, "twice")) << bad.what;
  // The same size with the shipped shape's dimple (c0 = 0.207) is solved.
  BiconcaveParameters shipped;
  shipped.radius = 0.45;
  const Outcome ok = Iim<D>::SolveThinBiconcave(shipped);
  EXPECT_FALSE(ok.refused) << ok.what;
}

TYPED_TEST(InterfaceGuarantees, WarmStartRefreshSavesTheReferenceSolve) {
  constexpr int D = TypeParam::value;
  // A warm solve from the answer: with refresh = 0 it still solves R(0) for |b|; with refresh
  // > 0 it reuses |b| of the cold solve before it (one potential solve fewer).
  const Outcome plain = Iim<D>::WarmSolve(0);
  const Outcome refreshed = Iim<D>::WarmSolve(4);
  ASSERT_FALSE(plain.refused) << plain.what;
  ASSERT_FALSE(refreshed.refused) << refreshed.what;
  EXPECT_LT(refreshed.poisson_solves, plain.poisson_solves);
}

}  // namespace
}  // namespace ehd
