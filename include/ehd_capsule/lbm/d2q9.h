// D2Q9 lattice and the MRT moment basis of song2019 section 3.1.1 (eq. (98) and the matrix M that
// follows eq. (98); Lallemand & Luo, Phys. Rev. E 61, 6546 (2000)).
//
// Velocities (eq. (98)): c_0 = (0,0); c_1..c_4 = (1,0), (0,1), (-1,0), (0,-1);
// c_5..c_8 = (1,1), (-1,1), (-1,-1), (1,-1). Lattice units: dx = dt = 1, c_s^2 = 1/3.
// Moments m = M f = (rho, e, epsilon, j_x, q_x, j_y, q_y, p_xx, p_xy). The rows of M are
// mutually orthogonal, so M^-1 = M^T diag(1 / |row_k|^2) with |row_k|^2 = kMomentNorm[k].
//
// Relaxation-rate numbering: the reference counts from 0 (s_0 rho, s_1 e, s_2 epsilon, s_3 j_x,
// s_4 q_x, s_5 j_y, s_6 q_y, s_7 p_xx, s_8 p_xy), so its "s_2 = 1.54" is the rate of epsilon
// (energy square) and "s_4 = s_6 = 1.9" those of the heat fluxes q; s_1 (e, bulk viscosity,
// eq. (99)) is not given a value in the text.
#pragma once

#include <array>

namespace ehd::d2q9 {

inline constexpr int kQ = 9;
inline constexpr std::array<int, kQ> kCx = {0, 1, 0, -1, 0, 1, -1, -1, 1};
inline constexpr std::array<int, kQ> kCy = {0, 0, 1, 0, -1, 1, 1, -1, -1};
inline constexpr std::array<int, kQ> kOpposite = {0, 3, 4, 1, 2, 7, 8, 5, 6};
inline constexpr std::array<double, kQ> kWeight = {4.0 / 9,  1.0 / 9,  1.0 / 9,  1.0 / 9, 1.0 / 9,
                                                   1.0 / 36, 1.0 / 36, 1.0 / 36, 1.0 / 36};
inline constexpr double kSoundSpeedSquared = 1.0 / 3.0;

// Index of each moment in m.
enum Moment : int {
  kRho = 0,
  kEnergy = 1,
  kEnergySquare = 2,
  kMomentumX = 3,
  kHeatFluxX = 4,
  kMomentumY = 5,
  kHeatFluxY = 6,
  kStressXX = 7,
  kStressXY = 8
};

// The transformation matrix M (row k = moment k, column i = velocity i), as printed in song2019.
inline constexpr std::array<std::array<double, kQ>, kQ> kMomentMatrix = {{
    {1, 1, 1, 1, 1, 1, 1, 1, 1},
    {-4, -1, -1, -1, -1, 2, 2, 2, 2},
    {4, -2, -2, -2, -2, 1, 1, 1, 1},
    {0, 1, 0, -1, 0, 1, -1, -1, 1},
    {0, -2, 0, 2, 0, 1, -1, -1, 1},
    {0, 0, 1, 0, -1, 1, 1, -1, -1},
    {0, 0, -2, 0, 2, 1, 1, -1, -1},
    {0, 1, -1, 1, -1, 0, 0, 0, 0},
    {0, 0, 0, 0, 0, 1, -1, 1, -1},
}};

// Squared Euclidean norm of each row of M.
inline constexpr std::array<double, kQ> kMomentNorm = {9, 36, 36, 6, 12, 6, 12, 4, 4};

// Kinematic viscosity <-> shear relaxation rate (song2019 eq. (99), lattice units):
//   nu = (1/s_nu - 1/2) / 3,  s_nu = 1 / (3 nu + 1/2) = 1 / tau.
inline double ShearRateFromViscosity(double nu) { return 1.0 / (3.0 * nu + 0.5); }
inline double ViscosityFromShearRate(double s_nu) { return (1.0 / s_nu - 0.5) / 3.0; }

}  // namespace ehd::d2q9
