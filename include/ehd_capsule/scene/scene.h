// A scene: one simulation case as data (config/scenes/<name>.yaml).
//
// The physics is given by the dimensionless numbers of song2019 (top-level keys):
//   Ca    = mu k a / E_s (capsule) or mu k a / gamma (drop)          eq. (119), sec. 4.2.2
//   Re    = rho k a^2 / mu                                            sec. 4.1
//   Oh    = mu / sqrt(rho a T), T = gamma or E_s (no shear only)      sec. 4.2.2
//   E_b   = E_B / (a^2 E_s)                                           eq. (120) (see units.h)
//   eta   = mu_s / (a mu)                                             eq. (121)
//   V     = mu_inside / mu_outside                                    sec. 5.4
//   prestress = tau_p / E_s: optional isotropic pre-tension of a capsule membrane,
//           tau = tau_p + E_s (lambda - 1) (not in song2019; 0 by default)
//   Ca_E  = eps+ a E^2 / T                                            sec. 4.2.2 and 5.1
//   sigma_r = sigma- / sigma+, eps_r = eps- / eps+ (inside / outside) sec. 4.2
// plus the resolution (N grid cells across the domain, M markers), the geometry, the membrane
// model, the flow, the electric field and the numerics. The keys are declared by modules
// (scene/scene_keys.h; the table in docs/scene_keys.md is generated from them) and LoadScene reads
// a scene from those declarations alone: an unknown key, a missing key, a wrong type or an
// out-of-range value throws SceneError naming the key, the value and the accepted range. Nothing
// here depends on the solvers; units.h turns a Scene into lattice values.
#pragma once

#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "ehd_capsule/scene/scene_keys.h"

namespace ehd {

struct SceneError : std::invalid_argument {
  using std::invalid_argument::invalid_argument;
};

enum class InitialShape { kCircle, kEllipse, kBiconcave, kSphere };  // kSphere: 3D only
// kDrop: interfacial tension gamma only. kCapsule: Hookean shear elasticity E_s, plus the
// Kelvin-Voigt membrane viscosity when eta > 0 and bending when E_b > 0.
enum class MembraneKind { kDrop, kCapsule };
// kShear: walls at y = +-L move at +-k L (u = (k y, 0)); kNone: closed box, fluid at rest.
enum class FlowKind { kShear, kNone };
enum class MarkerTimeScheme { kForwardEuler, kAdamsBashforth2 };
// 3D capsule membrane laws (song2019 eqs. (137)-(139); membrane/surface_elasticity.h).
enum class SurfaceLawKind { kNeoHookean, kZeroThickness, kSkalak };

const char* ToString(InitialShape shape);
const char* ToString(MembraneKind kind);
const char* ToString(FlowKind kind);
const char* ToString(MarkerTimeScheme scheme);
const char* ToString(SurfaceLawKind law);

struct SceneGeometry {
  InitialShape shape = InitialShape::kCircle;
  double half_width = 4.0;  // L / a: the domain is [-L, L]^2 (3D: the y extent, the walls)
  // 3D: L_x / a = L_z / a, the half box along the flow and the vorticity; 0 (unset) = half_width,
  // a cube. The grid has round(N half_length / half_width) cells along x and z.
  double half_length = 0.0;
  double aspect_ratio = 1.0;  // ellipse: minor / major semi-axis (area pi a^2), x-major
  double center_x = 0.0;      // initial centroid offset in units of a
  double center_y = 0.0;
  double center_z = 0.0;  // 3D only
};

// The applied field's time dependence E(t) = E f(t), E the amplitude from Ca_E (issue #45 item 5):
// kDc f = 1; kAc f = offset + cos(2 pi frequency t + phase); kPulses f = 1 during the first
// pulse_width of each pulse_period (from t = 0), 0 otherwise, for pulse_count pulses (0: no end).
enum class FieldWaveform { kDc, kAc, kPulses };

struct SceneElectric {
  double max_ca_e = 5.0;  // SetCaE accepts [0, max_ca_e]
  FieldWaveform waveform = FieldWaveform::kDc;
  double frequency = 0;  // kAc: cycles per unit of time (1/k with shear, else mu a / T)
  double phase = 0;      // kAc: radians
  double offset = 0;     // kAc: the DC part, in units of the amplitude
  double pulse_width = 0, pulse_period = 0;  // kPulses: in units of time
  int pulse_count = 0;                       // kPulses: 0 for no end
};

struct SceneNumerics {
  double tau = 1.0;  // LBM relaxation time of the outer fluid: nu = (tau - 1/2) / 3
  MarkerTimeScheme integrator = MarkerTimeScheme::kForwardEuler;
  // Time-step refinement n for a stiff membrane (explicit limit): the lattice step is divided by
  // n at fixed h, i.e. nu -> nu / n, k -> k / n, tau -> 1/2 + (tau - 1/2) / n (n times as many
  // steps per unit of time; the dimensionless numbers are unchanged).
  int membrane_substeps = 1;
  int electric_every = 1;              // solve the potential every n steps ...
  double electric_move_tolerance = 0;  // ... or when a marker moved more (cells) since the last
  // 3D: between solves, when the vertices have moved (electric_move_tolerance) but the surface
  // stays within this distance (cells) of the surface of the last solve, the traction field of
  // that solve is re-interpolated at the moved vertices instead of re-solving (tank-treading
  // carries vertices along a steady shape). 0 = off: every such move re-solves.
  double electric_shape_tolerance = 0;
  long max_steps = 1000000;        // hard cap for `ehd_sim run`
  double t_end = 10.0;             // default run length (dimensionless time)
  double area_drift_limit = 0.05;  // watchdog: |A/A0 - 1|
  // Drops only (0 = off): when the largest / smallest marker spacing exceeds this ratio, the
  // markers are re-spaced evenly along the curve (marker 0 stays). A drop's markers are not
  // material (isotropic tension), they drift with the tank-treading flow and bunch, and gaps of
  // several h let the immersed boundary leak (docs/coupling.md).
  double redistribute_markers = 0;  // 2D only
  // 3D drops only (0 = off): every n steps the vertices are relaxed along the surface
  // (geometry/mesh_relaxation.h), the 3D counterpart of redistribute_markers.
  int relax_mesh_every = 0;
  // Every n steps the markers are smoothed by the five-point sawtooth filter
  // (ib/sawtooth_filter.h) that removes the odd-even marker mode the immersed boundary cannot
  // damp; 0 = off. Bias on the shapes: docs/coupling.md ("Long runs").
  int marker_filter_every = 100;
  // 3D: the order p of the mesh-scale filter (ib/mesh_scale_filter.h).
  int mesh_filter_order = 8;
  // 3D: every n steps the vertices are moved by one common distance along their normals so that
  // the enclosed volume is the initial one again (geometry/triangle_mesh.h,
  // RestoreEnclosedVolume): the immersed boundary leaks slowly; 0 = off.
  int volume_correction_every = 0;
  // The immersed boundary's discrete delta: "cosine" (song2019 eq. (103); the default) or
  // "roma3" (Roma, Peskin & Berger 1999; more accurate at large strain in 3D, but not yet stable
  // over long runs: docs/validation_3d.md "The kernel"), "trapezoid3" (3 nodes with the
  // even-odd condition) or "roma3_even_odd" (trapezoid3 along each component's own axis, roma3
  // across: roma3's accuracy without its grid-Nyquist instability, "Damping the grid-Nyquist
  // mode"); ib/delta_kernel.h.
  std::string ib_kernel = "cosine";
  // The immersed boundary's points retracted inward along the normals by this many cells
  // (coupling/retracted_points.h; calibrated per kernel in docs/validation_3d.md); 0 = the points
  // themselves (song2019).
  double ib_retraction = 0.5;
  // With a retraction: 1 = the membrane moves with the velocity extrapolated from the retracted
  // points to its own (the kinematic condition), 0 = with the velocity at the retracted points.
  int ib_extrapolate_velocity = 1;
  double max_mach = 0.1;  // watchdog: max |u| / c_s
  int threads = 0;        // LBM OpenMP threads (0: OpenMP default)
};

struct Scene {
  std::string name;  // file stem, or "inline"
  std::string description;
  std::string source;     // path it came from
  std::string yaml_text;  // YAML text with the overrides applied (for publishing)
  std::vector<std::string> overrides;

