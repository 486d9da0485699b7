// The coupled EHD step, song2019 sec. 3.6 (see simulation.h for the outline).
//
// Departures from the text: the markers may also be advanced by second-order Adams-Bashforth
// (numerics.integrator); the potential may be re-solved less often than every step
// (numerics.electric_every / electric_move_tolerance), reusing F_E at the (material) markers in
// between.
#include "ehd_capsule/coupling/simulation.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <sstream>

#include "ehd_capsule/diagnostics/shape_diagnostics.h"
#include "ehd_capsule/electric/leaky_dielectric_solver.h"
#include "ehd_capsule/geometry/initial_shapes.h"
#include "ehd_capsule/ib/immersed_boundary.h"
#include "ehd_capsule/ib/marker_update.h"
#include "ehd_capsule/ib/sawtooth_filter.h"
#include "ehd_capsule/ib/viscosity_indicator.h"
#include "ehd_capsule/lbm/lattice_boltzmann_2d.h"
#include "ehd_capsule/membrane/membrane_model.h"

namespace ehd {

struct Simulation::Impl {
  std::unique_ptr<LatticeBoltzmann2D> fluid;
  std::unique_ptr<ImmersedBoundary> ib;
  std::unique_ptr<MembraneModel> membrane;
  std::unique_ptr<LeakyDielectricSolver> electric;  // only with a field
  std::unique_ptr<ViscosityIndicator> viscosity;    // only with V != 1
  // numerics.marker_filter_every; order 8, lower for fewer than 17 markers (it needs 2p + 1).
  std::unique_ptr<SawtoothFilter> sawtooth;

  MembraneParameters membrane_parameters;
  ClosedCurve curve;
  Eigen::Matrix2Xd initial_markers;
  // Markers at the last two membrane force evaluations: replayed on Restore to rebuild the
  // membrane's stretch history (Kelvin-Voigt) bit-for-bit.
  Eigen::Matrix2Xd force_markers_prev1, force_markers_prev2;
  int force_history = 0;
  Eigen::Matrix2Xd X, U, U_previous;  // markers, velocity, previous velocity (AB2)
  bool has_previous_velocity = false;
  Eigen::Matrix2Xd membrane_density, total_density, marker_force;
  Eigen::Matrix2Xd electric_density;  // F_E of the last solve (empty without field)
  Eigen::Matrix2Xd markers_at_last_solve;
  long last_solve_step = -1;
  long redistributions = 0;    // numerics.redistribute_markers events (drops)
  double solved_field = -1.0;  // |E| of the last solve
  std::vector<double> dl;
  std::vector<double> empty;

