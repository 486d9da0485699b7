// `ehd_sim iim`: convergence tables of the fast IIM on the manufactured interface problems of
// song2019 sec. 2.3.5 / 2.5 (and an ellipse and a five-petal star): per grid size N the L-inf
// error against the exact solution, error ratio, observed order, GMRES iterations and wall ms.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <limits>
#include <string>
#include <vector>

#include "command.h"
#include "ehd_capsule/electric/fast_iim_solver.h"
#include "ehd_capsule/electric/fast_iim_solver_3d.h"
#include "ehd_capsule/reference/correction_function_solver.h"
#include "ehd_capsule/reference/interface_examples.h"
#include "ehd_capsule/reference/interface_examples_3d.h"

namespace ehd::cli {
namespace {

// Max error over the nodes (each against its classified side's exact phi), of [phi_n] and of the
// Maxwell traction at the vertices (exact fields, exact normal).
struct Errors3D {
  double phi = 0, g = 0, traction = 0;
};

Errors3D MeasureErrors3D(const InterfaceExample3D& e, const Grid3D& grid, const TriangleMesh& mesh,
                         const FastIimSolver3D& solver, const std::vector<double>& g,
                         const std::vector<double>& phi, double eps_minus, double eps_plus) {
  Errors3D out;
  for (int k = 0; k < grid.nz; ++k)
    for (int j = 0; j < grid.ny; ++j)
      for (int i = 0; i < grid.nx; ++i) {
        const std::size_t c = grid.index(i, j, k);
        const Eigen::Vector3d p(grid.x(i), grid.y(j), grid.z(k));
        const double exact = solver.classification().side[c] > 0 ? e.phi_plus(p) : e.phi_minus(p);
        out.phi = std::max(out.phi, std::abs(phi[c] - exact));
      }
  const int nv = mesh.vertex_count();
  std::vector<double> en_minus(nv), en_plus(nv);
  for (int v = 0; v < nv; ++v) {
    en_minus[v] = -solver.normal_derivative_minus()[v];
    en_plus[v] = -solver.normal_derivative_plus()[v];
  }
  const Eigen::Matrix3Xd traction =
      MaxwellTraction3D(solver.normals(), eps_minus, eps_plus, en_minus, en_plus,
                        -solver.tangential_gradient_minus(), -solver.tangential_gradient_plus());
  for (int v = 0; v < nv; ++v) {
    const Eigen::Vector3d x = mesh.vertices().col(v), n = e.normal(x);
    const Eigen::Vector3d em = -e.grad_minus(x), ep = -e.grad_plus(x);
    out.g = std::max(out.g, std::abs(g[v] - (-ep.dot(n) + em.dot(n))));
    const double enm = em.dot(n), enp = ep.dot(n);
    const Eigen::Vector3d etm = em - enm * n, etp = ep - enp * n;
    const Eigen::Vector3d exact = 0.5 *
                                      (eps_plus * (enp * enp - etp.squaredNorm()) -
                                       eps_minus * (enm * enm - etm.squaredNorm())) *
                                      n +
                                  eps_plus * enp * etp - eps_minus * enm * etm;
    out.traction = std::max(out.traction, (traction.col(v) - exact).norm());
  }
  return out;
}

// The normal-derivative operator on its own: phi_n^- from the exact grid potential and the exact
// [phi_n], against the exact phi_n^- (max over the vertices).
double NormalDerivativeFitError(const InterfaceExample3D& e, const Grid3D& grid,
                                const TriangleMesh& mesh, FastIimSolver3D& solver) {
  double fit_error = 0;
  std::vector<double> exact_phi(grid.size()), exact_g(mesh.vertex_count()), dn;
  for (int k = 0; k < grid.nz; ++k)
    for (int j = 0; j < grid.ny; ++j)
      for (int i = 0; i < grid.nx; ++i) {
        const std::size_t c = grid.index(i, j, k);
        const Eigen::Vector3d p(grid.x(i), grid.y(j), grid.z(k));
        exact_phi[c] = solver.classification().side[c] > 0 ? e.phi_plus(p) : e.phi_minus(p);
      }
  for (int v = 0; v < mesh.vertex_count(); ++v) {
    const Eigen::Vector3d x = mesh.vertices().col(v);
    exact_g[v] = (e.grad_plus(x) - e.grad_minus(x)).dot(e.normal(x));
  }
  solver.EvaluateNormalDerivative(exact_phi, exact_g, dn);
  for (int v = 0; v < mesh.vertex_count(); ++v) {
    const Eigen::Vector3d x = mesh.vertices().col(v);
    fit_error = std::max(fit_error, std::abs(dn[v] - e.grad_minus(x).dot(e.normal(x))));
  }
  return fit_error;
}

// The time of one Poisson solve of the grid's size (the mean of 3 after a first one), for the
// cost ratio of an interface solve.
double PoissonSolveMs(const Grid3D& grid, const PoissonBoundaries3D& boundaries) {
  FastPoissonSolver3D poisson(grid, boundaries);
  std::vector<double> rhs(grid.size(), 1.0), out;
  poisson.Solve(rhs, out);
  const auto t0 = std::chrono::steady_clock::now();
  for (int r = 0; r < 3; ++r) poisson.Solve(rhs, out);
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count() /
         3;
}

// A second solve with the surface moved by 0.01 h along x, from g (the previous solution).
InterfaceSolveReport ResolveMoved(const InterfaceExample3D& e, const Grid3D& grid,
                                  const TriangleMesh& mesh, FastIimSolver3D& solver,
                                  std::vector<double>& g) {
  Eigen::Matrix3Xd moved = mesh.vertices();
  moved.row(0).array() += 0.01 * grid.h;
  TriangleMesh shifted = mesh;
  shifted.SetVertices(moved);
  const InterfaceProblem3D p2 =
      SampleInterfaceProblem3D(e, grid, shifted, ClassifyNodes(grid, shifted));
  std::vector<double> phi2;
  return solver.Solve(shifted, p2, g, phi2);
}

int RunIim3D(const std::vector<std::string>& args) {
  std::string example = "sphere_field";
  double sigma_minus = 1, sigma_plus = 1, eps_minus = 3.5, eps_plus = 1;
  std::vector<int> grids = {32, 48, 64, 96};
  bool csv = false, warm = false;
  int mesh_level = 0;  // 0: the coarsest with edges <= 1.5 h
  FastIim3DOptions options;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if (a == "--dim") {
      OptionValue(args, i);
    } else if (a == "--example") {
      example = OptionValue(args, i);
    } else if (a == "--sigma-minus" || a == "--sigma-plus" || a == "--eps-minus" ||
               a == "--eps-plus") {
      const double value = ParseDouble(a, OptionValue(args, i));
      if (!(value > 0)) throw UsageError(a + " must be > 0");
      (a == "--sigma-minus"  ? sigma_minus
       : a == "--sigma-plus" ? sigma_plus
       : a == "--eps-minus"  ? eps_minus
                             : eps_plus) = value;
    } else if (a == "--grids") {
      grids = ParseIntList(a, OptionValue(args, i));
      for (int n : grids)
        if (n < 8) throw UsageError("--grids: each N must be >= 8, got " + std::to_string(n));
    } else if (a == "--max-fit-disagreement") {
      options.max_fit_disagreement = ParseDouble(a, OptionValue(args, i));
    } else if (a == "--max-harmonic-degree") {
      options.max_harmonic_degree = static_cast<int>(ParseLong(a, OptionValue(args, i)));
      if (options.max_harmonic_degree < 2 || options.max_harmonic_degree > 64) {
        throw UsageError("--max-harmonic-degree must be in [2, 64]");
      }
    } else if (a == "--max-inner-ratio") {
      options.max_inner_ratio = ParseDouble(a, OptionValue(args, i));
    } else if (a == "--gmres-tolerance") {
      options.gmres.tolerance = ParseDouble(a, OptionValue(args, i));
      if (!(options.gmres.tolerance > 0.0 && options.gmres.tolerance < 1.0)) {
        throw UsageError("--gmres-tolerance must be in (0, 1)");
      }
    } else if (a == "--mesh-level") {
      mesh_level = static_cast<int>(ParseLong(a, OptionValue(args, i)));
      if (mesh_level < 1 || mesh_level > 7) throw UsageError("--mesh-level must be in [1, 7]");
    } else if (a == "--warm") {
      warm = true;
    } else if (a == "--csv") {
      csv = true;
    } else {
      throw UsageError("unknown option '" + a + "'");
    }
  }
  InterfaceExample3D e;
  try {
    e = MakeInterfaceExample3D(example, sigma_minus, sigma_plus);
  } catch (const std::invalid_argument& err) {
    throw UsageError(std::string("--example: ") + err.what());
  }
  if (csv) {
    std::cout
        << "example,N,vertices,sigma_minus,sigma_plus,linf_phi,order_phi,linf_g,order_g,"
           "linf_traction,order_traction,fit_error,fit_disagreement,iterations,solve_ms,"
           "poisson_solves,poisson_ms,warm_iterations,warm_ms,harmonic_degree,flux_balance_error,"
           "status\n";
  } else {
    std::printf("3D example %s: %s\nsigma- = %g, sigma+ = %g, eps- = %g, eps+ = %g\n",
                e.name.c_str(), e.description.c_str(), sigma_minus, sigma_plus, eps_minus,
                eps_plus);
    std::printf("%5s %8s %10s %6s %10s %6s %10s %6s %10s %9s %5s %9s %7s %9s %3s %9s%s\n", "N",
                "vertices", "Linf phi", "order", "[phi_n]", "order", "traction", "order",
                "fit(exact)", "fit dis.", "iter", "ms/solve", "solves", "Poisson ms", "L",
                "flux err", warm ? "  warm iter  warm ms" : "");
  }
  Errors3D previous;
  int previous_n = 0, refused = 0;
  for (int n : grids) {
    const Grid3D grid = e.MakeGrid(n);
    const TriangleMesh mesh = mesh_level > 0 ? e.mesh(mesh_level) : e.MeshFor(grid.h);
    FastIimSolver3D solver(grid, e.boundaries, options);
    std::vector<double> g, phi;
    InterfaceSolveReport report;
    const SurfaceClassification3D sides = ClassifyNodes(grid, mesh);
    const InterfaceProblem3D problem = SampleInterfaceProblem3D(e, grid, mesh, sides);
    try {
      report = solver.Solve(mesh, problem, g, phi);
    } catch (const SolverError& err) {
      ++refused;
      if (csv) {
        std::printf("%s,%d,%d,%g,%g,,,,,,,,,,,,,,,refused: %s\n", e.name.c_str(), n,
                    mesh.vertex_count(), sigma_minus, sigma_plus, err.what());
      } else {
        std::printf("%5d %8d   refused: %s\n", n, mesh.vertex_count(), err.what());
      }
      previous_n = 0;
      continue;
    }
    const int solves = solver.poisson_solves();
    const double disagreement = solver.fit_disagreement();
    const int harmonic_degree = solver.harmonic_degree();
    const double flux_error = solver.flux_balance_error();
    const double fit_error = NormalDerivativeFitError(e, grid, mesh, solver);
    const Errors3D err = MeasureErrors3D(e, grid, mesh, solver, g, phi, eps_minus, eps_plus);
    const double poisson_ms = PoissonSolveMs(grid, e.boundaries);
    // Warm start: the surface moved by 0.01 h, G of the solve above as the guess.
    int warm_iterations = -1;
    double warm_ms = 0;
    if (warm) {
      const InterfaceSolveReport r2 = ResolveMoved(e, grid, mesh, solver, g);
      warm_iterations = r2.iterations;
      warm_ms = r2.solve_ms;
    }
    const auto order = [&](double now, double before) {
      return previous_n > 0 ? std::log(before / now) / std::log(static_cast<double>(n) / previous_n)
                            : std::nan("");
    };
    const double op = order(err.phi, previous.phi), og = order(err.g, previous.g),
                 ot = order(err.traction, previous.traction);
    if (csv) {
      std::printf(
          "%s,%d,%d,%g,%g,%.6e,%.3f,%.6e,%.3f,%.6e,%.3f,%.6e,%.6e,%d,%.2f,%d,%.3f,%d,%.2f,%d,%.3e,"
          "ok\n",
          e.name.c_str(), n, mesh.vertex_count(), sigma_minus, sigma_plus, err.phi, op, err.g, og,
          err.traction, ot, fit_error, disagreement, report.iterations, report.solve_ms, solves,
          poisson_ms, warm_iterations, warm_ms, harmonic_degree, flux_error);
    } else {
      std::printf(
          "%5d %8d %10.3e %6.2f %10.3e %6.2f %10.3e %6.2f %10.2e %9.2e %5d %9.1f %7d %9.2f %3d "
          "%9.2e",
          n, mesh.vertex_count(), err.phi, op, err.g, og, err.traction, ot, fit_error, disagreement,
          report.iterations, report.solve_ms, solves, poisson_ms, harmonic_degree, flux_error);
      if (warm) std::printf("  %9d %8.1f", warm_iterations, warm_ms);
      std::printf("\n");
    }
    previous = err;
    previous_n = n;
  }
  return refused > 0 ? 1 : 0;
}

// The options of ehd_sim iim --dim 2.
struct Iim2DOptions {
  std::string example = "1", method = "iim";
  double sigma_minus = -1, sigma_plus = -1;
  std::vector<int> grids = {40, 80, 160, 320};
  int markers = 0;
  bool csv = false;
  int deferred = -1;  // -1: the solver's default (on)
  bool checks = true;
  double gmres_tolerance = -1.0;  // -1: the solver's default
  double marker_spacing = -1.0;   // in h; -1: the example's default (about 2 h)
  double control_spacing = -1.0;  // FastIimOptions::min_control_spacing_h; -1: its default
  double wavelength = -1.0;       // FastIimOptions::basis_wavelength_h; -1: its default
};

Iim2DOptions ParseIim2D(const std::vector<std::string>& args) {
  Iim2DOptions o;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if (a == "--example") {
      o.example = OptionValue(args, i);
    } else if (a == "--dim") {
      OptionValue(args, i);  // 2 (3 is dispatched above)
    } else if (a == "--method") {
      o.method = OptionValue(args, i);
      if (o.method != "iim" && o.method != "cfm") {
        throw UsageError("--method: expected iim or cfm, got '" + o.method + "'");
      }
    } else if (a == "--sigma-minus") {
      o.sigma_minus = ParseDouble(a, OptionValue(args, i));
      if (!(o.sigma_minus > 0)) throw UsageError("--sigma-minus must be > 0");
    } else if (a == "--sigma-plus") {
      o.sigma_plus = ParseDouble(a, OptionValue(args, i));
      if (!(o.sigma_plus > 0)) throw UsageError("--sigma-plus must be > 0");
    } else if (a == "--grids") {
      o.grids = ParseIntList(a, OptionValue(args, i));
      for (int n : o.grids)
        if (n < 8) throw UsageError("--grids: each N must be >= 8, got " + std::to_string(n));
    } else if (a == "--markers") {
      o.markers = static_cast<int>(ParseLong(a, OptionValue(args, i)));
      if (o.markers < 8) throw UsageError("--markers must be >= 8");
    } else if (a == "--deferred-correction") {
      o.deferred = 1;
    } else if (a == "--no-deferred-correction") {
      o.deferred = 0;
    } else if (a == "--marker-spacing") {
      o.marker_spacing = ParseDouble(a, OptionValue(args, i));
      if (!(o.marker_spacing > 0.0)) throw UsageError("--marker-spacing must be > 0");
    } else if (a == "--gmres-tolerance") {
      o.gmres_tolerance = ParseDouble(a, OptionValue(args, i));
      if (!(o.gmres_tolerance > 0.0 && o.gmres_tolerance < 1.0)) {
        throw UsageError("--gmres-tolerance must be in (0, 1)");
      }
    } else if (a == "--fourier-wavelength") {
      o.wavelength = ParseDouble(a, OptionValue(args, i));
      if (!(o.wavelength >= 0.0)) throw UsageError("--fourier-wavelength must be >= 0");
    } else if (a == "--control-spacing") {
      o.control_spacing = ParseDouble(a, OptionValue(args, i));
      if (!(o.control_spacing > 0.0)) throw UsageError("--control-spacing must be > 0");
    } else if (a == "--no-checks") {
      o.checks = false;
    } else if (a == "--csv") {
      o.csv = true;
    } else {
      throw UsageError("unknown option '" + a + "'");
    }
  }
  return o;
}

