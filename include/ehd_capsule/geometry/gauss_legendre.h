// Gauss-Legendre rules.
//
// 5-point rule on [0, 1]: exact for polynomials of degree <= 9, so exact for the
// products of cubic-spline pieces that curve lengths, areas and moments integrate (the speed
// |X'| is not polynomial; its quadrature error is O(h^10) per segment).
#pragma once

namespace ehd {

inline constexpr int kGaussPoints = 5;
inline constexpr double kGaussNode[kGaussPoints] = {0.046910077030668, 0.230765344947158, 0.5,
                                                    0.769234655052842, 0.953089922969332};
inline constexpr double kGaussWeight[kGaussPoints] = {
    0.118463442528095, 0.239314335249683, 0.284444444444444, 0.239314335249683, 0.118463442528095};

// 4-point Gauss-Legendre rule on [-1, 1] (exact to degree 7), used for integrals along pieces of
// the interface in the correction function method.
inline constexpr double kGauss4Node[4] = {-0.861136311594052575, -0.339981043584856265,
                                          0.339981043584856265, 0.861136311594052575};
inline constexpr double kGauss4Weight[4] = {0.347854845137453857, 0.652145154862546143,
                                            0.652145154862546143, 0.347854845137453857};

}  // namespace ehd
