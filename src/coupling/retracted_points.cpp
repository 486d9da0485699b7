// The retracted immersed boundary (coupling/retracted_points.h).
#include "ehd_capsule/coupling/retracted_points.h"

#include <Eigen/Dense>
#include <stdexcept>

namespace ehd {

template <int D>
void RetractAlongNormals(const BodyShape<D>& shape, double distance, PointsOf<D>& out) {
  out = shape.positions();
  if constexpr (D == 2) {
    for (int k = 0; k < shape.size(); ++k) {
      out.col(k) -= distance * shape.curve.AtMarker(k).normal;
    }
  } else {
    out -= distance * AreaWeightedVertexNormals(shape.mesh);
  }
}

template <int D>
void ExtrapolateToPoints(const PointsOf<D>& retracted, const PointsOf<D>& points, PointsOf<D>& U) {
  using Matrix = Eigen::Matrix<double, D, D>;
  using Vector = Eigen::Matrix<double, D, 1>;
  const Eigen::Index n = retracted.cols();
  const Vector x_mean = retracted.rowwise().mean(), u_mean = U.rowwise().mean();
  Matrix xx = Matrix::Zero(), ux = Matrix::Zero();
  for (Eigen::Index k = 0; k < n; ++k) {
    const Vector dx = retracted.col(k) - x_mean;
    xx += dx * dx.transpose();
    ux += (U.col(k) - u_mean) * dx.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Matrix> spread(xx);
  const auto& lambda = spread.eigenvalues();  // ascending
  if (!(lambda(0) > 1e-12 * lambda(D - 1))) {
    throw std::invalid_argument(
        "ExtrapolateToPoints: the points do not span the dimension (no velocity gradient)");
  }
  // A = ux xx^{-1} (xx symmetric).
  const Matrix gradient = ux * spread.operatorInverseSqrt() * spread.operatorInverseSqrt();
  U += gradient * (points - retracted);
}

template void RetractAlongNormals<2>(const BodyShape<2>&, double, PointsOf<2>&);
template void RetractAlongNormals<3>(const BodyShape<3>&, double, PointsOf<3>&);
template void ExtrapolateToPoints<2>(const PointsOf<2>&, const PointsOf<2>&, PointsOf<2>&);
template void ExtrapolateToPoints<3>(const PointsOf<3>&, const PointsOf<3>&, PointsOf<3>&);

}  // namespace ehd
