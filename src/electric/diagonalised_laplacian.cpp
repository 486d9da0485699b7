// The diagonalised Laplacian of both fast Poisson solvers (diagonalised_laplacian.h).
#include "diagonalised_laplacian.h"

#include <cmath>
#include <cstring>
#include <mutex>
#include <stdexcept>

namespace ehd::poisson_detail {

DiagonalisedLaplacian::DiagonalisedLaplacian(const std::vector<const AxisTransform*>& axes,
                                             const std::vector<int>& sizes, double h,
                                             const std::string& owner) {
  const int rank = static_cast<int>(axes.size());
  // The normalisation and each eigenvalue sum from the fastest axis to the slowest (the order
  // of the sums is part of the result, bit for bit).
  double normalisation = 1.0;
  std::size_t n = 1;
  for (int a = rank - 1; a >= 0; --a) {
    normalisation *= axes[a]->normalisation;
    n *= static_cast<std::size_t>(sizes[a]);
  }
  const double h2 = h * h;
  const double scale = 1.0 / normalisation;
  inverse_eigenvalues_.assign(n, 0.0);
  std::vector<int> index(rank, 0);  // the multi-index of the flat position, slowest first
  for (std::size_t flat = 0; flat < n; ++flat) {
    double lambda = axes[rank - 1]->eigenvalues[index[rank - 1]];
    for (int a = rank - 2; a >= 0; --a) lambda += axes[a]->eigenvalues[index[a]];
    lambda /= h2;
    // The only zero eigenvalue is the constant mode of the singular (no Dirichlet) case.
    inverse_eigenvalues_[flat] = (std::abs(lambda) > 1e-12 / h2) ? scale / lambda : 0.0;
    for (int a = rank - 1; a >= 0 && ++index[a] == sizes[a]; --a) index[a] = 0;
  }
  std::vector<fftw_r2r_kind> forward(rank), inverse(rank);
  for (int a = 0; a < rank; ++a) {
    forward[a] = axes[a]->forward;
    inverse[a] = axes[a]->inverse;
  }
  std::lock_guard<std::mutex> lock(PlannerMutex());
  ImportWisdom();
  buffer_ = fftw_alloc_real(n);
  forward_ = fftw_plan_r2r(rank, sizes.data(), buffer_, buffer_, forward.data(), FFTW_MEASURE);
  inverse_ = fftw_plan_r2r(rank, sizes.data(), buffer_, buffer_, inverse.data(), FFTW_MEASURE);
  if (!forward_ || !inverse_) {
    if (forward_) fftw_destroy_plan(forward_);
    if (inverse_) fftw_destroy_plan(inverse_);
    fftw_free(buffer_);
    throw std::runtime_error(owner + ": FFTW could not make a plan");
  }
  ExportWisdom();
}

DiagonalisedLaplacian::~DiagonalisedLaplacian() {
  std::lock_guard<std::mutex> lock(PlannerMutex());
  if (forward_) fftw_destroy_plan(forward_);
  if (inverse_) fftw_destroy_plan(inverse_);
  if (buffer_) fftw_free(buffer_);
}

void DiagonalisedLaplacian::Solve(const std::vector<double>& rhs, std::vector<double>& solution) {
  const std::size_t n = inverse_eigenvalues_.size();
  double* __restrict buf = buffer_;
  std::memcpy(buf, rhs.data(), n * sizeof(double));
  fftw_execute(forward_);
  const double* __restrict inv = inverse_eigenvalues_.data();
  for (std::size_t k = 0; k < n; ++k) buf[k] *= inv[k];
  fftw_execute(inverse_);
  solution.resize(n);
  std::memcpy(solution.data(), buf, n * sizeof(double));
}

}  // namespace ehd::poisson_detail