// One grid of the table: the example solved by the chosen method (twice, the second timed);
// phi the grid solution, *jump_error the error of [phi_n] (iim; -1 for cfm). Throws SolverError
// when the solver refuses.
InterfaceSolveReport SolveOneGrid(const Iim2DOptions& o, const InterfaceExample& e,
                                  const Grid2D& grid, const ClosedCurve& curve,
                                  const InterfaceProblem& problem, std::vector<double>& phi,
                                  double* jump_error) {
  InterfaceSolveReport report;
  *jump_error = -1.0;
  if (o.method == "iim") {
    FastIimOptions options;
    if (o.deferred >= 0) options.deferred_correction = o.deferred == 1;
    if (o.gmres_tolerance > 0.0) options.gmres.tolerance = o.gmres_tolerance;
    if (o.control_spacing > 0.0) options.min_control_spacing_h = o.control_spacing;
    if (o.wavelength >= 0.0) options.basis_wavelength_h = o.wavelength;
    if (!o.checks) {
      options.max_curvature_h = options.max_marker_oscillation = options.verify_min_ratio =
          options.max_fit_disagreement = options.max_inner_ratio =
              std::numeric_limits<double>::infinity();
    }
    FastIimSolver solver(grid, PoissonBoundaries{}, options);
    std::vector<double> g;
    report = solver.Solve(curve, problem, g, phi);
    // Time a second, identical solve from a cold guess (plans and buffers already made).
    g.clear();
    report = solver.Solve(curve, problem, g, phi);
    *jump_error = JumpNormalDerivativeError(e, curve, g);
  } else {
    CorrectionFunctionOptions options;
    if (o.deferred >= 0) options.deferred_correction = o.deferred == 1;
    CorrectionFunctionSolver solver(grid, PoissonBoundaries{}, options);
    report = solver.Solve(curve, problem, phi);
    report = solver.Solve(curve, problem, phi);
  }
  return report;
}

