#include "interface_case.h"

#include <algorithm>
#include <cmath>

namespace ehd::test {

InterfaceCase::InterfaceCase(const std::string& name, int n, double sigma_minus, double sigma_plus,
                             int markers, const PoissonBoundaries& bc)
    : example(MakeInterfaceExample(name, sigma_minus, sigma_plus)), grid(example.MakeGrid(n)) {
  curve.Update(example.Markers(markers > 0 ? markers : example.DefaultMarkers(n)));
  problem = SampleInterfaceProblem(example, grid, curve, bc);
  exact = ExactSolution(example, grid, curve);
}

InterfaceCase::InterfaceCase(const InterfaceExample& e, int n, const Eigen::Matrix2Xd& x,
                             const PoissonBoundaries& bc)
    : example(e), grid(example.MakeGrid(n)), curve(x) {
  problem = SampleInterfaceProblem(example, grid, curve, bc);
  exact = ExactSolution(example, grid, curve);
}

double InterfaceCase::MaxError(const std::vector<double>& phi) const {
  double err = 0;
  for (std::size_t k = 0; k < phi.size(); ++k) err = std::max(err, std::abs(phi[k] - exact[k]));
  return err;
}

InterfaceCase3D::InterfaceCase3D(const std::string& name, int n, double sigma_minus,
                                 double sigma_plus)
    : InterfaceCase3D(MakeInterfaceExample3D(name, sigma_minus, sigma_plus), n) {}

InterfaceCase3D::InterfaceCase3D(const InterfaceExample3D& e, int n)
    : InterfaceCase3D(e, n, e.MeshFor(e.MakeGrid(n).h)) {}

InterfaceCase3D::InterfaceCase3D(const InterfaceExample3D& e, int n, const TriangleMesh& m)
    : example(e), grid(example.MakeGrid(n)), mesh(m), sides(ClassifyNodes(grid, mesh)) {
  problem = SampleInterfaceProblem3D(example, grid, mesh, sides);
}

double InterfaceCase3D::MaxNodeError(const FastIimSolver3D& solver,
                                     const std::vector<double>& phi) const {
  double err = 0;
  for (int k = 0; k < grid.nz; ++k)
    for (int j = 0; j < grid.ny; ++j)
      for (int i = 0; i < grid.nx; ++i) {
        const std::size_t c = grid.index(i, j, k);
        const Eigen::Vector3d p(grid.x(i), grid.y(j), grid.z(k));
        const bool outside = solver.classification().side[c] > 0;
        err = std::max(err,
                       std::abs(phi[c] - (outside ? example.phi_plus(p) : example.phi_minus(p))));
      }
  return err;
}

double InterfaceCase3D::MaxJumpError(const std::vector<double>& g) const {
  double err = 0;
  for (int v = 0; v < mesh.vertex_count(); ++v) {
    const Eigen::Vector3d x = mesh.vertices().col(v);
    err = std::max(
        err,
        std::abs(g[v] - (example.grad_plus(x) - example.grad_minus(x)).dot(example.normal(x))));
  }
  return err;
}

}  // namespace ehd::test
