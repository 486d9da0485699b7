// The immersed boundary's effective radius (docs/validation_3d.md, "The immersed boundary's
// effective radius" and "The retracted immersed boundary"; issue #42), measured on a nearly rigid
// capsule in shear against exact Stokes results:
//   - its stresslet (SimulationState::stresslet_xy) against a rigid body's in unbounded simple
//     shear (Batchelor 1970): S_xy = (10 pi / 3) mu k a^3 for a sphere, 2 pi mu k a^2 per unit
//     depth for a circular cylinder. A spherical capsule at small Ca tank-treads as a rigid
//     sphere rotates, so its stresslet is the rigid one. The force is smeared over the kernel's
//     support, so the fluid sees a larger body: S = S_exact (a_eff / a)^D;
//   - its small-deformation D = (25/12) Ca (Barthes-Biesel & Rallison 1981, the scenes' G_s
//     convention) and its tank-treading rate k / 2 (a rigid sphere's rotation), the exact
//     problems numerics.ib_retraction is calibrated on.
// Default run: one coarse grid each (seconds). Full* (scripts/test --full): two or three grids,
// the observed orders and the targets at a = 8.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "ehd_capsule/coupling/simulation.h"
#include "ehd_capsule/scene/scene.h"

namespace ehd {
namespace {

struct StiffCapsule {
  double radius_excess = 0;  // a_eff / a - 1 from the stresslet
  double d_ratio = 0;        // D / ((25/12) Ca) (3D)
  double tank_treading = 0;  // d(phase)/dt over t in [0.25, 0.5], units of k
};

// At t = 0.5 (steady after ~0.1: the viscous and the elastic times are 0.1 and 0.002 units of
// 1/k), one thread.
StiffCapsule Measure(const std::string& scene, std::vector<std::string> overrides) {
  overrides.push_back("numerics.threads=1");
  Simulation sim(LoadScene(scene, overrides));
  while (sim.state().time < 0.25) sim.Step();
  const double t0 = sim.state().time, phase0 = sim.state().tt_phase;
  double phase = phase0, previous = phase0;
  while (sim.state().time < 0.5) {
    sim.Step();
    double step = sim.state().tt_phase - previous;  // unwrap
    step -= 2.0 * M_PI * std::round(step / (2.0 * M_PI));
    phase += step;
    previous = sim.state().tt_phase;
  }
  const SimulationState& s = sim.state();
  const int d = s.dimension;
  const double exact = d == 3 ? 10.0 * M_PI / 3.0 : 2.0 * M_PI;
  EXPECT_GT(s.stresslet_xy, 0.0) << scene;
  StiffCapsule out;
  out.radius_excess = std::pow(s.stresslet_xy / exact, 1.0 / d) - 1.0;
  out.d_ratio = s.dxy / (25.0 / 12.0 * s.ca);
  out.tank_treading = std::abs(phase - phase0) / (s.time - t0);
  return out;
}

// The immersed boundary of song2019 (the cosine kernel at the points) or the roma3 kernel
// retracted 0.37 h (issue #42).
enum class Boundary { kAtThePoints, kDefault };

StiffCapsule Sphere(int a, int level, Boundary boundary) {
  std::vector<std::string> o = {"Ca=0.002",
                                "E_b=0",
                                "N=" + std::to_string(8 * a),
                                "geometry.half_width=4",
                                "mesh_subdivisions=" + std::to_string(level),
                                "numerics.membrane_substeps=4"};
  if (boundary == Boundary::kAtThePoints) {
    o.push_back("numerics.ib_kernel=cosine");
    o.push_back("numerics.ib_retraction=0");
  } else {
    o.push_back("numerics.ib_kernel=roma3");  // its retraction's default, 0.37 h
  }
  return Measure("sphere_shear", o);
}

StiffCapsule Cylinder(int a, double retraction) {
  // Walls at +-4a; E_b keeps the 2D Hookean ring round (without bending it takes the elliptic
  // mode freely, D ~ Ca^(1/3)).
  const std::string n = std::to_string(8 * a);
  return Measure("capsule_shear",
                 {"Ca=0.002", "E_b=0.05", "N=" + n, "M=" + n, "numerics.membrane_substeps=4",
                  "numerics.ib_retraction=" + std::to_string(retraction)});
}

// The force is spread over the kernel's half-support 2 h on each side of the points: the body
// the fluid sees lies between the marker surface and that, 0 < a_eff - a < 2 h.
void ExpectWithinTheKernel(double excess, int a) {
  EXPECT_GT(excess, 0.0) << "a = " << a;
  EXPECT_LT(excess, 2.0 / a) << "a = " << a;
}

TEST(Stresslet, StiffCylinderSeesABodyWithinTheKernel) {
  // Measured 0.120 at a = 8 (0.069 at a = 16, 0.048 at a = 32).
  ExpectWithinTheKernel(Cylinder(8, 0.0).radius_excess, 8);
}

TEST(Stresslet, StiffSphereSeesABodyWithinTheKernel) {
  // Measured 0.229 at a = 4 (0.139, 0.094, 0.058 at a = 6, 8, 12): a + 0.92 ... 0.69 h.
  ExpectWithinTheKernel(Sphere(4, 3, Boundary::kAtThePoints).radius_excess, 4);
}

TEST(Stresslet, FullStiffCylinderApproachesTheRigidValueAtFirstOrder) {
  std::vector<double> excess;
  for (const int a : {8, 16}) {
    excess.push_back(Cylinder(a, 0.0).radius_excess);
    ExpectWithinTheKernel(excess.back(), a);
  }
  const double order = std::log2(excess[0] / excess[1]);
  EXPECT_GT(order, 0.6) << excess[0] << " " << excess[1];
}

TEST(Stresslet, FullStiffSphereApproachesTheRigidValueAtFirstOrder) {
  std::vector<double> excess;
  for (const auto& [a, level] : {std::pair<int, int>{4, 3}, {6, 4}}) {
    excess.push_back(Sphere(a, level, Boundary::kAtThePoints).radius_excess);
    ExpectWithinTheKernel(excess.back(), a);
  }
  const double order = std::log(excess[0] / excess[1]) / std::log(1.5);
  EXPECT_GT(order, 0.8) << excess[0] << " " << excess[1];
}

// The retracted immersed boundary with the roma3 kernel (retracted 0.37 h,
// docs/validation_3d.md "The kernel"): at a = 4 the small-Ca D is within 3 % of (25/12) Ca
// (measured -0.3 %; song2019's boundary: +25 %; the cosine kernel retracted 0.5 h, the remedy
// before: -4.9 %) and the tank-treading rate within 1.5 % of k / 2 (measured 0.4976). A
// retraction 0.13 h off moves D by 6.5 %, and 0.5 h in place of 0.37 h gives -6.7 %: the test
// fails if the calibration is lost.
TEST(RetractedBoundary, SmallCaSphereDeformsAsTheExactTheoryAtA4) {
  const StiffCapsule at_points = Sphere(4, 3, Boundary::kAtThePoints);
  const StiffCapsule retracted = Sphere(4, 3, Boundary::kDefault);
  EXPECT_GT(at_points.d_ratio - 1.0, 0.15);
  EXPECT_LT(std::abs(retracted.d_ratio - 1.0), 0.03);
  EXPECT_LT(std::abs(retracted.tank_treading / 0.5 - 1.0), 0.015);
}

// At a = 8 (the benchmark's resolution): D within 2 % of (25/12) Ca (measured -1.3 %; at the
// points +12 %) and the rotation within 1 % of k / 2 (measured 0.4985).
TEST(RetractedBoundary, FullSmallCaSphereDeformsAsTheExactTheoryAtA8) {
  const StiffCapsule retracted = Sphere(8, 4, Boundary::kDefault);
  EXPECT_LT(std::abs(retracted.d_ratio - 1.0), 0.02);
  EXPECT_LT(std::abs(retracted.tank_treading / 0.5 - 1.0), 0.01);
}

}  // namespace
}  // namespace ehd