int RunIim(const std::vector<std::string>& args) {
  for (std::size_t i = 0; i + 1 < args.size(); ++i) {
    if (args[i] == "--dim") {
      if (args[i + 1] == "3") return RunIim3D(args);
      if (args[i + 1] != "2") throw UsageError("--dim: expected 2 or 3, got '" + args[i + 1] + "'");
    }
  }
  const Iim2DOptions o = ParseIim2D(args);
  InterfaceExample e;
  try {
    e = MakeInterfaceExample(o.example);
    if (o.sigma_minus > 0 || o.sigma_plus > 0) {
      e = MakeInterfaceExample(o.example, o.sigma_minus > 0 ? o.sigma_minus : e.sigma_minus,
                               o.sigma_plus > 0 ? o.sigma_plus : e.sigma_plus);
    }
  } catch (const std::invalid_argument& err) {
    throw UsageError(std::string("--example: ") + err.what());
  }
  if (o.csv) {
    std::cout << "example,method,N,markers,sigma_minus,sigma_plus,linf_error,order,iterations,"
                 "solve_ms,estimated_error,jump_error,status\n";
  } else {
    std::printf("example %s: %s\nmethod %s, sigma- = %g, sigma+ = %g\n", e.name.c_str(),
                e.description.c_str(), o.method.c_str(), e.sigma_minus, e.sigma_plus);
    std::printf("%6s %8s %12s %9s %7s %6s %10s %10s %10s\n", "N", "markers", "Linf error", "ratio",
                "order", "iter", "ms/solve", "est. error", "G error");
  }
  double previous = 0.0;
  int previous_n = 0;
  int refused = 0;
  for (int n : o.grids) {
    const Grid2D grid = e.MakeGrid(n);
    int m = o.markers > 0 ? o.markers : e.DefaultMarkers(n);
    if (o.marker_spacing > 0.0) {
      // DefaultMarkers spaces markers about 2 h apart.
      m = std::max(8, static_cast<int>(std::lround(e.DefaultMarkers(n) * 2.0 / o.marker_spacing)));
    }
    const ClosedCurve curve(e.Markers(m));
    const InterfaceProblem problem = SampleInterfaceProblem(e, grid, curve);
    std::vector<double> phi;
    InterfaceSolveReport report;
    double jump_error = -1.0;  // of [phi_n] (iim only)
    try {
      report = SolveOneGrid(o, e, grid, curve, problem, phi, &jump_error);
    } catch (const SolverError& err) {
      // The solver refused (unresolved curve, failed verification): say so in the row and go
      // on with the next grid; the exit status is 1 at the end.
      ++refused;
      if (o.csv) {
        std::printf("%s,%s,%d,%d,%g,%g,,,,,,,refused: %s\n", e.name.c_str(), o.method.c_str(), n, m,
                    e.sigma_minus, e.sigma_plus, err.what());
      } else {
        std::printf("%6d %8d   refused: %s\n", n, m, err.what());
      }
      previous = 0.0;
      continue;
    }
    const std::vector<double> exact = ExactSolution(e, grid, curve);
    double err = 0.0;
    for (std::size_t k = 0; k < exact.size(); ++k) err = std::max(err, std::abs(phi[k] - exact[k]));
    const double ratio = previous > 0 ? previous / err : 0.0;
    char estimate_text[32] = "-";
    if (report.estimated_error >= 0) {
      std::snprintf(estimate_text, sizeof estimate_text, "%.2e", report.estimated_error);
    }
    const std::string estimate = estimate_text;
    char jump_text[32] = "-";
    if (jump_error >= 0) std::snprintf(jump_text, sizeof jump_text, "%.2e", jump_error);
    const double order =
        previous > 0 ? std::log(ratio) / std::log(static_cast<double>(n) / previous_n) : 0.0;
    if (o.csv) {
      std::printf("%s,%s,%d,%d,%g,%g,%.6e,%s,%d,%.3f,%s,%s,ok\n", e.name.c_str(), o.method.c_str(),
                  n, m, e.sigma_minus, e.sigma_plus, err,
                  previous > 0 ? std::to_string(order).c_str() : "", report.iterations,
                  report.solve_ms, estimate.c_str(), jump_error >= 0 ? jump_text : "");
    } else if (previous > 0) {
      std::printf("%6d %8d %12.4e %9.4f %7.3f %6d %10.2f %10s %10s\n", n, m, err, ratio, order,
                  report.iterations, report.solve_ms, estimate.c_str(), jump_text);
    } else {
      std::printf("%6d %8d %12.4e %9s %7s %6d %10.2f %10s %10s\n", n, m, err, "-", "-",
                  report.iterations, report.solve_ms, estimate.c_str(), jump_text);
    }
    previous = err;
    previous_n = n;
  }
  return refused > 0 ? 1 : 0;
}