  double initial_area = 0.0;
  double shear_rate = 0.0;  // k in effect
  double field = 0.0;       // |E| in effect
  double pending_ca = -1.0, pending_ca_e = -1.0;
  double tt_angle = 0.0;        // last raw angle of marker 0 about the centroid
  double viscous_number = 0.0;  // Kelvin-Voigt stability indicator (membrane_stability.h)
};

namespace {

Eigen::Matrix2Xd InitialMarkers(const Scene& s, const LatticeUnits& u) {
  const double a = u.radius;
  const Eigen::Vector2d centre(s.geometry.center_x * a, s.geometry.center_y * a);
  switch (s.geometry.shape) {
    case InitialShape::kCircle:
      return CircleMarkers(s.M, a, centre);
    case InitialShape::kEllipse: {
      // Same area as the circle of radius a: semi-axes a / sqrt(q) (x) and a sqrt(q) (y).
      const double q = s.geometry.aspect_ratio;
      return EllipseMarkers(s.M, a / std::sqrt(q), a * std::sqrt(q), centre);
    }
    case InitialShape::kBiconcave: {
      BiconcaveParameters p;
      p.radius = a;
      return BiconcaveMarkers(s.M, p, centre);
    }
  }
  return {};
}

std::string Fmt(double v) {
  std::ostringstream o;
  o << v;
  return o.str();
}

}  // namespace

Simulation::Simulation(const Scene& scene) : scene_(scene), units_(DeriveLatticeUnits(scene)) {
  impl_ = std::make_unique<Impl>();
  Impl& m = *impl_;
  LbmParameters p;
  p.nx = p.ny = scene_.N;
  p.viscosity = units_.viscosity;
  p.threads = scene_.numerics.threads;
  p.boundary = scene_.has_shear() ? FluidBoundary::kShearWalls : FluidBoundary::kClosedBox;
  m.fluid = std::make_unique<LatticeBoltzmann2D>(p);
  grid_ = m.fluid->grid();
  m.ib = std::make_unique<ImmersedBoundary>(grid_, scene_.has_shear(), false);

  m.initial_markers = InitialMarkers(scene_, units_);
  m.sawtooth = std::make_unique<SawtoothFilter>(
      std::clamp((static_cast<int>(m.initial_markers.cols()) - 1) / 2, 1, 8));
  const ClosedCurve reference(m.initial_markers);
  MembraneParameters& mp = m.membrane_parameters;
  if (scene_.membrane == MembraneKind::kDrop) {
    mp.tension = units_.tension;
  } else {
    mp.shear_modulus = units_.tension;
    mp.tension = scene_.prestress * units_.tension;  // tau = tau_p + E_s (lambda - 1)
    mp.membrane_viscosity = units_.membrane_viscosity;
    mp.bending_modulus = units_.bending_modulus;
  }
  m.membrane = std::make_unique<MembraneModel>(mp, reference);  // rebuilt by Reset
  // Explicit membrane limit at the initial shape (membrane_stability.h: the estimate is safe for
  // AB2; forward Euler allows twice the step). The lattice step is 1; numerics.membrane_substeps
  // = n divides the physical step by n (units.h), which multiplies the limit by n.
  const MembraneStabilityLimits limits = m.membrane->Stability(reference, units_.viscosity);
  const double dt_stable =
      limits.min_dt() * (scene_.numerics.integrator == MarkerTimeScheme::kForwardEuler ? 2.0 : 1.0);
  if (dt_stable < 1.0) {
    const int need = static_cast<int>(std::ceil(scene_.numerics.membrane_substeps / dt_stable));
    const char* term = limits.bending_dt == limits.min_dt()   ? "bending (E_b)"
                       : limits.elastic_dt == limits.min_dt() ? "elasticity (Ca)"
                                                              : "tension (Ca)";
    throw SceneError("scene " + scene_.name + ": membrane explicit limit exceeded by the " + term +
                     " term: stable lattice dt " + Fmt(dt_stable) + " < 1 (" +
                     m.membrane->Describe() +
                     "); set numerics.membrane_substeps >= " + std::to_string(need) + " (now " +
                     std::to_string(scene_.numerics.membrane_substeps) + ")");
  }
  m.viscous_number = limits.viscous_number;

  if (scene_.electric_field) {
    m.electric = std::make_unique<LeakyDielectricSolver>(
        grid_, units_.sigma_minus, units_.sigma_plus, units_.eps_minus, units_.eps_plus);
  }
  if (scene_.has_viscosity_contrast()) {
    m.viscosity = std::make_unique<ViscosityIndicator>(grid_, scene_.has_shear(), false,
                                                       units_.viscosity_inner, units_.viscosity);
  }
  Reset();
}

Simulation::~Simulation() = default;

void Simulation::Reset() {
  Impl& m = *impl_;
  m.shear_rate = units_.shear_rate;
  m.field = units_.field;
  m.pending_ca = m.pending_ca_e = -1.0;
  if (scene_.has_shear())
    m.fluid->InitializeShear(m.shear_rate);
  else
    m.fluid->InitializeAtRest();
  m.fluid->ClearForce();
  m.X = m.initial_markers;
  m.curve.Update(m.X);
  m.U.setZero(2, m.X.cols());
  m.U_previous.setZero(2, m.X.cols());
  m.has_previous_velocity = false;
  m.membrane = std::make_unique<MembraneModel>(m.membrane_parameters, ClosedCurve(m.X));
  m.force_history = 0;
  m.membrane_density.setZero(2, m.X.cols());
  m.total_density.setZero(2, m.X.cols());
  m.marker_force.setZero(2, m.X.cols());
  if (m.electric) {
    m.electric_density.setZero(2, m.X.cols());
    m.electric->set_jump_normal_derivative(std::vector<double>(m.X.cols(), 0.0));
  }
  m.last_solve_step = -1;
  m.solved_field = -1.0;
  m.initial_area = m.curve.Area();

  state_ = SimulationState();
  state_.ca = scene_.has_shear() ? scene_.Ca : 0.0;
  state_.ca_e = scene_.electric_field ? scene_.Ca_E : 0.0;
  if (m.electric) state_.electric_force.setZero(2, m.X.cols());
  const ShapeDiagnostics d = MeasureShape(m.curve);
  m.tt_angle = std::atan2(m.X(1, 0) - d.centroid.y(), m.X(0, 0) - d.centroid.x());
  state_.markers = m.X;
  state_.dxy = d.dxy;
  state_.inclination = d.inclination;
  state_.area = d.area;
  state_.tt_phase = m.tt_angle;
  if (m.viscosity) {
    m.viscosity->Update(m.curve);
    m.fluid->SetViscosityField(m.viscosity->viscosity());
  }
}

bool Simulation::has_electric_field() const { return impl_->electric != nullptr; }
bool Simulation::has_bending() const { return scene_.has_bending(); }
bool Simulation::has_viscosity_contrast() const { return impl_->viscosity != nullptr; }
const std::vector<double>& Simulation::ux() const { return impl_->fluid->ux(); }
const std::vector<double>& Simulation::uy() const { return impl_->fluid->uy(); }
const std::vector<double>& Simulation::potential() const {
  return impl_->electric ? impl_->electric->potential() : impl_->empty;
}

void Simulation::SetCaE(double ca_e) {
  const double max = scene_.electric.max_ca_e;
  if (!(ca_e >= 0.0 && ca_e <= max)) {
    throw std::invalid_argument("Ca_E = " + Fmt(ca_e) + " is out of range: accepted [0, " +
                                Fmt(max) + "] (electric.max_Ca_E)");
  }
  if (ca_e > 0.0 && !impl_->electric) {
    throw std::invalid_argument("Ca_E = " + Fmt(ca_e) + " needs the electric field, but scene " +
                                scene_.name +
                                " was built without it (accepted: 0; add an `electric:` block "
                                "or Ca_E > 0 to the scene)");
  }
  impl_->pending_ca_e = ca_e;
}

void Simulation::SetCa(double ca) {
  if (!scene_.has_shear()) {
    throw std::invalid_argument("Ca = " + Fmt(ca) + ": scene " + scene_.name +
                                " has no shear flow (flow: none); accepted: none");
  }
  if (ca == 0.0) {
    // Time is counted in units of 1/k (sum of k dt): with the walls stopped it would stand still
    // while the steps go on.
    throw std::invalid_argument(
        "Ca = 0 would stop the walls and with them the time unit 1/k: "
        "accepted (0, " +
        Fmt(scene_.max_Ca) + "]");
  }
  if (!(ca > 0.0 && ca <= scene_.max_Ca)) {
    throw std::invalid_argument("Ca = " + Fmt(ca) + " is out of range: accepted (0, " +
                                Fmt(scene_.max_Ca) + "] (max_Ca, the scene's measured limit)");
  }
  const double k = ShearRateForCa(units_, ca);
  const double mach = k * units_.half_width / kLatticeSoundSpeed;
  if (mach > scene_.numerics.max_mach) {
    const double ca_max = scene_.numerics.max_mach * kLatticeSoundSpeed / units_.half_width *
                          units_.viscosity * units_.radius / units_.tension;
    throw std::invalid_argument("Ca = " + Fmt(ca) + " gives wall Mach " + Fmt(mach) + " > " +
                                Fmt(scene_.numerics.max_mach) + ": accepted [0, " + Fmt(ca_max) +
                                "]");
  }
  impl_->pending_ca = ca;
}

void Simulation::Step() {
  Impl& m = *impl_;
  const long step = state_.step + 1;
  auto fail = [&](const std::string& what) {
    throw SimulationError("step " + std::to_string(step) + ": " + what);
  };

  // Queued changes (applied before the step, turtlesim-style).
  if (m.pending_ca >= 0.0) {
    m.shear_rate = ShearRateForCa(units_, m.pending_ca);
    m.fluid->SetWallVelocities(-m.shear_rate * units_.half_width, m.shear_rate * units_.half_width);
    state_.ca = m.pending_ca;
    m.pending_ca = -1.0;
  }
  if (m.pending_ca_e >= 0.0) {
    m.field = FieldForCaE(units_, m.pending_ca_e);
    state_.ca_e = m.pending_ca_e;
    m.pending_ca_e = -1.0;
  }

  const int markers = static_cast<int>(m.X.cols());
  MarkerArcElements(m.curve, m.dl);

  // 1. Electric potential and interfacial force.
  state_.gmres_iterations = 0;
  if (m.electric) {
    if (m.field > 0.0) {
      bool solve = m.last_solve_step < 0 || m.solved_field != m.field ||
                   step - m.last_solve_step >= scene_.numerics.electric_every;
      if (!solve && scene_.numerics.electric_move_tolerance > 0.0) {
        // Largest marker displacement since the last solve (no temporary: this runs every step).
        double moved2 = 0.0;
        for (int k = 0; k < markers; ++k) {
          moved2 = std::max(moved2, (m.X.col(k) - m.markers_at_last_solve.col(k)).squaredNorm());
        }
        const double tol = scene_.numerics.electric_move_tolerance;
        solve = moved2 > tol * tol;
      }
      if (solve) {
        m.electric->SetAppliedField(m.field);
        InterfaceSolveReport report;
        try {
          report = m.electric->Solve(m.curve, static_cast<double>(step));
        } catch (const std::exception& e) {
          fail(std::string("electric potential solve failed: ") + e.what());
        }
        state_.gmres_iterations = report.iterations;
        state_.gmres_residual = report.residual;
        if (!report.converged) {
          fail("GMRES did not converge (residual " + Fmt(report.residual) + " after " +
               std::to_string(report.iterations) + " iterations)");
        }
        m.electric_density = m.electric->force();
        m.markers_at_last_solve = m.X;
        m.last_solve_step = step;
        m.solved_field = m.field;
      }
    } else {
      m.electric_density.setZero(2, markers);
      m.solved_field = 0.0;
    }
  }

  // 2. Membrane force density; 3. spread (density x dl).
  m.membrane->ComputeForce(m.curve, 1.0, m.membrane_density);
  m.force_markers_prev2 = m.force_markers_prev1;
  m.force_markers_prev1 = m.X;
  m.force_history = std::min(m.force_history + 1, 2);
  m.total_density = m.membrane_density;
  if (m.electric) m.total_density += m.electric_density;
  for (int k = 0; k < markers; ++k) m.marker_force.col(k) = m.total_density.col(k) * m.dl[k];
  m.fluid->ClearForce();
  m.ib->Spread(m.X, m.marker_force, m.fluid->force_x(), m.fluid->force_y());
  if (m.viscosity) {
    // The fluid's field was last set from this indicator (build, reset, restore), so passing
    // only the band the indicator rewrote keeps them equal at O(band) cost per step.
    m.viscosity->Update(m.curve);
    if (m.viscosity->last_update_was_full()) {
      m.fluid->SetViscosityField(m.viscosity->viscosity());
    } else {
      m.fluid->UpdateViscosityField(m.viscosity->viscosity(), m.viscosity->updated_nodes());
    }
  }

  // 4. Fluid.
  m.fluid->Step();

  // 5. Markers.
  m.ib->Interpolate(m.fluid->ux(), m.fluid->uy(), m.X, m.U);
  if (scene_.numerics.integrator == MarkerTimeScheme::kAdamsBashforth2 && m.has_previous_velocity) {
    m.X += 1.5 * m.U - 0.5 * m.U_previous;
  } else {
    m.X += m.U;
  }
  m.U_previous = m.U;
  m.has_previous_velocity = true;
  if (scene_.numerics.marker_filter_every > 0 && step % scene_.numerics.marker_filter_every == 0) {
    m.sawtooth->Apply(m.X);
  }
  if (scene_.has_shear()) WrapCurveIntoDomain(grid_, m.X);

  // Watchdogs and diagnostics.
  if (!m.X.allFinite()) fail("marker position is not finite (NaN/Inf)");
  double max_speed2 = 0.0;
  const auto& ux = m.fluid->ux();
  const auto& uy = m.fluid->uy();
  for (std::size_t i = 0; i < ux.size(); ++i) {
    const double s2 = ux[i] * ux[i] + uy[i] * uy[i];
    if (!(s2 <= max_speed2)) {
      if (!std::isfinite(s2))
        fail("fluid velocity is not finite (NaN/Inf) at node " + std::to_string(i));
      max_speed2 = s2;
    }
  }
  state_.max_mach = std::sqrt(max_speed2) / kLatticeSoundSpeed;
  if (state_.max_mach > scene_.numerics.max_mach) {
    // Name the force behind the fast flow, so the user knows which number to lower.
    const double membrane_max = m.membrane_density.colwise().norm().maxCoeff();
    std::string forces = "; largest force density: membrane " + Fmt(membrane_max);
    if (m.electric) {
      forces += ", electric " + Fmt(m.electric_density.colwise().norm().maxCoeff()) +
                " (Ca_E = " + Fmt(state_.ca_e) + ")";
    }
    fail("lattice Mach number " + Fmt(state_.max_mach) + " > " + Fmt(scene_.numerics.max_mach) +
         " (numerics.max_mach)" + forces);
  }
  const double margin = 2.0 * grid_.h;
  for (int k = 0; k < markers; ++k) {
    const double y = m.X(1, k);
    if (y < grid_.y0 + margin || y > grid_.y_max() - margin) {
      fail("marker " + std::to_string(k) + " at y = " + Fmt(y) + " is within 2h of the wall y = " +
           Fmt(y < 0 ? grid_.y0 : grid_.y_max()) + " (the membrane left the domain)");
    }
    if (!scene_.has_shear()) {
      const double x = m.X(0, k);
      if (x < grid_.x0 + margin || x > grid_.x_max() - margin) {
        fail("marker " + std::to_string(k) + " at x = " + Fmt(x) +
             " is within 2h of the side wall (the membrane left the domain)");
      }
    }
  }
  try {
    m.curve.Update(m.X);
  } catch (const std::exception& e) {
    fail(std::string("membrane curve is degenerate: ") + e.what());
  }
  if (scene_.numerics.redistribute_markers > 0.0) RedistributeBunchedMarkers();
  const ShapeDiagnostics d = MeasureShape(m.curve);
  state_.area_drift = RelativeAreaDrift(d.area, m.initial_area);
  if (!std::isfinite(d.area) || std::abs(state_.area_drift) > scene_.numerics.area_drift_limit) {
    // The usual cause is a gap between markers through which the immersed boundary leaks:
    // name the spacing, and for a drop the cure (its markers are not material and bunch).
    double smallest = 1e300, largest = 0.0;
    for (int k = 0; k < markers; ++k) {
      const double l = m.curve.SegmentArcLength(k);
      smallest = std::min(smallest, l);
      largest = std::max(largest, l);
    }
    std::string hint = "; marker spacing " + Fmt(smallest) + " .. " + Fmt(largest) + " h";
    if (scene_.membrane == MembraneKind::kDrop && scene_.numerics.redistribute_markers == 0.0) {
      hint +=
          " (a drop's markers drift along its surface and bunch, leaving gaps the flow leaks "
          "through: set numerics.redistribute_markers = 2)";
    } else if (largest > 2.0) {
      hint += " (gaps > 2 h leak: raise M)";
    }
    fail("enclosed area drifted by " + Fmt(100.0 * state_.area_drift) + "% (limit " +
         Fmt(100.0 * scene_.numerics.area_drift_limit) + "%, numerics.area_drift_limit)" + hint);
  }

  state_.step = step;
  state_.time += scene_.has_shear() ? m.shear_rate : units_.dt;
  state_.markers = m.X;
  state_.dxy = d.dxy;
  state_.inclination = d.inclination;
  state_.area = d.area;
  const double angle = std::atan2(m.X(1, 0) - d.centroid.y(), m.X(0, 0) - d.centroid.x());
  double turn = angle - m.tt_angle;
  if (turn > M_PI) turn -= 2.0 * M_PI;
  if (turn < -M_PI) turn += 2.0 * M_PI;
  state_.tt_phase += turn;
  m.tt_angle = angle;
  if (m.electric) {
    state_.electric_force = m.electric_density;
    Eigen::Vector2d total(0, 0);
    for (int k = 0; k < markers; ++k) total += m.electric_density.col(k) * m.dl[k];
    state_.electric_force_total = total;
  }
}

std::string Simulation::Pipeline() const {
  const Impl& m = *impl_;
  std::ostringstream out;
  out << "pipeline (song2019 sec. 3.6):\n";
  if (m.electric) {
    out << "  1. electric: fast IIM leaky dielectric, sigma-/sigma+ = " << scene_.sigma_r
        << ", eps-/eps+ = " << scene_.eps_r << ", E_inf = (0, -" << m.field << "), solved every "
        << scene_.numerics.electric_every << " step(s)";
    if (scene_.numerics.electric_move_tolerance > 0) {
      out << " or after a move > " << scene_.numerics.electric_move_tolerance << " h";
    }
    out << ", F_E = [M_E].n\n";
  } else {
    out << "  1. electric: none (no field: solver not built)\n";
  }
  out << "  2. membrane: " << m.membrane->Describe();
  if (scene_.numerics.membrane_substeps > 1) {
    out << " (time step refined " << scene_.numerics.membrane_substeps << "x)";
  }
  out << '\n';
  if (m.viscous_number >= 0.5) {
    out << "     warning: Kelvin-Voigt stability number " << m.viscous_number
        << " >= 1/2 (explicit membrane viscosity may be unstable; lower eta)\n";
  }
  out << "  3. immersed boundary: cosine delta (eq. 103), spread F dl"
      << (scene_.has_shear() ? ", periodic in x" : "") << '\n';
  if (m.viscosity) {
    out << "     viscosity contrast: smoothed Heaviside (eq. 117), nu_in = "
        << units_.viscosity_inner << ", nu_out = " << units_.viscosity << '\n';
  }
  out << "  4. fluid: D2Q9 MRT LBM " << scene_.N << "x" << scene_.N << ", tau = " << units_.tau
      << ", " << (scene_.has_shear() ? "moving shear walls" : "closed box at rest") << '\n';
  out << "  5. markers: interpolate u, "
      << (scene_.numerics.integrator == MarkerTimeScheme::kAdamsBashforth2 ? "Adams-Bashforth 2"
                                                                           : "forward Euler");
  if (scene_.numerics.redistribute_markers > 0.0) {
    out << ", re-spaced evenly when max/min spacing > " << scene_.numerics.redistribute_markers;
  }
  if (scene_.numerics.marker_filter_every > 0) {
    out << ", sawtooth filter (order " << m.sawtooth->order() << ") every "
        << scene_.numerics.marker_filter_every << " steps";
  }
  out << '\n';
  return out.str();
}

// ---------------------------------------------------------------------------------------------
// Checkpoint: "EHDCKPT" + version + scene text + raw arrays (little-endian doubles as stored).
namespace {

constexpr char kCheckpointMagic[8] = {'E', 'H', 'D', 'C', 'K', 'P', 'T', '\0'};
constexpr std::int32_t kCheckpointVersion = 2;  // 2: electric warm-start history

class Writer {
 public:
  explicit Writer(const std::string& path) : out_(path, std::ios::binary) {
    if (!out_) throw std::runtime_error("checkpoint: cannot write " + path);
  }
  template <typename T>
  void Pod(const T& v) {
    out_.write(reinterpret_cast<const char*>(&v), sizeof(T));
  }
  void Doubles(const double* p, std::size_t n) {
    Pod<std::uint64_t>(n);
    out_.write(reinterpret_cast<const char*>(p), static_cast<std::streamsize>(n * sizeof(double)));
  }
  void Vec(const std::vector<double>& v) { Doubles(v.data(), v.size()); }
  void Mat(const Eigen::Matrix2Xd& m) { Doubles(m.data(), static_cast<std::size_t>(m.size())); }
  void Text(const std::string& s) {
    Pod<std::uint64_t>(s.size());
    out_.write(s.data(), static_cast<std::streamsize>(s.size()));
  }
  void Finish(const std::string& path) {
    out_.flush();
    if (!out_) throw std::runtime_error("checkpoint: write to " + path + " failed");
  }

