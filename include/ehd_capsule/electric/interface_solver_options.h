// The settings of the fast immersed interface method that the curve (2D, fast_iim_solver.h) and
// the surface (3D, fast_iim_solver_3d.h) solvers share (issue #43 item 1): one struct over the
// dimension, which FastIimOptions and FastIim3DOptions extend with what really differs.
//
// Every guarantee named here holds in both dimensions (interface_guarantees.h; the lists in
// docs/electric_solver.md and docs/electric_solver_3d.md): a solve that cannot be trusted throws
// a SolverError naming the point, the quantity, the option and the remedy.
#pragma once

#include "ehd_capsule/electric/gmres.h"

namespace ehd {

template <int D>
struct InterfaceSolverOptions {
  static_assert(D == 2 || D == 3, "InterfaceSolverOptions: 2 or 3 dimensions");

  GmresOptions gmres;
  // The weighted least-squares fit of phi_n^- (song2019 eq. (66)-(67)): radius alpha in h and
  // degree, 3 (cubic, default: O(h^3) derivatives) or 2 (the reference's quadratic).
  double fit_radius_h = 3.0;
  int fit_degree = 3;

  // Resolution, before solving: every interface point with |kappa| h <= max_curvature_h (the
  // largest principal curvature in 3D) and at least min_face_distance_h * h inside the box's
  // faces (measured in both dimensions: the error is that of a centred interface down to
  // 0.5-0.75 h from a face and O(1) closer; twice that limit).
  double max_curvature_h = 1.0;
  double min_face_distance_h = 1.0;

  // sigma^-/sigma^+ above which the solve is refused: the near-null mode of the Schur system
  // amplifies the discretisation error by about the ratio, and the reduced basis and deflation
  // below are measured up to 1000 only (docs/electric_solver.md sec. 3, electric_solver_3d.md).
  double max_inner_ratio = 1000.0;

  // A much more conducting inside, sigma^-/sigma^+ from basis_min_ratio (2D: at or above it; 3D:
  // above it, so 10:1 itself is solved at the vertices, as the tables were measured): G is sought
  // in a smooth basis along the interface (a Fourier series in arc length in 2D, spherical
  // harmonics in 3D) whose shortest wavelength is >= basis_wavelength_h * h. The wavelength
  // differs by dimension as measured: in 2D 4 h already lets GMRES grow with N on the five-petal
  // stars at 1000:1 (39-108 iterations) and 5 h keeps it at 15-19; in 3D the harmonic degree is
  // capped (FastIim3DOptions::max_harmonic_degree) and 4 h was measured on the sphere, the
  // ellipsoid and the red cell (docs/electric_solver_3d.md); neither was remeasured at the other
  // value.
  double basis_min_ratio = 10.0;
  double basis_wavelength_h = D == 2 ? 5.0 : 4.0;

  // After the solve, phi_n^- from the fit one degree lower (the quadratic beside the cubic) must
  // agree with the fit's to this fraction of max |phi_n^+-| at every point: where they do not,
  // the potential varies on the grid scale near the interface (a thin part, a source or field
  // on the grid scale). Resolved cases measure <= 0.075 in both dimensions (the 2D star and the
  // 3D red cell on their coarsest accepted grids; <= 0.013 on the smooth shapes), refused cases
  // 0.11-0.23 (the 2D star on N = 20-24, the 3D cell on N = 16).
  double max_fit_disagreement = 0.1;

  // After the solve, for sigma^- != sigma^+, the point-scale content of G (the fourth
  // difference along the markers / 16 in 2D, the squared graph Laplacian / 4 on the mesh in 3D,
  // the same operator on a chain) must stay below this fraction of max(|G|, |phi_n^+-|): a spike
  // at a few points is the signature of an unresolved tip. Resolved cases measure <= 0.08 in 2D
  // (the star on N = 40) and <= 0.03 in 3D (the red cell on N = 24).
  double max_marker_oscillation = 0.1;

  // 0 (default): the tolerance is always relative to |b| = |R(0)| of the current problem, and a
  // guess only shortens GMRES (a checkpoint of G restarts bit for bit). k > 0: a guess solves
  // for the correction against |b| of the last cold solve, every k-th warm solve cold again (one
  // potential solve fewer; results depend on the solve history). interface_schur_system.h.
  int warm_start_refresh = 0;
};

}  // namespace ehd