  double Ca = 0.0;
  double max_Ca = 10.0;  // SetCa accepts [0, max_Ca] (and below the wall Mach limit)
  double Re = 0.0;
  double Oh = 0.0;
  double E_b = 0.0;
  double eta = 0.0;
  double prestress = 0.0;  // capsule: isotropic pre-tension tau_p / E_s (optional key)
  double V = 1.0;
  double Ca_E = 0.0;
  double sigma_r = 1.0;
  double eps_r = 1.0;
  int N = 0;  // grid cells across the domain (N^2 in 2D, N^3 in 3D)
  int M = 0;  // markers on the membrane (2D)

  // 3D (dimension: 3): a triangulated capsule (geometry/triangle_mesh.h) with a finite-element
  // membrane law; no drop, membrane viscosity, viscosity contrast or field yet.
  int dimension = 2;
  int mesh_subdivisions = 0;  // icosphere level: 10 4^k + 2 vertices
  SurfaceLawKind law = SurfaceLawKind::kNeoHookean;
  double area_dilation = 0.0;  // Skalak C
  double c0 = 0.0;             // spontaneous curvature times a (Helfrich)

  SceneGeometry geometry;
  MembraneKind membrane = MembraneKind::kCapsule;
  FlowKind flow = FlowKind::kShear;
  bool electric_field = false;  // Ca_E > 0 or an explicit `electric:` block
  SceneElectric electric;
  SceneNumerics numerics;
  // Every key read, by path, with its value or default (blocks: present). The scene library's own
  // keys are also in the fields above; a module outside it (a force term) reads its own here.
  std::map<std::string, SceneValue> values;
  // The value of a key that was read (a declared key with a default, or a given one); throws
  // std::logic_error naming the path otherwise.
  double Number(const std::string& path) const;
  bool Has(const std::string& path) const { return values.count(path) > 0; }

  bool has_shear() const { return flow == FlowKind::kShear; }
  bool has_bending() const { return membrane == MembraneKind::kCapsule && E_b > 0.0; }
  bool has_membrane_viscosity() const { return membrane == MembraneKind::kCapsule && eta > 0.0; }
  bool has_viscosity_contrast() const { return V != 1.0; }
};

// Directory of the shipped scenes (the EHD_SCENE_DIR compile definition).
std::string SceneDirectory();
// Names (file stems) of the scenes in SceneDirectory(), sorted.
std::vector<std::string> ListScenes();

// Loads a scene by name (SceneDirectory()/<name>.yaml) or by path (anything containing '/' or
// ending in .yaml), applies "key=value" overrides (nested keys as "geometry.shape=ellipse";
// the value is read as YAML) and validates it. Throws SceneError.
Scene LoadScene(const std::string& name_or_path, const std::vector<std::string>& overrides = {});
// The same from YAML text; `origin` names it in error messages.
Scene ParseScene(const std::string& yaml_text, const std::vector<std::string>& overrides = {},
                 const std::string& origin = "<inline>");

// One line per dimensionless number and setting, for printing at start.
std::string DescribeScene(const Scene& scene);

}  // namespace ehd
