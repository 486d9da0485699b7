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
  const Eigen::SelfAdjointEigenSolver<Matrix> spread(xx, Eigen::EigenvaluesOnly);
  const auto& lambda = spread.eigenvalues();  // ascending
  if (!(lambda(0) > 1e-12 * lambda(D - 1))) {
    throw std::invalid_argument(
        "ExtrapolateToPoints: the points do not span the dimension (no velocity gradient)");
  }
  Matrix gradient = ux * xx.inverse();                  // xx is D x D and well conditioned here
  gradient.diagonal().array() -= gradient.trace() / D;  // the inside is incompressible
  U += gradient * (points - retracted);
}

template <int D>
void RemoveEnclosedMeasureRate(const BodyShape<D>& shape, PointsOf<D>& U) {
  const PointsOf<D>& x = shape.positions();
  const Eigen::Index n = x.cols();
  PointsOf<D> g = PointsOf<D>::Zero(D, n);
  if constexpr (D == 2) {
    // A = (1/2) sum_k x_k x y_{k+1} - x_{k+1} x y_k: dA/dx_k = (1/2) (y_{k+1} - y_{k-1}, x_{k-1} -
    // x_{k+1}) for a counter-clockwise curve (sign-free below: only g's direction enters).
    for (Eigen::Index k = 0; k < n; ++k) {
      const Eigen::Vector2d next = x.col((k + 1) % n), prev = x.col((k + n - 1) % n);
      g(0, k) = 0.5 * (next.y() - prev.y());
      g(1, k) = 0.5 * (prev.x() - next.x());
    }
  } else {
    // V = (1/6) sum_t x_a . (x_b x x_c): dV/dx_a = (1/6) x_b x x_c over the triangles of a.
    for (const auto& t : shape.mesh.triangles()) {
      for (int c = 0; c < 3; ++c) {
        const Eigen::Vector3d b = x.col(t[(c + 1) % 3]), d = x.col(t[(c + 2) % 3]);
        g.col(t[c]) += b.cross(d) / 6.0;
      }
    }
  }
  const double norm2 = g.squaredNorm();
  if (!(norm2 > 0.0)) return;
  U -= (g.cwiseProduct(U).sum() / norm2) * g;
}

template void RetractAlongNormals<2>(const BodyShape<2>&, double, PointsOf<2>&);
template void RetractAlongNormals<3>(const BodyShape<3>&, double, PointsOf<3>&);
template void ExtrapolateToPoints<2>(const PointsOf<2>&, const PointsOf<2>&, PointsOf<2>&);
template void ExtrapolateToPoints<3>(const PointsOf<3>&, const PointsOf<3>&, PointsOf<3>&);
template void RemoveEnclosedMeasureRate<2>(const BodyShape<2>&, PointsOf<2>&);
template void RemoveEnclosedMeasureRate<3>(const BodyShape<3>&, PointsOf<3>&);

}  // namespace ehd
