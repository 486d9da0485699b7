// Timing of the immersed-boundary and membrane kernels per call, for M = 64 ... 512 markers on a
// 256 x 256 lattice-unit grid (circle of marker spacing ~0.7 h, slightly deformed):
//   Interpolate (eq. 104), Spread (eq. 106), ClosedCurve::Update (spline fit),
//   MarkerArcElements, MembraneModel::ComputeForce (Hookean + bending; all four terms),
//   ViscosityIndicator::Update (band update, eqs. 117-118).
// Usage: ib_bench [--grid N] [--min-time SECONDS]
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include "ehd_capsule/geometry/initial_shapes.h"
#include "ehd_capsule/ib/immersed_boundary.h"
#include "ehd_capsule/ib/viscosity_indicator.h"
#include "ehd_capsule/membrane/membrane_model.h"

namespace {

// Mean microseconds per call of f, repeating until min_time seconds have passed.
double TimePerCall(const std::function<void()>& f, double min_time) {
  using Clock = std::chrono::steady_clock;
  f();  // warm-up
  long calls = 0;
  const auto start = Clock::now();
  double elapsed = 0.0;
  do {
    for (int r = 0; r < 10; ++r) f();
    calls += 10;
    elapsed = std::chrono::duration<double>(Clock::now() - start).count();
  } while (elapsed < min_time);
  return 1e6 * elapsed / calls;
}

}  // namespace

int main(int argc, char** argv) {
  int n = 256;
  double min_time = 0.2;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--grid" && i + 1 < argc) {
      n = std::atoi(argv[++i]);
    } else if (a == "--min-time" && i + 1 < argc) {
      min_time = std::atof(argv[++i]);
    } else {
      std::fprintf(stderr, "usage: ib_bench [--grid N] [--min-time SECONDS]\n");
      return 2;
    }
  }
  if (n < 32) {
    std::fprintf(stderr, "ib_bench: --grid must be >= 32, got %d\n", n);
    return 2;
  }
  const ehd::Grid2D grid{n, n, 1.0, -0.5 * n, -0.5 * n};
  const ehd::ImmersedBoundary ib(grid, true, false);
  std::vector<double> ux(grid.size()), uy(grid.size()), fx(grid.size(), 0.0), fy(grid.size(), 0.0);
  std::mt19937 gen(1);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (auto& v : ux) v = u(gen);
  for (auto& v : uy) v = u(gen);

  std::printf("# ib_bench: grid %d x %d (h = 1), times in microseconds per call\n", n, n);
  std::printf("%6s %8s %10s %10s %10s %10s %12s %12s %12s\n", "M", "radius", "interp", "spread",
              "spline", "arc_elem", "force_EsEB", "force_all", "visc_band");
  for (int m : {64, 128, 256, 512}) {
    const double radius = std::min(0.7 * m / (2.0 * M_PI), 0.35 * n);
    const ehd::ClosedCurve reference(ehd::CircleMarkers(m, radius));
    Eigen::Matrix2Xd x = ehd::EllipseMarkers(m, 1.1 * radius, radius / 1.1);
    ehd::ClosedCurve curve(x);
    Eigen::Matrix2Xd U, F = Eigen::Matrix2Xd::Random(2, m), force;
    std::vector<double> dl;
    ehd::MembraneModel elastic({0.0, 0.01, 0.0, 1e-3}, reference);
    ehd::MembraneModel all({1e-3, 0.01, 0.05, 1e-3}, reference);
    ehd::ViscosityIndicator visc(grid, true, false, 0.5, 0.1);
    visc.Update(curve);
    Eigen::Matrix2Xd x_moved = x;
    double shift = 0.0;

    const double t_interp = TimePerCall([&] { ib.Interpolate(ux, uy, x, U); }, min_time);
    const double t_spread = TimePerCall([&] { ib.Spread(x, F, fx, fy); }, min_time);
    const double t_spline = TimePerCall([&] { curve.Update(x); }, min_time);
    const double t_dl = TimePerCall([&] { ehd::MarkerArcElements(curve, dl); }, min_time);
    const double t_force = TimePerCall([&] { elastic.ComputeForce(curve, 1.0, force); }, min_time);
    const double t_all = TimePerCall([&] { all.ComputeForce(curve, 1.0, force); }, min_time);
    // Band update of a curve creeping by 0.01 h per call (never triggers the full refill).
    ehd::ClosedCurve moving(x_moved);
    const double t_visc = TimePerCall(
        [&] {
          shift = shift > 0.4 ? -0.4 : shift + 0.01;
          x_moved.row(0) = x.row(0).array() + shift;
          moving.Update(x_moved);
          visc.Update(moving);
        },
        min_time);
    std::printf("%6d %8.1f %10.2f %10.2f %10.2f %10.2f %12.2f %12.2f %12.2f\n", m, radius, t_interp,
                t_spread, t_spline, t_dl, t_force, t_all, t_visc);
  }
  std::printf("# visc_band includes one ClosedCurve::Update; band size ~ perimeter x 6h\n");
  return 0;
}
