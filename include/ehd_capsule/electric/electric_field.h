// Electric field and interfacial electric force (song2019 sec. 2.4.4 and sec. 3.5, eq.
// (146)-(148)).
//
// Grid field E = -grad phi: centred differences at regular points; at an irregular point the
// one-sided difference towards the neighbour on the same side (sec. 2.4.4); if both neighbours
// of a direction lie across the curve, the centred difference of the same-side extension
// phi(x_k) - s_k J(x_k) (jump_relations.h). At the domain edges, one-sided differences.
//
// Force per unit length at a marker, from the jump of the Maxwell stress
// M_E = eps (E E - |E|^2 I / 2) across the interface, E = E_n n + E_tau t:
//   F_E = [M_E] . n = 1/2 [eps (E_n^2 - E_tau^2)] n + [eps E_n E_tau] t
// (sec. 3.5; with E_tau continuous this is 1/2 [eps (E_n^2 - E_tau^2)] n + [eps E_n] E_tau t),
// [q] = q^+ - q^-, n out of Omega^-, t counter-clockwise.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "ehd_capsule/electric/interface_classification.h"
#include "ehd_capsule/geometry/closed_curve.h"

namespace ehd {

// E = -grad phi on the grid (see the file comment). band_jump: J at the band points of classes.
void ComputeGridField(const InterfaceClassification& classes, const std::vector<double>& phi,
                      const std::vector<double>& band_jump, std::vector<double>& ex,
                      std::vector<double>& ey);

// Maxwell force density per unit length at the markers from the one-sided normal and
// tangential field components (E_n = -phi_n, E_tau = -phi_tau).
Eigen::Matrix2Xd MaxwellForce(const ClosedCurve& curve, double eps_minus, double eps_plus,
                              const std::vector<double>& en_minus,
                              const std::vector<double>& en_plus,
                              const std::vector<double>& et_minus,
                              const std::vector<double>& et_plus);

}  // namespace ehd
