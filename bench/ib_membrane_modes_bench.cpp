// The explicit stability of a membrane mode in the immersed boundary coupling, measured with the
// project's own classes (issue #42): a flat periodic membrane of M markers along x in a doubly
// periodic nx x ny D2Q9 MRT box (LatticeBoltzmann2D, the coupling's relaxation rates and
// song2019's split-momentum forcing, or others by option), spread and interpolated by
// ImmersedBoundaryTransfer<2> with the cosine, roma3 or trapezoid3 kernel, moved by
// PointAdvector<2> with dt = 1 in the coupling's stage order (force -> spread -> LBM step ->
// interpolate -> advance, song2019 sec. 3.6).
//
// The membrane's force is the linearised Hookean chain (MembraneModel's tension law about a
// uniform state): the point force on marker c is S (d_{c+1} - 2 d_c + d_{c-1}) / dl along the
// perturbed direction, S the tension (normal displacement d = y) or the elastic modulus E_s
// (tangential d = x). One Fourier mode d_c = A cos(k X_c), k = 2 pi m / (nx h), is imposed with a
// tiny amplitude; the state (markers, populations, AB2 history) is rescaled whenever it drifts
// away, so what is measured is the dominant eigenvalue's modulus g per step of the linear system
// the mode excites (its grid aliases included). Stiffness is given as S dt / (mu h) (lattice
// units, mu = rho nu).
//
// Usage: ib_membrane_modes_bench [--kernel cosine|roma3|trapezoid3|roma3_even_odd] [--nx N] [--ny
// N] [--markers M]
//          [--tau T] [--yoffset F] [--xoffset F] [--dir normal|tangential]
//          [--integrator euler|ab2] [--steps N] [--mode m] [--stiffness S]
//          [--s_e R] [--s_eps R] [--s_q R] [--forcing split|guo] [--threshold] [--scan]
//   --mode m --stiffness S : g for that mode and stiffness;
//   --threshold            : the smallest S/mu at which mode m grows (g > 1), by bisection;
//   --scan                 : the threshold of every mode m = 1 .. M/2, and the minimum.
// Every threshold line also prints the old estimate's limit for that mode (quasi-static Stokes,
// phi_hat(k h)^2) and the new one (with the grid-Nyquist limit of a tangential mode).
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "ehd_capsule/ib/delta_kernel.h"
#include "ehd_capsule/ib/immersed_boundary.h"
#include "ehd_capsule/ib/marker_update.h"
#include "ehd_capsule/lbm/lattice_boltzmann.h"
#include "ehd_capsule/membrane/membrane_stability.h"

