// A body of the coupled step (a capsule, a drop or a red cell): one type over the dimension D.
// Contracts in docs/architecture.md ("Body" and "Force source"); in short:
//   - the geometry is BodyShape<D>: markers on a closed curve (2D) or the vertices of a triangle
//     mesh (3D), stored unwrapped along periodic axes, moved only through SetPositions, which
//     keeps the curve or mesh consistent with the points;
//   - every force on the membrane is a ForceSource in the body's list, written by the stage that
//     owns it; the sources add up in one place, Body::SumLoads, in list order;
//   - a source's load is in the body's load unit: force per unit length at each marker in 2D
//     (the spread multiplies by the arc element dl, song2019 eq. (106)), force per vertex in 3D
//     (finite-element nodal forces are already integrated over the vertex's area).
// A step holds a list of bodies (StepData::bodies); the shipped scenes have one.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "ehd_capsule/coupling/simulation_state.h"
#include "ehd_capsule/geometry/closed_curve.h"
#include "ehd_capsule/geometry/triangle_mesh.h"

namespace ehd {

template <int D>
using PointsOf = Eigen::Matrix<double, D, Eigen::Dynamic>;

// The membrane's geometry, the only dimension-specific part of a body.
template <int D>
struct BodyShape;

template <>
struct BodyShape<2> {
  static constexpr const char* kPointName = "marker";
  Eigen::Matrix2Xd X;  // marker positions (lattice units)
  ClosedCurve curve;   // the periodic spline through X
  const Eigen::Matrix2Xd& positions() const { return X; }
  // Throws what ClosedCurve::Update throws for a degenerate curve.
  void SetPositions(const Eigen::Matrix2Xd& x) {
    X = x;
    curve.Update(X);
  }
  int size() const { return static_cast<int>(X.cols()); }
};

template <>
struct BodyShape<3> {
  static constexpr const char* kPointName = "vertex";
  TriangleMesh mesh;  // its vertices are the positions
  const Eigen::Matrix3Xd& positions() const { return mesh.vertices(); }
  void SetPositions(const Eigen::Matrix3Xd& x) { mesh.SetVertices(x); }
  int size() const { return mesh.vertex_count(); }
};

// One force on the membrane, per point (marker or vertex).
template <int D>
struct ForceSource {
  std::string name;      // "membrane", "bending", "electric", ...: messages and docs
  PointsOf<D> load;      // in the body's load unit (header comment); D x points
  PointsOf<D> traction;  // the same force per unit length (2D) or area (3D) where the source
                         // publishes it (electric); empty otherwise
};

template <int D>
struct Body {
  using Points = PointsOf<D>;
  BodyShape<D> shape;
  Points initial;  // the scene's initial positions
  Points U;        // the points' velocity this step (interpolated; coupling/retracted_points.h)
  // Where the force is spread and the velocity interpolated when the immersed boundary is
  // retracted (numerics.ib_retraction, set by the spread stage each step); empty: the points.
  Points coupling;
  // The sources, in the order they add up (unique_ptr: stages keep references to them).
  std::vector<std::unique_ptr<ForceSource<D>>> sources;
  Points load;   // SumLoads: the sum of the sources' loads
  Points force;  // what is spread, per point: load dl in 2D, load in 3D (the spread stage)
  std::vector<double> dl;       // 2D: the arc elements the load was spread with; 3D: empty
  double initial_measure = 0;   // enclosed area (2D) or volume (3D) of the initial shape
  double initial_surface = 0;   // 3D: surface area of the initial shape
  double volume_corrected = 0;  // 3D: the volume numerics.volume_correction_every restored / V0
  int tracked_point = 0;        // the material point whose angle is the tank-treading phase

  int size() const { return shape.size(); }
  const Points& positions() const { return shape.positions(); }
  const Points& coupling_points() const {
    return coupling.cols() == size() ? coupling : positions();
  }

  // A new source at the end of the list (a stage's constructor calls it, in build order).
  ForceSource<D>& AddForceSource(const std::string& name);
  // The source of that name, or nullptr.
  const ForceSource<D>* FindForceSource(const std::string& name) const;
  // Back to `positions`: zero velocity, loads and force; the initial measures from the shape.
  void ResetTo(const Points& positions);
  // load = the sources' loads summed in list order (the one place forces add up).
  void SumLoads();
  // The largest |load| of each source, "membrane 0.001, electric 0.002", for messages.
  std::string DescribeLargestLoads() const;
};

// The controls in effect (the Simulation applies queued changes before a step).
struct StepControls {
  double shear_rate = 0;  // k (lattice units); 0 without shear
  double field = 0;       // |E_inf| (lattice units)
};

// What the stages of one step share: the bodies, the controls and the clock of the step being
// taken. `bodies` is filled before the stages are built and never resized after (the stages keep
// references).
template <int D>
struct StepData {
  std::vector<Body<D>> bodies;
  StepControls controls;
  SimulationState* state = nullptr;  // what the stages report to
  // The step being taken and the time it reaches (set by the step before its stages run).
  long step = 0;
  double time = 0;
  // Called when a stage moved a body's points to new material positions along its membrane (2D
  // drops: markers re-spaced evenly): `resample` maps values at the old points to the new ones,
  // in place. Stages that keep per-point state of their own (the electric warm start) register
  // here at construction.
  using Resample = std::function<void(std::vector<double>&)>;
  std::vector<std::function<void(int body, const Resample& resample)>> on_points_resampled;
};

extern template struct Body<2>;
extern template struct Body<3>;

}  // namespace ehd
