// Fast immersed interface method in 3D (issue #13; song2019 sec. 2.4 and ch. 6): the 2D method of
// fast_iim_solver.h on a closed triangulated surface,
//
//   div(sigma grad phi) = f in Omega^- (inside) and Omega^+ (outside),
//   [phi] = w,  [sigma phi_n] = v  on the surface,   sigma^-, sigma^+ constant,
//
// with the augmented unknown G = [phi_n] at the mesh vertices. For a given G:
//   L Phi = F + C(w, G)
// L the 7-point Laplacian (FastPoissonSolver3D), F = f/sigma of each node's region, C the
// corrections of interface_jumps_3d.h at the irregular nodes (J about each node's foot point on
// the local quadratic reconstruction, geometry/local_surface_fit.h; w and G enter through their
// local quadratic fits, so J is affine in G with precomputed rows). phi_n^- at each vertex comes
// from a weighted least-squares cubic fit in the vertex's normal frame (xi, eta1, eta2) of the
// minus-side extension (phi inside, phi - J outside) at the nodes within fit_radius_h * h, with
// the weights (1 + cos(pi r / alpha)) / 2 of song2019 eq. (67) (the 2D fit of
// normal_derivative_fit.h in three variables: 20 terms; a quadratic, 10 terms, where the cubic is
// rank deficient), and phi_n^+ = phi_n^- + G. The Schur system is the scaled flux residual
//   R(G) = phi_n^- + (sigma^+/[sigma]) G - v/[sigma]   (= ([sigma phi_n] - v)/[sigma]),
// solved by restarted GMRES with the mat-vec R(G) - R(0), one Poisson solve each (the Schur
// solver shared with the 2D solver, interface_schur_system.h); for
// sigma^+ = sigma^- G = v/sigma and one solve suffices.
//
// Departures from the text and from the 2D solver: J includes the cubic term (as in 2D; the
// deferred correction of the 2D solver is not carried over), and [f/sigma], [d_xi(f/sigma)] on
// the surface are given by the caller (InterfaceProblem3D: the leaky dielectric has f = 0, so
// only manufactured tests need them).
//
// A much more conducting inside (sigma^-/sigma^+ > basis_min_ratio; not in the text).
// The map G -> phi_n^- has near-null modes there, and the Schur operator's eigenvalues on them are
// about sigma^+/[sigma] (-1/999 at 1000:1), smaller than the discretisation error of phi_n^-, so
// GMRES on the vertex values stalls and its answer would be O(1) wrong (measured: 100 % on the
// ellipsoid at 1000:1, N = 32, with a direct solve). Two families, as in 2D
// (fast_iim_solver.h): (1) the equilibrium density (the potential of G constant inside), and (2)
// vertex-scale modes of G, which the grid's corrections and fits average out. The 3D treatment:
// (2) G = sum_lm c_lm Y_lm of a parametrisation of the surface by the unit sphere: on a mesh of
// icosphere connectivity (every surface of the package) the unit-sphere position of each vertex
// in IcosphereMesh (geometry/spherical_harmonics.h); on any other triangulation the directions of
// the vertices from the centroid after the linear map that makes the volume's second moment
// isotropic (geometry/radial_parametrisation.h: the surface must be star-shaped about its
// centroid, else it is refused, naming a triangle seen edge-on or from behind). Degree L with
// shortest wavelength 2 pi R / L >= basis_wavelength_h * h, solved in the Galerkin sense (the
// residual tested against each Y_lm with the vertex areas) where the 2D solver uses control
// markers; (1) the flux balance: the surface integral of phi_n^- is that of f^-/sigma^- over the
// inside (divergence theorem), so the area mean of every solution is mu = (mean(v)/[sigma] -
// flux/area) / (sigma^+/[sigma]), known before solving, and the solver works on R(G) - (mean(G) -
// mu) = 0 (the eigenvalue moves from sigma^+/[sigma] to sigma^+/[sigma] - 1). mu divides the data's
// mean by sigma^+/[sigma], so its quadrature error is multiplied by sigma^-/sigma^+. The means use
// vertex weights Richardson-extrapolated over the icosphere's last two subdivision levels (error
// estimate from the levels below), or on another mesh with data (v or f non-zero) the radial
// parametrisation's high-order surface weights (exact on the sphere for degree <= 24; error
// estimate from 4 degrees fewer) and without data (the leaky dielectric: mu = 0 exactly) the vertex
// third areas. The flux, which needs the inside volume, is the caller's
// (InterfaceProblem3D::interior_source_integral). The estimate is reported (flux_balance_error())
// and refused above max_flux_balance_error.
//
// Guarantees (SolverError naming the vertex or the quantity and the remedy; the options and the
// dimension-free checks are shared with the 2D solver: interface_solver_options.h,
// interface_guarantees.h): sigma^-/sigma^+ <= max_inner_ratio; every vertex with
// max(|kappa1|, |kappa2|) h <= max_curvature_h and at least min_face_distance_h * h inside the
// box, every mesh edge <= max_edge_h * h (the jump data live on the vertices), no grid segment
// crossed twice by the surface (a part thinner than h), every fit with enough nodes; GMRES must
// converge; after the solve, for sigma^- != sigma^+, the vertex-scale content of G (squared graph
// Laplacian) below max_marker_oscillation of max(|G|, |phi_n^+-|), and the cubic and the
// quadratic fits of phi_n^- must agree to max_fit_disagreement of max |phi_n| at every vertex
// (where they do not, the potential varies on the grid scale near the surface and the answer
// cannot be trusted). The 2D solver's coarse-grid verification is not carried over (the flux
// balance's quadrature estimate above is the 3D check at high ratios).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <limits>
#include <memory>
#include <vector>

