// One axis of the fast Poisson solvers (2D and 3D, internal to the electric library): the FFTW
// real-to-real transform pair that diagonalises the cell-centred second difference with the
// axis's two side conditions, its normalisation and its eigenvalues (table in
// fast_poisson_solver.h); and the mutex that serialises FFTW's planner.
#pragma once

#include <fftw3.h>

#include <cmath>
#include <mutex>
#include <stdexcept>
#include <string>
#include <vector>

#include "ehd_capsule/electric/fast_poisson_solver.h"

namespace ehd::poisson_detail {

// FFTW's planner is not thread-safe; serialise plan creation and destruction.
inline std::mutex& PlannerMutex() {
  static std::mutex m;
  return m;
}

// Plans are chosen by timing (FFTW_MEASURE), so two processes can pick different algorithms for
// the same transform, which round differently: runs and restarts would repeat only to rounding.
// The plans are therefore kept in a wisdom file shared by the processes of a machine: the first
// process to plan a size measures it and writes the file, later ones read the same plan. The
// file is $EHD_FFTW_WISDOM, else $XDG_CACHE_HOME/ehd_capsule/fftw_wisdom, else
// $HOME/.cache/ehd_capsule/fftw_wisdom; EHD_FFTW_WISDOM=off plans afresh in every process.
// Two processes measuring the same new size at the same moment may still differ (the later
// write wins). Call both with PlannerMutex held, around the planning.
std::string WisdomPath();  // empty: no file
void ImportWisdom();
void ExportWisdom();  // rewrites the file only when it lacks some of this process's wisdom

struct AxisTransform {
  fftw_r2r_kind forward;
  fftw_r2r_kind inverse;
  double normalisation;
  std::vector<double> eigenvalues;  // times h^2
};

inline AxisTransform MakeAxis(BoundaryKind lo, BoundaryKind hi, int n, const char* axis) {
  const bool lo_periodic = lo == BoundaryKind::kPeriodic;
  const bool hi_periodic = hi == BoundaryKind::kPeriodic;
  if (lo_periodic != hi_periodic) {
    throw std::invalid_argument(std::string("PoissonBoundaries: periodic ") + axis +
                                " sides must pair up (both min and max periodic)");
  }
  AxisTransform a;
  a.eigenvalues.resize(n);
  const double pi = M_PI;
  auto sin2 = [](double t) { return std::sin(t) * std::sin(t); };
  if (lo_periodic) {
    a.forward = FFTW_R2HC;
    a.inverse = FFTW_HC2R;
    a.normalisation = n;
    for (int k = 0; k < n; ++k) {
      const int m = (k <= n / 2) ? k : n - k;
      a.eigenvalues[k] = -4.0 * sin2(pi * m / n);
    }
    return a;
  }
  a.normalisation = 2.0 * n;
  const bool lo_d = lo == BoundaryKind::kDirichlet, hi_d = hi == BoundaryKind::kDirichlet;
  if (lo_d && hi_d) {
    a.forward = FFTW_RODFT10;
    a.inverse = FFTW_RODFT01;
    for (int k = 0; k < n; ++k) a.eigenvalues[k] = -4.0 * sin2(pi * (k + 1) / (2.0 * n));
  } else if (!lo_d && !hi_d) {
    a.forward = FFTW_REDFT10;
    a.inverse = FFTW_REDFT01;
    for (int k = 0; k < n; ++k) a.eigenvalues[k] = -4.0 * sin2(pi * k / (2.0 * n));
  } else {
    a.forward = lo_d ? FFTW_RODFT11 : FFTW_REDFT11;
    a.inverse = a.forward;
    for (int k = 0; k < n; ++k) a.eigenvalues[k] = -4.0 * sin2(pi * (k + 0.5) / (2.0 * n));
  }
  return a;
}

}  // namespace ehd::poisson_detail
