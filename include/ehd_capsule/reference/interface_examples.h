// Manufactured interface problems with exact solutions, shared by the fast IIM and the
// correction function method (CFM) tests and by `ehd_sim iim`.
//
// Each example gives the curve X(t), t in [0, 2 pi) (markers at t_k = 2 pi k / M, so they are
// unevenly spaced in arc length on the ellipse and the star), the exact phi^-(x, y) inside and
// phi^+(x, y) outside with gradients, and the sources f^+- = sigma^+- Laplace(phi^+-), all on the
// box [-1, 1]^2 with Dirichlet sides from the exact phi. Jumps at the markers follow from the
// exact solution: w = phi^+ - phi^-, v = sigma^+ grad phi^+ . n - sigma^- grad phi^- . n.
//
// Names (song2019 sec. 2.5 unless said otherwise):
//   "1"   circle r0 = 1/2: phi^- = 1, phi^+ = 1 + log(2r); f = 0, [phi] = 0, [phi_n] = 2
//         (also CFM example 1 of sec. 2.3.5; default sigma^- = sigma^+ = 1).
//   "2"   circle centre (1/2, 1/2), radius 1/4: phi^- = exp(-x^2-y^2), phi^+ = 0; sigma^- = 1,
//         sigma^+ = 2. The text states f^- = 8(r^2-1)e^{-r^2}, which is sigma^- Laplace(phi^-)
//         only for sigma^- = 2; here f^- = sigma^- (4r^2 - 4) e^{-r^2} from the exact solution,
//         and v from the exact solution too.
//   "3"   circle r0 = 1/2: phi^- = r^2/sigma^-, phi^+ = (r^4 - 0.1 log(2r))/sigma^+ + r0^2/sigma^-
//         - r0^4/sigma^+; the text's f = 4/sigma^-, 16 r^2/sigma^+ is Laplace(phi), not
//         div(sigma grad phi): here f^- = 4, f^+ = 16 r^2. [phi] = 0, [sigma phi_n] = -0.7.
//         Defaults sigma^- = 1, sigma^+ = 10 (Table 5; Table 6 is sigma^+ = 100).
//   "4"   circle r0 = 1/2: phi^- = e^x cos y, phi^+ = 0, f = 0; default sigma^+- = 1.
//   "cfm1" same as "1" (sec. 2.3.5 example 1).
//   "cfm2" circle r0 = 1/2: phi^- = x^2 - y^2, phi^+ = 0, f = 0 (sec. 2.3.5 example 2).
//   "ellipse" (ours) ellipse centre (0.05, -0.03), semi-axes 0.6 x 0.35 rotated by 0.3 rad;
//         phi^- = sin(2x) cos(3y) + 1, phi^+ = x y + exp((x - y)/2).
//   "star" (ours) five-petal star r = 0.5 + 0.1 sin(5 theta) about (0.02, 0.01); same phi.
//   "star_tight" (ours) the same with r = 0.5 + 0.18 sin(5 theta): troughs of curvature radius
//         0.0245, tighter than the grid for N < 82 (the solver's resolution checks).
//   "star_sharp" (ours) r = 0.5 + 0.2 sin(5 theta): petal amplitude 0.4 of the mean radius,
//         troughs of curvature radius 0.0191 (2 h at N = 209).
//   "biconcave" (ours) red-cell profile x = R cos t, y = (R/2) sin t (0.207 + 2.003 cos^2 t
//         - 1.123 cos^4 t) (Evans-Fung), R = 0.7, about (0.02, 0.01); same phi. The dimple is
//         only ~0.1 thick (2.5 h at N = 40), so fit and band reach across it.
// Any example accepts any sigma^-, sigma^+ > 0 (f and v are derived from phi for them).
#pragma once

#include <Eigen/Core>
#include <functional>
#include <string>
#include <vector>

#include "ehd_capsule/electric/interface_problem.h"
#include "ehd_capsule/geometry/closed_curve.h"
#include "ehd_capsule/geometry/grid.h"

namespace ehd {

struct InterfaceExample {
  std::string name;
  std::string description;
  double sigma_minus = 1.0;
  double sigma_plus = 1.0;
  double box_min = -1.0, box_max = 1.0;            // square domain [box_min, box_max]^2
  std::function<Eigen::Vector2d(double t)> curve;  // t in [0, 2 pi), counter-clockwise
  std::function<double(const Eigen::Vector2d&)> phi_minus, phi_plus;
  std::function<Eigen::Vector2d(const Eigen::Vector2d&)> grad_minus, grad_plus;
  // Laplace(phi^-+); f^-+ = sigma^-+ times these.
  std::function<double(const Eigen::Vector2d&)> laplace_minus, laplace_plus;
  // Markers at t_k = 2 pi k / M.
  Eigen::Matrix2Xd Markers(int count) const;
  // Default marker count for an N x N grid on the box: marker spacing about 2 h of arc length.
  int DefaultMarkers(int n) const;
  // N x N cell-centred grid covering the box.
  Grid2D MakeGrid(int n) const;
};

// Known names: "1", "2", "3", "3a" (= 3, sigma^+ = 10), "3b" (= 3, sigma^+ = 100), "4", "cfm1",
// "cfm2", "ellipse", "star", "star_tight", "star_sharp", "biconcave". Throws std::invalid_argument
// for an unknown name (listing them).
InterfaceExample MakeInterfaceExample(const std::string& name);
// Same with the given conductivities (> 0; f and v follow from the exact phi for them).
InterfaceExample MakeInterfaceExample(const std::string& name, double sigma_minus,
                                      double sigma_plus);
std::vector<std::string> InterfaceExampleNames();

// Samples the problem on the grid for the given curve (markers on the exact curve): f from the
// region of each grid point (curve.Contains), w and v at the markers from the exact solution,
// side data from the exact phi of the region there: values on Dirichlet sides (all four by
// default), outward normal derivatives on Neumann ones.
InterfaceProblem SampleInterfaceProblem(const InterfaceExample& example, const Grid2D& grid,
                                        const ClosedCurve& curve,
                                        const PoissonBoundaries& bc = PoissonBoundaries{});
// Exact phi at every grid point (region by curve.Contains).
std::vector<double> ExactSolution(const InterfaceExample& example, const Grid2D& grid,
                                  const ClosedCurve& curve);

// The error of G = [phi_n] at the markers against the example's exact jump, relative to the
// largest of |[phi_n]|, |phi_n^-|, |phi_n^+| there (the scale of FastIimOptions::verify_tolerance).
double JumpNormalDerivativeError(const InterfaceExample& example, const ClosedCurve& curve,
                                 const std::vector<double>& g);

}  // namespace ehd