#include "ehd_capsule/electric/fast_poisson_solver_3d.h"
#include "ehd_capsule/electric/gmres.h"
#include "ehd_capsule/electric/interface_problem.h"
#include "ehd_capsule/electric/interface_schur_system.h"
#include "ehd_capsule/electric/interface_solver_options.h"
#include "ehd_capsule/electric/surface_classification_3d.h"
#include "ehd_capsule/geometry/local_surface_fit.h"
#include "ehd_capsule/geometry/radial_parametrisation.h"

namespace ehd {

struct InterfaceProblem3D {
  double sigma_minus = 1.0;
  double sigma_plus = 1.0;
  // f = div(sigma grad phi) at the nodes (each node its own region's value); empty means 0.
  std::vector<double> f;
  // [f/sigma] at the vertices; required when f is given. [d(f/sigma)/dn] at the vertices (the
  // cubic term of J); empty means 0.
  std::vector<double> f_over_sigma_jump, f_over_sigma_dxi_jump;
  // [phi] and [sigma phi_n] at the vertices; empty means zero.
  std::vector<double> w, v;
  PoissonBoundaryData3D boundary;
  // The integral of f^-/sigma^- over the inside, for a much more conducting inside with f given
  // (FastIim3DOptions::basis_min_ratio; the flux balance needs it to better than the
  // inverse of the ratio, which a grid sum cannot give). NaN: not given.
  double interior_source_integral = std::numeric_limits<double>::quiet_NaN();
};

// The shared settings (interface_solver_options.h; here the basis is the spherical harmonics,
// used above basis_min_ratio with shortest wavelength basis_wavelength_h = 4 h) and what only the
// surface solver has: the mesh-edge limit (the jump data live on the vertices), the harmonic
// degree cap, the flux balance's quadrature check (the 3D deflation's mean comes from a vertex
// quadrature whose error the ratio amplifies) and the set-up's threads.
struct FastIim3DOptions : InterfaceSolverOptions<3> {
  double max_edge_h = 2.0;
  int max_harmonic_degree = 48;  // the harmonic basis' largest degree
  // Refused above: the flux balance's quadrature error estimate relative to max |G|.
  double max_flux_balance_error = 0.05;
  // OpenMP threads of the set-up (the per-vertex fits and the band rows; <= 0: the OpenMP
  // default). The answer does not depend on it.
  int threads = 0;
};

class FastIimSolver3D {
 public:
  // Throws std::invalid_argument for a bad option (fit radius < 2, degree not 2 or 3).
  FastIimSolver3D(const Grid3D& grid, const PoissonBoundaries3D& bc,
                  const FastIim3DOptions& options = FastIim3DOptions());
  ~FastIimSolver3D();

  // g: initial guess for [phi_n] at the vertices on entry (another size: zero), the solution on
  // exit; phi: the grid solution. Throws std::invalid_argument for inconsistent sizes or
  // sigma <= 0, SolverError for a surface the grid cannot resolve, a refused conductivity ratio
  // or a GMRES that does not converge.
  InterfaceSolveReport Solve(const TriangleMesh& surface, const InterfaceProblem3D& problem,
                             std::vector<double>& g, std::vector<double>& phi);