 private:
  std::ofstream out_;
};

class Reader {
 public:
  explicit Reader(const std::string& path) : in_(path, std::ios::binary), path_(path) {
    if (!in_) throw std::runtime_error("checkpoint: cannot read " + path);
  }
  template <typename T>
  T Pod() {
    T v{};
    in_.read(reinterpret_cast<char*>(&v), sizeof(T));
    Check();
    return v;
  }
  std::vector<double> Vec() {
    const auto n = Pod<std::uint64_t>();
    if (n > (1ull << 34)) throw std::runtime_error("checkpoint " + path_ + ": corrupt size");
    std::vector<double> v(n);
    in_.read(reinterpret_cast<char*>(v.data()), static_cast<std::streamsize>(n * sizeof(double)));
    Check();
    return v;
  }
  Eigen::Matrix2Xd Mat() {
    const std::vector<double> v = Vec();
    Eigen::Matrix2Xd m(2, static_cast<Eigen::Index>(v.size() / 2));
    if (!v.empty()) std::memcpy(m.data(), v.data(), v.size() * sizeof(double));
    return m;
  }
  std::string Text() {
    const auto n = Pod<std::uint64_t>();
    if (n > (1ull << 30)) throw std::runtime_error("checkpoint " + path_ + ": corrupt size");
    std::string s(n, '\0');
    in_.read(s.data(), static_cast<std::streamsize>(n));
    Check();
    return s;
  }

