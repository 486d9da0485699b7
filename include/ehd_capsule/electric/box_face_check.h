// The check every electric solver makes before solving: each interface point (marker or vertex)
// at least min_face_distance_h cells inside the faces of the solver's box. Measured on exact
// solutions (test/electric/box_face_check_test.cpp for the 2D fast IIM and the CFM,
// FastIimSolver3D.SurfaceNearABoxFaceIsAccurateOrRefused): the error is that of a centred
// interface down to 0.5-0.75 h from a face; once the interface passes between the last cell
// centres and the face, the face's condition sets the ghost values there instead of the
// interface problem, and the answer is O(1) wrong (0.1-0.3 on an O(1) potential) while every
// other check passes. The solvers refuse at 1 h, twice that limit.
#pragma once

#include <Eigen/Core>
#include <sstream>

#include "ehd_capsule/electric/gmres.h"  // SolverError
#include "ehd_capsule/geometry/grid.h"

namespace ehd {

// Throws SolverError "<solver>: <point_name> k (coordinates) is d h from the box face x = X
// (< min_face_distance_h = ...): ..." for the first point nearer a face than that.
template <int D>
void CheckInsideBoxFaces(const Grid<D>& grid, const Eigen::Matrix<double, D, Eigen::Dynamic>& x,
                         double min_face_distance_h, const char* solver, const char* point_name) {
  const double h = grid.h, margin = min_face_distance_h * h;
  for (Eigen::Index k = 0; k < x.cols(); ++k) {
    for (int a = 0; a < D; ++a) {
      const double lo = grid.origin(a), hi = lo + grid.extent(a) * h, p = x(a, k);
      if (p - lo >= margin && hi - p >= margin) continue;
      const bool low = p - lo < hi - p;
      std::ostringstream msg;
      msg << solver << ": " << point_name << " " << k << " (";
      for (int b = 0; b < D; ++b) msg << (b ? ", " : "") << x(b, k);
      msg << ") is " << (low ? p - lo : hi - p) / h << " h from the box face "
          << "xyz"[a] << " = " << (low ? lo : hi)
          << " (< min_face_distance_h = " << min_face_distance_h
          << "): between the last grid cells and the face the face's condition sets the "
             "potential, not the interface problem; enlarge the box (or move the interface)";
      throw SolverError(msg.str());
    }
  }
}

}  // namespace ehd