const CommandRegistration kIim(
    {"iim", "convergence tables of the fast IIM / CFM on the interface examples (2D and 3D)",
     "usage: ehd_sim iim [--dim 2] [--example "
     "1|2|3|3a|3b|4|cfm1|cfm2|ellipse|star|star_tight|star_sharp|biconcave]\n"
     "                   [--method iim|cfm] [--sigma-minus S] [--sigma-plus S]\n"
     "                   [--grids 40,80,160,320]\n"
     "                   [--markers M | --marker-spacing S] [--[no-]deferred-correction]\n"
     "                   [--no-checks] [--fourier-wavelength H] [--control-spacing H]\n"
     "                   [--gmres-tolerance TOL] [--csv]\n"
     "Solves the example on N x N grids of [-1,1]^2 and prints per N the L-inf error against\n"
     "the exact solution, the error ratio, observed order, GMRES iterations and ms per solve.\n"
     "--markers defaults to a marker spacing of about 2 h of arc length; --marker-spacing S\n"
     "sets it to about S h.\n"
     "The fast IIM refuses a grid that does not resolve the curve or whose answer it cannot\n"
     "verify (FastIimOptions: max_curvature_h, max_marker_oscillation, max_fit_disagreement,\n"
     "max_inner_ratio, verify_min_ratio, and a curve thinner than h; the row says why, the exit\n"
     "status is then 1); 'est. error' is its a-posteriori estimate of the relative error of\n"
     "[phi_n] (sigma-/sigma+ >= 10). --no-checks turns the checks with a threshold off to\n"
     "measure the bare discretisation.\n"
     "--[no-]deferred-correction: re-solve with the 5-point truncation T estimated from the\n"
     "first solution (FastIimOptions / CorrectionFunctionOptions::deferred_correction; default\n"
     "on for both).\n"
     "'G error': max |[phi_n] - exact| at the markers relative to max(|[phi_n]|, |phi_n|).\n"
     "--fourier-wavelength H: the shortest wavelength, in h, of the Fourier basis of [phi_n]\n"
     "for sigma-/sigma+ >= 10 (FastIimOptions::basis_wavelength_h, default 5; 0: as many\n"
     "terms as controls); --control-spacing H: FastIimOptions::min_control_spacing_h (1.5).\n"
     "\n"
     "usage: ehd_sim iim --dim 3 [--example sphere_field|sphere|ellipsoid|biconcave]\n"
     "                   [--sigma-minus S] [--sigma-plus S] [--eps-minus E] [--eps-plus E]\n"
     "                   [--grids 32,48,64,96] [--max-inner-ratio R] [--gmres-tolerance TOL]\n"
     "                   [--max-fit-disagreement F] [--mesh-level L] [--warm] [--csv]\n"
     "                   [--max-harmonic-degree L]\n"
     "The 3D fast IIM (FastIimSolver3D) on N^3 grids of [-1,1]^3, the mesh level the coarsest\n"
     "with edges <= 1.5 h (or --mesh-level: icosphere level, 4 = 2562 vertices): per N the\n"
     "L-inf error of phi over the nodes, of [phi_n] and of the Maxwell traction (eps-, eps+;\n"
     "default 3.5, 1) at the vertices, observed orders; 'fit(exact)', the phi_n^- error of the\n"
     "normal-derivative fit applied to the exact potential (the operator on its own);\n"
     "'fit dis.', the cubic/quadratic disagreement the solver checks; GMRES iterations, ms per\n"
     "solve, Poisson solves per solve and the time of one Poisson solve of that size; 'L', the\n"
     "degree of the spherical-harmonic basis of [phi_n] (sigma-/sigma+ above\n"
     "basis_min_ratio = 10; 0: vertex values) and 'flux err', the flux balance's\n"
     "quadrature error estimate relative to max |[phi_n]|.\n"
     "--warm: re-solve with the surface moved by 0.01 h from the previous G.\n"
     "A refused solve (unresolved surface, sigma-/sigma+ > max-inner-ratio, failed checks) is\n"
     "a row saying why; the exit status is then 1.\n",
     RunIim});

}  // namespace
}  // namespace ehd::cli
