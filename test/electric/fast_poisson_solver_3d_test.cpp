// 3D fast Poisson solver (electric/fast_poisson_solver_3d.h): the discrete operator is inverted
// exactly (a random discrete solution is recovered to round-off for every face combination), and
// manufactured smooth solutions with inhomogeneous Dirichlet / Neumann / periodic face data
// converge at second order.
#include "ehd_capsule/electric/fast_poisson_solver_3d.h"

#include <fftw3.h>
#include <gtest/gtest.h>
#include <stdlib.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <random>
#include <string>

namespace ehd {
namespace {

using K = BoundaryKind;

// The 7-point operator with homogeneous face conditions applied to u (ghosts: Dirichlet -u,
// Neumann u, periodic wrap), independently of the solver.
std::vector<double> ApplyLaplacian(const Grid3D& g, const PoissonBoundaries3D& bc,
                                   const std::vector<double>& u) {
  std::vector<double> out(g.size(), 0.0);
  const BoundaryKind lo[3] = {bc.x_min, bc.y_min, bc.z_min}, hi[3] = {bc.x_max, bc.y_max, bc.z_max};
  const int n[3] = {g.nx, g.ny, g.nz};
  for (int k = 0; k < g.nz; ++k)
    for (int j = 0; j < g.ny; ++j)
      for (int i = 0; i < g.nx; ++i) {
        const int c[3] = {i, j, k};
        const double centre = u[g.index(i, j, k)];
        double sum = 0;
        for (int a = 0; a < 3; ++a) {
          for (int s : {-1, 1}) {
            int d[3] = {i, j, k};
            d[a] += s;
            double v;
            if (d[a] < 0 || d[a] >= n[a]) {
              const BoundaryKind kind = d[a] < 0 ? lo[a] : hi[a];
              if (kind == K::kPeriodic) {
                d[a] = (d[a] + n[a]) % n[a];
                v = u[g.index(d[0], d[1], d[2])];
              } else {
                v = kind == K::kDirichlet ? -centre : centre;
              }
            } else {
              v = u[g.index(d[0], d[1], d[2])];
            }
            sum += v - centre;
          }
          (void)c;
        }
        out[g.index(i, j, k)] = sum / (g.h * g.h);
      }
  return out;
}

const PoissonBoundaries3D kCases[] = {
    {K::kDirichlet, K::kDirichlet, K::kDirichlet, K::kDirichlet, K::kDirichlet, K::kDirichlet},
    {K::kNeumann, K::kNeumann, K::kNeumann, K::kNeumann, K::kDirichlet, K::kDirichlet},  // ch. 6
    {K::kPeriodic, K::kPeriodic, K::kDirichlet, K::kNeumann, K::kPeriodic, K::kPeriodic},
    {K::kNeumann, K::kDirichlet, K::kDirichlet, K::kNeumann, K::kNeumann, K::kNeumann},
    {K::kNeumann, K::kNeumann, K::kNeumann, K::kNeumann, K::kNeumann, K::kNeumann},  // singular
};

TEST(FastPoissonSolver3D, InvertsTheDiscreteOperatorExactly) {
  std::mt19937 gen(3);
  std::uniform_real_distribution<double> uni(-1, 1);
  const Grid3D g{7, 6, 5, 0.3, 0, 0, 0};
  for (const PoissonBoundaries3D& bc : kCases) {
    std::vector<double> u(g.size());
    for (double& v : u) v = uni(gen);
    if (IsSingular(bc)) {  // the solver returns the zero-mean solution
      double mean = 0;
      for (double v : u) mean += v;
      mean /= u.size();
      for (double& v : u) v -= mean;
    }
    FastPoissonSolver3D solver(g, bc);
    std::vector<double> back;
    solver.Solve(ApplyLaplacian(g, bc, u), back);
    for (std::size_t n = 0; n < u.size(); ++n) EXPECT_NEAR(back[n], u[n], 1e-12);
  }
}

// u = exp(0.3 x) (periodic factors where an axis is periodic) on [0, 1]^3.
struct Manufactured {
  bool periodic[3];
  double Value(double x, double y, double z) const { return Axis(0, x) * Axis(1, y) * Axis(2, z); }
  double Axis(int a, double t) const {
    if (periodic[a]) return std::sin(2 * M_PI * t) + 2.0;
    const double w[3] = {1.1, 0.7, 1.3};
    return std::cos(w[a] * t + 0.2 * a) + 0.1 * t;
  }
  double D1(int a, double t) const {
    if (periodic[a]) return 2 * M_PI * std::cos(2 * M_PI * t);
    const double w[3] = {1.1, 0.7, 1.3};
    return -w[a] * std::sin(w[a] * t + 0.2 * a) + 0.1;
  }
  double D2(int a, double t) const {
    if (periodic[a]) return -4 * M_PI * M_PI * std::sin(2 * M_PI * t);
    const double w[3] = {1.1, 0.7, 1.3};
    return -w[a] * w[a] * std::cos(w[a] * t + 0.2 * a);
  }
};

double ManufacturedError(const PoissonBoundaries3D& bc, int n) {
  const Grid3D g{n, n, n, 1.0 / n, 0, 0, 0};
  const Manufactured m{
      {bc.x_min == K::kPeriodic, bc.y_min == K::kPeriodic, bc.z_min == K::kPeriodic}};
  std::vector<double> rhs(g.size()), exact(g.size());
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const double x = g.x(i), y = g.y(j), z = g.z(k);
        exact[g.index(i, j, k)] = m.Value(x, y, z);
        rhs[g.index(i, j, k)] = m.D2(0, x) * m.Axis(1, y) * m.Axis(2, z) +
                                m.Axis(0, x) * m.D2(1, y) * m.Axis(2, z) +
                                m.Axis(0, x) * m.Axis(1, y) * m.D2(2, z);
      }
  const PoissonBoundaryData3D data = SampleBoundaryData(
      g, bc, [&](double x, double y, double z) { return m.Value(x, y, z); },
      [&](double x, double y, double z) {
        return Eigen::Vector3d(m.D1(0, x) * m.Axis(1, y) * m.Axis(2, z),
                               m.Axis(0, x) * m.D1(1, y) * m.Axis(2, z),
                               m.Axis(0, x) * m.Axis(1, y) * m.D1(2, z));
      });
  AddBoundaryDataToRhs(g, bc, data, rhs);
  FastPoissonSolver3D solver(g, bc);
  std::vector<double> u;
  solver.Solve(rhs, u);
  double shift = 0;
  if (IsSingular(bc)) {
    for (std::size_t q = 0; q < u.size(); ++q) shift += exact[q] - u[q];
    shift /= u.size();
  }
  double err = 0;
  for (std::size_t q = 0; q < u.size(); ++q) err = std::max(err, std::abs(u[q] + shift - exact[q]));
  return err;
}

TEST(FastPoissonSolver3D, ManufacturedSolutionsConvergeAtSecondOrder) {
  for (const PoissonBoundaries3D& bc : kCases) {
    const double coarse = ManufacturedError(bc, 12), fine = ManufacturedError(bc, 24);
    EXPECT_GT(std::log2(coarse / fine), 1.8) << coarse << " " << fine;
    EXPECT_LT(fine, 3e-2);  // |u| up to ~3; the periodic factor sin(2 pi t) has u'''' ~ (2 pi)^4
  }
}

TEST(FastPoissonSolver3D, RejectsUnpairedPeriodicFacesAndWrongData) {
  const Grid3D g{4, 4, 4, 0.25, 0, 0, 0};
  PoissonBoundaries3D bc;
  bc.z_min = K::kPeriodic;
  EXPECT_THROW(FastPoissonSolver3D(g, bc), std::invalid_argument);
  PoissonBoundaryData3D data;
  data.x_min.assign(3, 0.0);
  std::vector<double> rhs(g.size(), 0.0);
  EXPECT_THROW(AddBoundaryDataToRhs(g, PoissonBoundaries3D{}, data, rhs), std::invalid_argument);
}

// The plans go to the wisdom file (src/electric/poisson_axis.h), which FFTW reads back, so a
// later process plans the same transforms the same way, and is rewritten only when a new size
// was planned; EHD_FFTW_WISDOM=off writes none. (That
// two processes then repeat a field run bit for bit is checked by hand in
// docs/validation_3d_ehd.md: one process cannot show it.)
TEST(FastPoissonSolver3D, PlansAreKeptInTheWisdomFile) {
  const char* before = std::getenv("EHD_FFTW_WISDOM");
  const std::string saved = before ? before : "";
  const std::string path = ::testing::TempDir() + "/ehd_fftw_wisdom_test";
  std::remove(path.c_str());
  setenv("EHD_FFTW_WISDOM", path.c_str(), 1);
  const Grid3D g{6, 5, 4, 0.25, 0, 0, 0};
  { FastPoissonSolver3D solver(g, PoissonBoundaries3D{}); }
  std::FILE* file = std::fopen(path.c_str(), "r");
  ASSERT_NE(file, nullptr) << path;
  std::fclose(file);
  EXPECT_EQ(fftw_import_wisdom_from_filename(path.c_str()), 1);
  // A solver of a size planned before adds nothing: the file is not rewritten.
  const auto old_time = std::filesystem::file_time_type::clock::now() - std::chrono::hours(1);
  std::filesystem::last_write_time(path, old_time);
  { FastPoissonSolver3D solver(g, PoissonBoundaries3D{}); }
  EXPECT_EQ(std::filesystem::last_write_time(path), old_time);
  // A new size is added to it.
  { FastPoissonSolver3D solver(Grid3D{7, 5, 4, 0.25, 0, 0, 0}, PoissonBoundaries3D{}); }
  EXPECT_NE(std::filesystem::last_write_time(path), old_time);
  std::remove(path.c_str());
  setenv("EHD_FFTW_WISDOM", "off", 1);
  { FastPoissonSolver3D solver(g, PoissonBoundaries3D{}); }
  EXPECT_EQ(std::fopen(path.c_str(), "r"), nullptr);
  if (before) {
    setenv("EHD_FFTW_WISDOM", saved.c_str(), 1);
  } else {
    unsetenv("EHD_FFTW_WISDOM");
  }
}

}  // namespace
}  // namespace ehd
