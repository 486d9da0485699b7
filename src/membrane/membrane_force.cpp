// f = d(tau t + q n)/dl = (dq/dl - kappa tau) n + (dtau/dl + kappa q) t, the negative of
// song2019 eq. (110); see membrane_force.h.
#include "ehd_capsule/membrane/membrane_force.h"

namespace ehd {

namespace {

// Fills the frames from any curve type with size(), orientation() and AtMarker(k).
template <typename Curve>
void FillFrames(const Curve& c, MarkerFrames& f) {
  const int m = c.size();
  if (f.tangent.cols() != m) {
    f.tangent.resize(2, m);
    f.normal.resize(2, m);
  }
  f.curvature.resize(m);
  f.orientation = c.orientation();
  for (int k = 0; k < m; ++k) {
    const CurvePoint p = c.AtMarker(k);
    f.tangent.col(k) = p.tangent;
    f.normal.col(k) = p.normal;
    f.curvature[k] = p.curvature;
  }
}

}  // namespace

void MarkerFrames::Update(const ClosedCurve& c) { FillFrames(c, *this); }

void MarkerFrames::Update(const CurveSegments& c) { FillFrames(c, *this); }

void MembraneForceDensity(const MarkerFrames& frames, const ArcLengthStencil& stencil,
                          const std::vector<double>& segment_tension, const std::vector<double>* q,
                          const std::vector<double>* dq_dl, std::vector<double>& tau_at_marker,
                          Eigen::Matrix2Xd& force_density) {
  const int m = stencil.size();
  if (force_density.cols() != m) force_density.resize(2, m);
  tau_at_marker.resize(m);
  for (int k = 0; k < m; ++k) {
    const double tau = stencil.SegmentToMarker(segment_tension, k);
    const double dtau = frames.orientation * stencil.SegmentDerivativeAtMarker(segment_tension, k);
    const double kappa = frames.curvature[k];
    double fn = -kappa * tau, ft = dtau;
    if (q != nullptr) {
      fn += (*dq_dl)[k];
      ft += kappa * (*q)[k];
    }
    tau_at_marker[k] = tau;
    force_density.col(k) = fn * frames.normal.col(k) + ft * frames.tangent.col(k);
  }
}

}  // namespace ehd
