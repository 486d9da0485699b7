// The core of the fast Poisson solvers of both dimensions (internal to the electric library): the
// cell-centred Laplacian diagonalised by one rank-2 or rank-3 FFTW real-to-real transform, each
// axis with its own transform pair and exact eigenvalues (poisson_axis.h). A solve is: forward
// transform, division by the eigenvalues (the normalisation folded in, the constant mode of a
// singular operator set to zero), inverse transform.
#pragma once

#include <fftw3.h>

#include <string>
#include <vector>

#include "poisson_axis.h"

namespace ehd::poisson_detail {

class DiagonalisedLaplacian {
 public:
  // axes and sizes in storage order, slowest first ((y, x) in 2D, (z, y, x) in 3D: index =
  // (k ny + j) nx + i); h the grid spacing; owner names the solver in errors. Plans with
  // FFTW_MEASURE under the planner mutex, through the shared wisdom file.
  DiagonalisedLaplacian(const std::vector<const AxisTransform*>& axes,
                        const std::vector<int>& sizes, double h, const std::string& owner);
  ~DiagonalisedLaplacian();
  DiagonalisedLaplacian(const DiagonalisedLaplacian&) = delete;
  DiagonalisedLaplacian& operator=(const DiagonalisedLaplacian&) = delete;

  // Laplacian(solution) = rhs, rhs of size(): solution resized (may alias rhs).
  void Solve(const std::vector<double>& rhs, std::vector<double>& solution);
  std::size_t size() const { return inverse_eigenvalues_.size(); }

 private:
  double* buffer_ = nullptr;
  fftw_plan forward_ = nullptr;
  fftw_plan inverse_ = nullptr;
  std::vector<double> inverse_eigenvalues_;  // 1 / (sum of the axes' lambdas) / normalisation
};

}  // namespace ehd::poisson_detail
