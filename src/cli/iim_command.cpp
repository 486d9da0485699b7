// `ehd_sim iim`: convergence tables of the fast IIM on the manufactured interface problems of
// song2019 sec. 2.3.5 / 2.5 (and an ellipse and a five-petal star): per grid size N the L-inf
// error against the exact solution, error ratio, observed order, GMRES iterations and wall ms.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <limits>
#include <string>
#include <vector>

#include "command.h"
#include "ehd_capsule/electric/correction_function_solver.h"
#include "ehd_capsule/electric/fast_iim_solver.h"
#include "ehd_capsule/electric/interface_examples.h"

namespace ehd::cli {
namespace {

int RunIim(const std::vector<std::string>& args) {
  std::string example = "1", method = "iim";
  double sigma_minus = -1, sigma_plus = -1;
  std::vector<int> grids = {40, 80, 160, 320};
  int markers = 0;
  bool csv = false;
  int deferred = -1;  // -1: the solver's default (on)
  bool checks = true;
  double gmres_tolerance = -1.0;  // -1: the solver's default
  double marker_spacing = -1.0;   // in h; -1: the example's default (about 2 h)
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if (a == "--example") {
      example = OptionValue(args, i);
    } else if (a == "--method") {
      method = OptionValue(args, i);
      if (method != "iim" && method != "cfm") {
        throw UsageError("--method: expected iim or cfm, got '" + method + "'");
      }
    } else if (a == "--sigma-minus") {
      sigma_minus = ParseDouble(a, OptionValue(args, i));
      if (!(sigma_minus > 0)) throw UsageError("--sigma-minus must be > 0");
    } else if (a == "--sigma-plus") {
      sigma_plus = ParseDouble(a, OptionValue(args, i));
      if (!(sigma_plus > 0)) throw UsageError("--sigma-plus must be > 0");
    } else if (a == "--grids") {
      grids = ParseIntList(a, OptionValue(args, i));
      for (int n : grids)
        if (n < 8) throw UsageError("--grids: each N must be >= 8, got " + std::to_string(n));
    } else if (a == "--markers") {
      markers = static_cast<int>(ParseLong(a, OptionValue(args, i)));
      if (markers < 8) throw UsageError("--markers must be >= 8");
    } else if (a == "--deferred-correction") {
      deferred = 1;
    } else if (a == "--no-deferred-correction") {
      deferred = 0;
    } else if (a == "--marker-spacing") {
      marker_spacing = ParseDouble(a, OptionValue(args, i));
      if (!(marker_spacing > 0.0)) throw UsageError("--marker-spacing must be > 0");
    } else if (a == "--gmres-tolerance") {
      gmres_tolerance = ParseDouble(a, OptionValue(args, i));
      if (!(gmres_tolerance > 0.0 && gmres_tolerance < 1.0)) {
        throw UsageError("--gmres-tolerance must be in (0, 1)");
      }
    } else if (a == "--no-checks") {
      checks = false;
    } else if (a == "--csv") {
      csv = true;
    } else {
      throw UsageError("unknown option '" + a + "'");
    }
  }
  InterfaceExample e;
  try {
    e = MakeInterfaceExample(example);
    if (sigma_minus > 0 || sigma_plus > 0) {
      e = MakeInterfaceExample(example, sigma_minus > 0 ? sigma_minus : e.sigma_minus,
                               sigma_plus > 0 ? sigma_plus : e.sigma_plus);
    }
  } catch (const std::invalid_argument& err) {
    throw UsageError(std::string("--example: ") + err.what());
  }
  if (csv) {
    std::cout << "example,method,N,markers,sigma_minus,sigma_plus,linf_error,order,iterations,"
                 "solve_ms,estimated_error,status\n";
  } else {
    std::printf("example %s: %s\nmethod %s, sigma- = %g, sigma+ = %g\n", e.name.c_str(),
                e.description.c_str(), method.c_str(), e.sigma_minus, e.sigma_plus);
    std::printf("%6s %8s %12s %9s %7s %6s %10s %10s\n", "N", "markers", "Linf error", "ratio",
                "order", "iter", "ms/solve", "est. error");
  }
  double previous = 0.0;
  int previous_n = 0;
  int refused = 0;
  for (int n : grids) {
    const Grid2D grid = e.MakeGrid(n);
    int m = markers > 0 ? markers : e.DefaultMarkers(n);
    if (marker_spacing > 0.0) {
      // DefaultMarkers spaces markers about 2 h apart.
      m = std::max(8, static_cast<int>(std::lround(e.DefaultMarkers(n) * 2.0 / marker_spacing)));
    }
    const ClosedCurve curve(e.Markers(m));
    const InterfaceProblem problem = SampleInterfaceProblem(e, grid, curve);
    std::vector<double> phi;
    InterfaceSolveReport report;
    try {
      if (method == "iim") {
        FastIimOptions options;
        if (deferred >= 0) options.deferred_correction = deferred == 1;
        if (gmres_tolerance > 0.0) options.gmres.tolerance = gmres_tolerance;
        if (!checks) {
          options.max_curvature_h = options.max_marker_oscillation = options.verify_min_ratio =
              std::numeric_limits<double>::infinity();
        }
        FastIimSolver solver(grid, PoissonBoundaries{}, options);
        std::vector<double> g;
        report = solver.Solve(curve, problem, g, phi);
        // Time a second, identical solve from a cold guess (plans and buffers already made).
        g.clear();
        report = solver.Solve(curve, problem, g, phi);
      } else {
        CorrectionFunctionOptions options;
        if (deferred >= 0) options.deferred_correction = deferred == 1;
        CorrectionFunctionSolver solver(grid, PoissonBoundaries{}, options);
        report = solver.Solve(curve, problem, phi);
        report = solver.Solve(curve, problem, phi);
      }
    } catch (const SolverError& err) {
      // The solver refused (unresolved curve, failed verification): say so in the row and go
      // on with the next grid; the exit status is 1 at the end.
      ++refused;
      if (csv) {
        std::printf("%s,%s,%d,%d,%g,%g,,,,,,refused: %s\n", e.name.c_str(), method.c_str(), n, m,
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
    const double order =
        previous > 0 ? std::log(ratio) / std::log(static_cast<double>(n) / previous_n) : 0.0;
    if (csv) {
      std::printf("%s,%s,%d,%d,%g,%g,%.6e,%s,%d,%.3f,%s,ok\n", e.name.c_str(), method.c_str(), n, m,
                  e.sigma_minus, e.sigma_plus, err,
                  previous > 0 ? std::to_string(order).c_str() : "", report.iterations,
                  report.solve_ms, estimate.c_str());
    } else if (previous > 0) {
      std::printf("%6d %8d %12.4e %9.4f %7.3f %6d %10.2f %10s\n", n, m, err, ratio, order,
                  report.iterations, report.solve_ms, estimate.c_str());
    } else {
      std::printf("%6d %8d %12.4e %9s %7s %6d %10.2f %10s\n", n, m, err, "-", "-",
                  report.iterations, report.solve_ms, estimate.c_str());
    }
    previous = err;
    previous_n = n;
  }
  return refused > 0 ? 1 : 0;
}

const CommandRegistration kIim(
    {"iim", "convergence tables of the fast IIM / CFM on the interface examples",
     "usage: ehd_sim iim [--example 1|2|3|3a|3b|4|cfm1|cfm2|ellipse|star|star_tight|biconcave]\n"
     "                   [--method iim|cfm] [--sigma-minus S] [--sigma-plus S]\n"
     "                   [--grids 40,80,160,320]\n"
     "                   [--markers M | --marker-spacing S] [--[no-]deferred-correction]\n"
     "                   [--no-checks]\n"
     "                   [--gmres-tolerance TOL] [--csv]\n"
     "Solves the example on N x N grids of [-1,1]^2 and prints per N the L-inf error against\n"
     "the exact solution, the error ratio, observed order, GMRES iterations and ms per solve.\n"
     "--markers defaults to a marker spacing of about 2 h of arc length; --marker-spacing S\n"
     "sets it to about S h.\n"
     "The fast IIM refuses a grid that does not resolve the curve or whose answer it cannot\n"
     "verify (FastIimOptions: max_curvature_h, max_marker_oscillation, verify_min_ratio; the\n"
     "row says why, the exit status is then 1); 'est. error' is its a-posteriori estimate of the\n"
     "relative error of [phi_n] (sigma-/sigma+ >= 10). --no-checks turns the checks off to\n"
     "measure the bare discretisation.\n"
     "--[no-]deferred-correction: re-solve with the 5-point truncation T estimated from the\n"
     "first solution (FastIimOptions / CorrectionFunctionOptions::deferred_correction; default\n"
     "on for both).\n",
     RunIim});

}  // namespace
}  // namespace ehd::cli
