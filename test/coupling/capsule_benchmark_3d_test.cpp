// The 3D capsule benchmark (docs/validation_3d.md, "The kernel: roma3"; issue #42): a
// neo-Hookean spherical capsule (sphere_shear, E_b = 0, walls at +-4a) in shear against the
// boundary-integral D(t) of Ramanujan & Pozrikidis (1998) at the papers' Ca = mu k a / E_s (the
// scene's Ca / 3), read off the curves D. Huet digitized (accurate to about +-0.003; the values
// of scripts/campaigns/capsule_benchmark_3d_table.py). With the roma3 immersed boundary (the
// roma3 kernel retracted 0.37 h) the campaign measured, at t = 1 / 2 / 3 / 4:
//   a = 6, papers' Ca = 0.05: -0.6 / -2.2 / -1.8 / -0.6 %
//   a = 8: within 2.2 % for the papers' Ca = 0.025, 0.05, 0.1 and 0.2
// (the cosine kernel retracted 0.5 h: -3.2 / -5.2 % at a = 6; at the points +8 / +9 %).
// Default run: a = 6 to t = 2 (about 15 s), within 3.5 %. A membrane modulus 5 % stiffer fails it
// (measured: D(1) -3.1 %, D(2) -5.2 %), as does the cosine kernel retracted 0.5 h (-5.2 % at t =
// 2). Full* (scripts/test --full): a = 8, the four Ca to t = 4, within 2.5 %.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "ehd_capsule/coupling/simulation.h"
#include "ehd_capsule/scene/scene.h"

namespace ehd {
namespace {

struct Benchmark {
  double papers_ca;
  double d[4];  // Ramanujan & Pozrikidis (1998) D at t = 1, 2, 3, 4 (1/k); 0: off the curve
};

constexpr Benchmark kRamanujanPozrikidis[] = {
    {0.025, {0.1437, 0.0, 0.0, 0.0}},
    {0.05, {0.2299, 0.2610, 0.2638, 0.2613}},
    {0.1, {0.3055, 0.3765, 0.3857, 0.3857}},
    {0.2, {0.3613, 0.4804, 0.5063, 0.5063}},
};

// D_xy at t = 1, ..., t_end of the capsule of radius a cells (N = 8a, icosphere level `level`),
// one thread, the scene's Ca = 3 x the papers'.
std::vector<double> DeformationAtUnitTimes(const Benchmark& b, int a, int level, int t_end) {
  Simulation sim(LoadScene(
      "sphere_shear", {"Ca=" + std::to_string(3.0 * b.papers_ca), "E_b=0", "geometry.half_width=4",
                       "N=" + std::to_string(8 * a), "mesh_subdivisions=" + std::to_string(level),
                       "numerics.threads=1", "numerics.ib_kernel=roma3"}));
  std::vector<double> d;
  for (int t = 1; t <= t_end; ++t) {
    double before = sim.state().dxy, t_before = sim.state().time;
    while (sim.state().time < t) {
      before = sim.state().dxy;
      t_before = sim.state().time;
      sim.Step();
    }
    // Linear interpolation to t between the two steps around it.
    const double w = (t - t_before) / (sim.state().time - t_before);
    d.push_back(before + w * (sim.state().dxy - before));
  }
  return d;
}

void ExpectOnTheBenchmark(const Benchmark& b, int a, int level, int t_end, double tolerance) {
  const std::vector<double> d = DeformationAtUnitTimes(b, a, level, t_end);
  for (int i = 0; i < t_end; ++i) {
    if (b.d[i] == 0.0) continue;
    const double error = d[i] / b.d[i] - 1.0;
    std::printf("a = %d, papers' Ca = %g, t = %d: D = %.4f, R&P %.4f (%+.1f %%)\n", a, b.papers_ca,
                i + 1, d[i], b.d[i], 100.0 * error);
    EXPECT_LT(std::abs(error), tolerance)
        << "a = " << a << ", Ca = " << b.papers_ca << ", t = " << i + 1;
  }
}

TEST(CapsuleBenchmark3D, ModerateCaFollowsTheBoundaryIntegralCurveAtA6) {
  ExpectOnTheBenchmark(kRamanujanPozrikidis[1], 6, 4, 2, 0.035);
}

TEST(CapsuleBenchmark3D, FullEveryCaFollowsTheBoundaryIntegralCurvesAtA8) {
  for (const Benchmark& b : kRamanujanPozrikidis) ExpectOnTheBenchmark(b, 8, 4, 4, 0.025);
}

}  // namespace
}  // namespace ehd