  const std::vector<double>& normal_derivative_minus() const { return dn_minus_; }
  const std::vector<double>& normal_derivative_plus() const { return dn_plus_; }
  // Of the last solve, at the vertices: the unit outward normal of the fits, and the tangential
  // gradients grad_s phi^- (fit) and grad_s phi^+ = grad_s phi^- + grad_s w. The field is
  // E = -grad phi: E_n^+- = -phi_n^+-, E_tau^+- = -grad_s phi^+-.
  const Eigen::Matrix3Xd& normals() const { return fit_normal_; }
  const Eigen::Matrix3Xd& tangential_gradient_minus() const { return tangent_minus_; }
  const Eigen::Matrix3Xd& tangential_gradient_plus() const { return tangent_plus_; }
  // E = -grad phi on the grid for the phi of the last solve: centred differences of the values
  // seen from the node's side (phi, or phi -/+ J across the surface), second-order one-sided
  // differences at the box faces. Departure from song2019 sec. 2.4.4 (and the 2D
  // ComputeGridField), which take the first-order one-sided difference towards the same-side
  // neighbour at irregular nodes: with J known there, the extension keeps the field second order.
  void GridField(const std::vector<double>& phi, std::vector<double>& ex, std::vector<double>& ey,
                 std::vector<double>& ez) const;
  const SurfaceClassification3D& classification() const { return sides_; }
  // The normal-derivative operator alone, for testing it apart from the solve: phi_n^- at the
  // vertices from given grid values phi and jumps [phi_n] = g (with the data of the last Solve(),
  // whose surface it uses).
  void EvaluateNormalDerivative(const std::vector<double>& phi, const std::vector<double>& g,
                                std::vector<double>& dn_minus);
  const Grid3D& grid() const { return poisson_.grid(); }
  int poisson_solves() const { return poisson_solves_; }
  int band_nodes() const { return static_cast<int>(band_node_.size()); }
  // The largest cubic/quadratic disagreement of phi_n^- of the last solve, relative to max
  // |phi_n^+-| (FastIim3DOptions::max_fit_disagreement).
  double fit_disagreement() const { return fit_disagreement_; }
  // The largest vertex-scale content of G of the last solve relative to max(|G|, |phi_n^+-|)
  // (InterfaceSolverOptions::max_marker_oscillation; 0 for sigma^- = sigma^+).
  double point_oscillation() const { return point_oscillation_; }
  // Forget |b| of the last cold solve (InterfaceSolverOptions::warm_start_refresh > 0 only); the
  // next Solve() is cold.
  void ResetWarmStart() { schur_.ResetWarmStart(); }
  // Of the last solve: the degree L of the harmonic basis (0: G at the vertices), and the flux
  // balance's quadrature error estimate relative to max |G| (0 without the basis).
  int harmonic_degree() const { return harmonic_degree_; }
  double flux_balance_error() const { return flux_balance_error_; }

 private:
  void CheckResolution(const TriangleMesh& surface) const;
  // A grid segment crossed twice by the surface (a fold, or a part thinner than h): SolverError.
  void CheckThinParts(const TriangleMesh& surface) const;
  // w, v, the data part of J at the band nodes and F = f / sigma with the face data.
  void SetUpData(const TriangleMesh& surface, const InterfaceProblem3D& problem);
  // R(G) at the vertices for the Schur solver: dn^-(G) + (sigma^+/[sigma]) G (- v/[sigma]).
  InterfaceSchurSolver::PointResidual SchurResidual();
  // GMRES on the Schur system with G at every vertex (g: guess in, solution out).
  GmresResult SolveAtVertices(int nv, std::vector<double>& g);
  // grad_s phi^- from the fits' tangent rows and grad_s phi^+ = grad_s phi^- + grad_s w.
  void TangentialGradients(const std::vector<double>& phi);
  // IcosphereLevel(surface) (-1: not of icosphere connectivity), with IcosphereMesh(j)'s
  // triangles for j <= level kept for the quadrature weights (rebuilt only when the connectivity
  // changes).
  int CachedIcosphereLevel(const TriangleMesh& surface);
  // The harmonic basis of degree L: on the icosphere parametrisation for level >= 0 (cached by
  // level and degree), else at the directions of radial_ (rebuilt when the surface's positions or
  // the degree change).
  void SetUpHarmonicBasis(const TriangleMesh& surface, int level, int degree);
  // GMRES in the harmonic basis with the flux balance deflated (g: guess in, solution out);
  // level: the icosphere level, or -1 for the radial parametrisation.
  GmresResult SolveInHarmonicBasis(const TriangleMesh& surface, const InterfaceProblem3D& problem,
                                   int level, std::vector<double>& g);
  // The nodes of vertex v's normal-derivative fit, |r| < fit_radius_h h (r = node - vertex), in
  // (k, j, i) order: visit(node, r, |r|^2).
  template <typename Visit>
  void ForEachFitNode(const TriangleMesh& surface, int v, const Visit& visit) const;
  void SetUpBand(const TriangleMesh& surface);
  void SetUpFits(const TriangleMesh& surface);
  // Throws SolverError above max_fit_disagreement.
  void CheckFitAgreement(const std::vector<double>& phi, const std::vector<double>& g);
  // Vertex-scale content of G (graph Laplacian squared); SolverError above
  // max_marker_oscillation.
  void CheckPointOscillation(const TriangleMesh& surface, const std::vector<double>& g);
  // J at the band nodes for G (and the data part when with_data).
  void BandJump(const double* g, bool with_data);
  // Solves for phi, then phi_n^- at the vertices into dn.
  void PotentialAndNormalDerivative(const double* g, bool with_data, std::vector<double>& phi,
                                    std::vector<double>& dn);