namespace {

constexpr double kPi = 3.141592653589793;

struct Setup {
  ehd::DeltaKernel kernel = ehd::DeltaKernel::kCosine4;
  std::string kernel_name = "cosine";
  int nx = 22, ny = 24, markers = 28;
  double tau = 1.0;
  double yoffset = 0.0, xoffset = 0.0;  // of the membrane from a node line / the first node, in h
  bool normal = false;
  bool ab2 = false;
  int steps = 3000;
  // MRT rates of the non-hydrodynamic moments (LbmParameters' 2D defaults) and the forcing.
  double s_e = 1.64, s_epsilon = 1.54, s_q = 1.9;
  ehd::ForcingScheme forcing = ehd::ForcingScheme::kSplitMomentum;
};

// g per step for mode m at stiffness S / mu = s_over_mu.
double Amplification(const Setup& s, int m, double s_over_mu, int* dominant = nullptr) {
  ehd::LbmParameters p;
  p.nx = s.nx;
  p.ny = s.ny;
  p.viscosity = (s.tau - 0.5) / 3.0;
  p.boundary = ehd::FluidBoundary::kPeriodic;
  p.threads = 1;
  p.s_e = s.s_e;
  p.s_epsilon = s.s_epsilon;
  p.s_q = s.s_q;
  p.forcing = s.forcing;
  ehd::LatticeBoltzmann2D lbm(p);
  lbm.InitializeAtRest();
  const std::vector<double> rest = lbm.populations();
  const ehd::Grid2D grid = lbm.grid();
  ehd::ImmersedBoundaryTransfer<2> ib(grid, {true, true}, s.kernel);
  ehd::PointAdvector<2> advector(s.ab2 ? ehd::MarkerIntegrator::kAdamsBashforth2
                                       : ehd::MarkerIntegrator::kForwardEuler);
  const int M = s.markers;
  const double dl = s.nx * grid.h / M;
  const double stiffness = s_over_mu * p.viscosity;  // rho = 1
  const double k = 2.0 * kPi * m / (s.nx * grid.h);
  const int axis = s.normal ? 1 : 0;
  Eigen::Matrix2Xd rest_x(2, M), X(2, M), F(2, M), U(2, M);
  for (int c = 0; c < M; ++c) {
    rest_x(0, c) = grid.x(0) + s.xoffset * grid.h + c * dl;
    rest_x(1, c) = grid.y(s.ny / 2) + s.yoffset * grid.h;
  }
  const double a0 = 1e-6;
  X = rest_x;
  // Mode m with both phases (cos and sin, so every mode its grid aliases couple to is excited);
  // m = 0: every mode, random amplitudes.
  unsigned seed = 12345u;
  auto random = [&seed]() {
    seed = seed * 1664525u + 1013904223u;
    return (seed >> 8) * (1.0 / 16777216.0) - 0.5;
  };
  for (int c = 0; c < M; ++c) {
    const double x = rest_x(0, c) - rest_x(0, 0);
    X(axis, c) += m > 0 ? a0 * (std::cos(k * x) + 0.7 * std::sin(k * x)) : a0 * random();
  }
  // RMS of the displacement along the axis, its mean (a neutral translation) removed.
  auto amplitude = [&]() {
    const Eigen::RowVectorXd d = X.row(axis) - rest_x.row(axis);
    const double mean = d.mean();
    return std::sqrt((d.array() - mean).square().mean());
  };
  double log_scale = 0.0;
  std::vector<double> log_a(s.steps + 1);
  log_a[0] = std::log(amplitude());
  for (int n = 1; n <= s.steps; ++n) {
    F.setZero();
    for (int c = 0; c < M; ++c) {
      const int l = (c + M - 1) % M, r = (c + 1) % M;
      const double d = X(axis, c) - rest_x(axis, c);
      const double dl_ = X(axis, l) - rest_x(axis, l), dr = X(axis, r) - rest_x(axis, r);
      F(axis, c) = stiffness * (dl_ - 2.0 * d + dr) / dl;
    }
    lbm.ClearForce();
    ib.Spread(X, F, {&lbm.force(0), &lbm.force(1)});
    lbm.Step();
    ib.Interpolate({&lbm.velocity(0), &lbm.velocity(1)}, X, U);
    advector.Advance(U, 1.0, X);
    const double amp = amplitude();
    if (!std::isfinite(amp)) return INFINITY;
    log_a[n] = std::log(amp) + log_scale;
    if (amp > 1e-4 || amp < 1e-9) {  // rescale the whole linear state back to a0
      const double f = a0 / amp;
      log_scale -= std::log(f);
      X = rest_x + f * (X - rest_x);
      std::vector<double> pop = lbm.populations();
      for (std::size_t i = 0; i < pop.size(); ++i) pop[i] = rest[i] + f * (pop[i] - rest[i]);
      for (int a = 0; a < 2; ++a) {
        for (double& v : lbm.force(a)) v *= f;
      }
      lbm.SetPopulations(pop);
      if (advector.has_previous_velocity()) {
        advector.SetPreviousVelocity(f * advector.previous_velocity(), true);
      }
    }
  }
  // The marker mode that dominates at the end (|DFT| of the displacement over the markers).
  if (dominant != nullptr) {
    double best = -1.0;
    for (int j = 0; j <= M / 2; ++j) {
      double re = 0.0, im = 0.0;
      for (int c = 0; c < M; ++c) {
        const double d = X(axis, c) - rest_x(axis, c);
        re += d * std::cos(2.0 * kPi * j * c / M);
        im += d * std::sin(2.0 * kPi * j * c / M);
      }
      if (re * re + im * im > best) {
        best = re * re + im * im;
        *dominant = j;
      }
    }
  }
  // Growth from the largest amplitude of the second quarter to that of the last quarter (an
  // oscillating eigenvalue pair makes the amplitude beat).
  const int q = s.steps / 4;
  const double first = *std::max_element(log_a.begin() + q, log_a.begin() + 2 * q);
  const double last = *std::max_element(log_a.begin() + 3 * q, log_a.end());
  return std::exp((last - first) / (2.0 * q));
}

// The smallest S / mu with g > 1 + 1e-5 (bisection to 0.5 %), or INFINITY beyond 1e4.
double Threshold(const Setup& s, int m, int* dominant) {
  const double unstable = 1.0 + 1e-5;
  double lo = 0.0, hi = 1.0;
  while (Amplification(s, m, hi) <= unstable) {
    lo = hi;
    hi *= 2.0;
    if (hi > 1e4) return INFINITY;
  }
  while (hi - lo > 0.005 * hi) {
    const double mid = 0.5 * (lo + hi);
    (Amplification(s, m, mid) > unstable ? hi : lo) = mid;
  }
  Amplification(s, m, hi, dominant);
  return 0.5 * (lo + hi);
}

// The limits the estimate gives for a single mode: S / mu at which dt = 1 is the forward-Euler
// (or AB2) limit, old (quasi-static Stokes 1 / (4 mu k), phi_hat(k h)^2) and new
// (ehd::LatticeModeRate).
void PrintLimits(const Setup& s, int m, double measured, int dominant) {
  const double h = 1.0, dl = s.nx * h / s.markers;
  const double k = 2.0 * kPi * m / s.nx;
  const ehd::KernelTransform phi =
      s.kernel == ehd::DeltaKernel::kRoma3 || s.kernel == ehd::DeltaKernel::kRoma3EvenOdd
          ? ehd::KernelTransform(ehd::Roma3DeltaTransform)
      : s.kernel == ehd::DeltaKernel::kTrapezoid3
          ? ehd::KernelTransform(ehd::Trapezoid3DeltaTransform)
          : ehd::KernelTransform(ehd::CosineDeltaTransform);
  const double euler = s.ab2 ? 1.0 : 2.0;
  // Old: sigma = S k phi^2 / (4 mu), the chain's k^2 taken as the continuous one.
  const double old_limit = euler * 4.0 / (k * std::pow(phi(k * h), 2));
  // New: the old one, and for a tangential mode the grid-Nyquist limit
  // (LatticeCompressionStep, AB2 convention: forward Euler twice it).
  const double mu = (s.tau - 0.5) / 3.0;
  const double nyquist = s.normal || s.kernel == ehd::DeltaKernel::kRoma3EvenOdd
                             ? INFINITY
                             : euler * ehd::LatticeCompressionStep(1.0, s.tau, h, dl, phi) / mu;
  const double new_limit = std::min(old_limit, nyquist);
  std::printf("%3d %6.3f %10.4g %10.4g %6.3f %10.4g %6.3f %4d %6.3f\n", m, k * h, measured,
              old_limit, measured / old_limit, new_limit, measured / new_limit, dominant,
              2.0 * kPi * dominant / s.nx);
}

int Usage() {
  std::fprintf(stderr,
               "usage: ib_membrane_modes_bench [--kernel cosine|roma3|trapezoid3|roma3_even_odd] "
               "[--nx N] [--ny N] "
               "[--markers M] [--tau T] [--yoffset F] [--xoffset F] [--dir normal|tangential] "
               "[--integrator euler|ab2] [--steps N] [--mode m] [--stiffness S] [--s_e R] "
               "[--s_eps R] [--s_q R] [--forcing split|guo] [--threshold] [--scan]\n");
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  Setup s;
  int mode = 1;
  double stiffness = -1.0;
  bool threshold = false, scan = false;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const bool has = i + 1 < argc;
    if (a == "--kernel" && has) {
      s.kernel_name = argv[++i];
      s.kernel = ehd::ParseDeltaKernel(s.kernel_name);
    } else if (a == "--nx" && has) {
      s.nx = std::atoi(argv[++i]);
    } else if (a == "--ny" && has) {
      s.ny = std::atoi(argv[++i]);
    } else if (a == "--markers" && has) {
      s.markers = std::atoi(argv[++i]);
    } else if (a == "--tau" && has) {
      s.tau = std::atof(argv[++i]);
    } else if (a == "--yoffset" && has) {
      s.yoffset = std::atof(argv[++i]);
    } else if (a == "--xoffset" && has) {
      s.xoffset = std::atof(argv[++i]);
    } else if (a == "--dir" && has) {
      s.normal = std::string(argv[++i]) == "normal";
    } else if (a == "--integrator" && has) {
      s.ab2 = std::string(argv[++i]) == "ab2";
    } else if (a == "--steps" && has) {
      s.steps = std::atoi(argv[++i]);
    } else if (a == "--mode" && has) {
      mode = std::atoi(argv[++i]);
    } else if (a == "--stiffness" && has) {
      stiffness = std::atof(argv[++i]);
    } else if (a == "--s_e" && has) {
      s.s_e = std::atof(argv[++i]);
    } else if (a == "--s_eps" && has) {
      s.s_epsilon = std::atof(argv[++i]);
    } else if (a == "--s_q" && has) {
      s.s_q = std::atof(argv[++i]);
    } else if (a == "--forcing" && has) {
      s.forcing = std::string(argv[++i]) == "guo" ? ehd::ForcingScheme::kGuo
                                                  : ehd::ForcingScheme::kSplitMomentum;
    } else if (a == "--threshold") {
      threshold = true;
    } else if (a == "--scan") {
      scan = true;
    } else {
      return Usage();
    }
  }
  if (s.nx < 8 || s.ny < 8 || s.markers < 4 || !(s.tau > 0.5) || s.steps < 40) return Usage();
  std::printf("# kernel %s, %d x %d, M = %d (dl = %.4f h), tau = %g, offsets y %g x %g h, %s, %s\n",
              s.kernel_name.c_str(), s.nx, s.ny, s.markers, static_cast<double>(s.nx) / s.markers,
              s.tau, s.yoffset, s.xoffset, s.normal ? "normal" : "tangential",
              s.ab2 ? "AB2" : "forward Euler");
  std::printf("# s_e = %g, s_eps = %g, s_q = %g, forcing %s\n", s.s_e, s.s_epsilon, s.s_q,
              s.forcing == ehd::ForcingScheme::kGuo ? "guo" : "split");
  if (stiffness >= 0.0) {
    int dominant = -1;
    const double g = Amplification(s, mode, stiffness, &dominant);
    std::printf("mode %d (k h = %.4f), S/mu = %g: g = %.6f per step, dominant mode %d\n", mode,
                2.0 * kPi * mode / s.nx, stiffness, g, dominant);
  }
  if (threshold || scan) {
    std::printf("#  m    k h  measured S/mu  old limit  ratio  new limit  ratio  grows (m, k h)\n");
    const int from = scan ? 1 : mode, to = scan ? s.markers / 2 : mode;  // mode 0: noise
    double worst = INFINITY;
    for (int m = from; m <= to; ++m) {
      int dominant = -1;
      const double t = Threshold(s, m, &dominant);
      worst = std::min(worst, t);
      PrintLimits(s, m, t, dominant);
    }
    if (scan) std::printf("# minimum measured threshold S/mu = %.4g\n", worst);
  }
  return 0;
}