 private:
  void Check() {
    if (!in_) throw std::runtime_error("checkpoint " + path_ + ": truncated file");
  }
  std::ifstream in_;
  std::string path_;
};

}  // namespace

long Simulation::marker_redistributions() const { return impl_->redistributions; }

void Simulation::RedistributeBunchedMarkers() {
  // Drops (numerics.redistribute_markers = r): when the largest / smallest segment exceeds r,
  // re-space the markers evenly in the curve's (chord-length) parameter from marker 0, which stays
  // where it is (it carries tt_phase). The AB2 velocity history and the electric warm start G are
  // carried over by the curve's periodic spline; the potential is re-solved at the next step.
  Impl& m = *impl_;
  const int n = static_cast<int>(m.X.cols());
  double shortest = m.curve.SegmentArcLength(0), longest = shortest;
  for (int k = 1; k < n; ++k) {
    const double l = m.curve.SegmentArcLength(k);
    shortest = std::min(shortest, l);
    longest = std::max(longest, l);
  }
  if (!(longest > scene_.numerics.redistribute_markers * shortest)) return;
  const double s0 = m.curve.knot(0), period = m.curve.period();
  auto new_parameter = [&](int k) { return s0 + period * k / n; };
  std::vector<double> values(n);
  auto resample = [&](std::vector<double>& v) {
    const PeriodicCubicSpline f = m.curve.FitScalar(v);
    for (int k = 0; k < n; ++k) v[k] = f.Value(new_parameter(k));
  };
  if (m.has_previous_velocity) {
    for (int c = 0; c < 2; ++c) {
      for (int k = 0; k < n; ++k) values[k] = m.U_previous(c, k);
      resample(values);
      for (int k = 0; k < n; ++k) m.U_previous(c, k) = values[k];
    }
  }
  if (m.electric) {
    values = m.electric->jump_normal_derivative();
    if (static_cast<int>(values.size()) == n) {
      resample(values);
      m.electric->set_jump_normal_derivative(values);
    }
    m.last_solve_step = -1;  // F_E at the old markers no longer applies
  }
  Eigen::Matrix2Xd x(2, n);
  x.col(0) = m.X.col(0);
  for (int k = 1; k < n; ++k) x.col(k) = m.curve.At(new_parameter(k)).position;
  m.X = x;
  m.curve.Update(m.X);
  ++m.redistributions;
}

void Simulation::Save(const std::string& path) const {
  const Impl& m = *impl_;
  Writer w(path);
  for (char c : kCheckpointMagic) w.Pod(c);
  w.Pod(kCheckpointVersion);
  w.Text(scene_.yaml_text);
  // State.
  w.Pod(state_.step);
  w.Pod(state_.time);
  w.Pod(state_.ca);
  w.Pod(state_.ca_e);
  w.Pod(state_.tt_phase);
  w.Pod(state_.gmres_iterations);
  w.Pod(state_.gmres_residual);
  w.Pod(m.tt_angle);
  w.Pod(m.shear_rate);
  w.Pod(m.field);
  w.Pod(m.pending_ca);
  w.Pod(m.pending_ca_e);
  // Markers and integrator.
  w.Mat(m.X);
  w.Mat(m.U_previous);
  w.Pod(static_cast<std::int32_t>(m.has_previous_velocity));
  // Fluid.
  w.Pod(m.fluid->step());
  w.Vec(m.fluid->populations());
  w.Vec(m.fluid->force_x());
  w.Vec(m.fluid->force_y());
  // Membrane history (Kelvin-Voigt): the markers of the last two force evaluations.
  w.Pod(static_cast<std::int32_t>(m.force_history));
  w.Mat(m.force_markers_prev1);
  w.Mat(m.force_markers_prev2);
  // Electric.
  w.Pod(static_cast<std::int32_t>(m.electric != nullptr));
  if (m.electric) {
    const LeakyDielectricSolver::WarmStartHistory& h = m.electric->warm_start_history();
    w.Pod(m.electric->applied_field());
    w.Vec(m.electric->jump_normal_derivative());
    w.Vec(h.g_previous);
    w.Pod(h.time_previous);
    w.Pod(h.time_last);
    w.Mat(m.electric_density);
    w.Mat(m.markers_at_last_solve);
    w.Pod(m.last_solve_step);
    w.Pod(m.solved_field);
  }
  w.Finish(path);
}

void Simulation::Restore(const std::string& path) {
  Impl& m = *impl_;
  Reader r(path);
  char magic[8];
  for (char& c : magic) c = r.Pod<char>();
  if (std::memcmp(magic, kCheckpointMagic, 8) != 0) {
    throw std::runtime_error("checkpoint " + path + ": not an ehd_capsule checkpoint");
  }
  const auto version = r.Pod<std::int32_t>();
  if (version != kCheckpointVersion) {
    throw std::runtime_error("checkpoint " + path + ": version " + std::to_string(version) +
                             ", this build reads version " + std::to_string(kCheckpointVersion));
  }
  const std::string text = r.Text();
  if (text != scene_.yaml_text) {
    throw std::runtime_error("checkpoint " + path +
                             " was written for a different scene (or overrides):\n" + text);
  }
  SimulationState s;
  s.step = r.Pod<long>();
  s.time = r.Pod<double>();
  s.ca = r.Pod<double>();
  s.ca_e = r.Pod<double>();
  s.tt_phase = r.Pod<double>();
  s.gmres_iterations = r.Pod<int>();
  s.gmres_residual = r.Pod<double>();
  m.tt_angle = r.Pod<double>();
  m.shear_rate = r.Pod<double>();
  m.field = r.Pod<double>();
  m.pending_ca = r.Pod<double>();
  m.pending_ca_e = r.Pod<double>();
  m.X = r.Mat();
  m.U_previous = r.Mat();
  m.has_previous_velocity = r.Pod<std::int32_t>() != 0;
  if (m.X.cols() != m.initial_markers.cols()) {
    throw std::runtime_error("checkpoint " + path + ": marker count differs");
  }
  const long fluid_step = r.Pod<long>();
  const std::vector<double> f = r.Vec();
  m.fluid->force_x() = r.Vec();
  m.fluid->force_y() = r.Vec();
  m.fluid->SetPopulations(f);
  m.fluid->SetStep(fluid_step);
  if (scene_.has_shear()) {
    m.fluid->SetWallVelocities(-m.shear_rate * units_.half_width, m.shear_rate * units_.half_width);
  }
  m.force_history = r.Pod<std::int32_t>();
  m.force_markers_prev1 = r.Mat();
  m.force_markers_prev2 = r.Mat();
  {
    // Replay the force evaluations on a fresh model to rebuild its stretch history.
    m.membrane =
        std::make_unique<MembraneModel>(m.membrane_parameters, ClosedCurve(m.initial_markers));
    Eigen::Matrix2Xd scratch;
    if (m.force_history >= 2)
      m.membrane->ComputeForce(ClosedCurve(m.force_markers_prev2), 1.0, scratch);
    if (m.force_history >= 1)
      m.membrane->ComputeForce(ClosedCurve(m.force_markers_prev1), 1.0, scratch);
  }
  const bool electric = r.Pod<std::int32_t>() != 0;
  if (electric != (m.electric != nullptr)) {
    throw std::runtime_error("checkpoint " + path + ": electric field presence differs");
  }
  if (m.electric) {
    m.electric->SetAppliedField(r.Pod<double>());
    m.electric->set_jump_normal_derivative(r.Vec());
    LeakyDielectricSolver::WarmStartHistory h;
    h.g_previous = r.Vec();
    h.time_previous = r.Pod<double>();
    h.time_last = r.Pod<double>();
    m.electric->set_warm_start_history(h);
    m.electric_density = r.Mat();
    m.markers_at_last_solve = r.Mat();
    m.last_solve_step = r.Pod<long>();
    m.solved_field = r.Pod<double>();
  }
  m.curve.Update(m.X);
  if (m.viscosity) {
    m.viscosity->Update(m.curve);
    m.fluid->SetViscosityField(m.viscosity->viscosity());
  }
  MarkerArcElements(m.curve, m.dl);
  const ShapeDiagnostics d = MeasureShape(m.curve);
  s.markers = m.X;
  s.dxy = d.dxy;
  s.inclination = d.inclination;
  s.area = d.area;
  s.area_drift = RelativeAreaDrift(d.area, m.initial_area);
  double max_speed2 = 0.0;
  for (std::size_t i = 0; i < m.fluid->ux().size(); ++i) {
    max_speed2 = std::max(
        max_speed2, m.fluid->ux()[i] * m.fluid->ux()[i] + m.fluid->uy()[i] * m.fluid->uy()[i]);
  }
  s.max_mach = std::sqrt(max_speed2) / kLatticeSoundSpeed;
  if (m.electric) {
    s.electric_force = m.electric_density;
    Eigen::Vector2d total(0, 0);
    for (int k = 0; k < m.X.cols(); ++k) total += m.electric_density.col(k) * m.dl[k];
    s.electric_force_total = total;
  }
  state_ = s;
}

}  // namespace ehd