  FastPoissonSolver3D poisson_;
  FastIim3DOptions options_;
  std::unique_ptr<LocalSurfaceFit> fit_;
  SurfaceClassification3D sides_;
  // Band: nodes whose J is needed (across a stencil from an irregular node, or outside within a
  // fit radius of a vertex). slot_ maps a node to its band slot (-1: not in the band).
  std::vector<int> slot_;
  std::vector<std::size_t> band_node_;
  std::vector<int> band_vertex_;                 // patch vertex of the foot point
  std::vector<int> band_offset_;                 // rows into the next three
  std::vector<int> band_support_;                // vertex indices
  std::vector<double> band_w_row_, band_g_row_;  // J rows (interface_jumps_3d.h)
  std::vector<double> band_f_coefficient_, band_f_dxi_coefficient_;
  std::vector<double> band_data_, band_jump_;
  struct Crossing {
    std::size_t node;
    int slot;
    double sign;
  };
  std::vector<Crossing> crossings_;
  // Normal-derivative fits: rows of (node, slot or -1 inside, gamma) per vertex.
  std::vector<int> fit_offset_;
  std::vector<std::size_t> fit_node_;
  std::vector<int> fit_slot_;
  std::vector<double> fit_gamma_, fit_gamma_t1_, fit_gamma_t2_, fit_gamma_check_;
  double fit_disagreement_ = 0, point_oscillation_ = 0;
  std::vector<double> dn_check_, laplacian_, point_content_;
  Eigen::Matrix3Xd fit_normal_, fit_t1_, fit_t2_;
  Eigen::Matrix3Xd tangent_minus_, tangent_plus_;
  std::vector<double> last_phi_side_jump_;  // J at the band nodes for the final G
  std::vector<double> rhs_base_, rhs_, phi_work_, dn_work_;
  std::vector<double> dn_minus_, dn_plus_;
  std::vector<double> w_, v_;
  double sigma_minus_ = 1, sigma_plus_ = 1;
  int poisson_solves_ = 0;
  InterfaceSchurSolver schur_;
  // Harmonic basis: Y at the vertices and the unit-sphere areas of the vertices (for projecting
  // a warm start), on the icosphere parametrisation (IcosphereMesh(basis_level_): the unit
  // icosphere's vertices and third areas) or, for basis_level_ = -1, on radial_ (its directions
  // and solid angles; basis_positions_: the surface it was built for).
  std::vector<std::vector<TriangleMesh::Triangle>> icosphere_triangles_;
  RadialParametrisation radial_;
  Eigen::Matrix3Xd basis_positions_;
  int basis_level_ = -1, basis_degree_ = -1;
  Eigen::MatrixXd basis_;
  Eigen::VectorXd basis_sphere_area_;
  int harmonic_degree_ = 0;
  double flux_balance_error_ = 0;
};

// Maxwell traction jump [M_E] . n per unit area at the vertices (song2019 sec. 3.5 in 3D),
// M_E = eps (E E - |E|^2 I / 2), E = E_n n + E_tau:
//   [M_E] . n = 1/2 [eps (E_n^2 - |E_tau|^2)] n + [eps E_n E_tau].
// Throws std::invalid_argument for inconsistent sizes.
Eigen::Matrix3Xd MaxwellTraction3D(const Eigen::Matrix3Xd& normal, double eps_minus,
                                   double eps_plus, const std::vector<double>& en_minus,
                                   const std::vector<double>& en_plus,
                                   const Eigen::Matrix3Xd& et_minus,
                                   const Eigen::Matrix3Xd& et_plus);

}  // namespace ehd
