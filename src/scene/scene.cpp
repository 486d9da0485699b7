// Scene files: parsing, overrides and validation (see scene.h for the keys and their meaning).
#include "ehd_capsule/scene/scene.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <set>
#include <sstream>

namespace ehd {
namespace {

std::string FormatNumber(double v) {
  std::ostringstream out;
  out << v;
  return out.str();
}

// An interval of accepted values, printed as "(0, 10]".
struct Range {
  double lo;
  double hi;
  bool lo_open = false;
  bool hi_open = false;
  bool Contains(double v) const {
    return (lo_open ? v > lo : v >= lo) && (hi_open ? v < hi : v <= hi);
  }
  std::string Text() const {
    return std::string(lo_open ? "(" : "[") + FormatNumber(lo) + ", " + FormatNumber(hi) +
           (hi_open ? ")" : "]");
  }
};
Range Closed(double lo, double hi) { return {lo, hi, false, false}; }
Range LeftOpen(double lo, double hi) { return {lo, hi, true, false}; }

std::string ScalarText(const YAML::Node& node) {
  if (node.IsScalar()) return "'" + node.Scalar() + "'";
  if (node.IsMap()) return "a block (map)";
  if (node.IsSequence()) return "a list";
  return "nothing";
}

// Reads the keys of one YAML block; remembers which keys it knows so that the rest are reported
// as unknown.
class BlockReader {
 public:
  BlockReader(const YAML::Node& node, std::string prefix, std::string origin)
      : node_(node), prefix_(std::move(prefix)), origin_(std::move(origin)) {
    if (node_ && !node_.IsNull() && !node_.IsMap()) {
      Fail(prefix_.empty() ? "the scene" : "'" + prefix_ + "'",
           "must be a block of 'key: value' lines, got " + ScalarText(node_));
    }
  }

  // A YAML scalar that reads as a number; false for blocks, lists and text.
  static bool ScalarAsDouble(const YAML::Node& v, double* x) {
    if (!v.IsScalar()) return false;
    try {
      *x = v.as<double>();
      return true;
    } catch (const YAML::Exception&) {
      return false;
    }
  }

  bool Has(const std::string& key) {
    known_.insert(key);
    return node_ && node_.IsMap() && node_[key].IsDefined() && !node_[key].IsNull();
  }
  bool Present(const std::string& key) {  // defined, possibly as an empty block
    known_.insert(key);
    return node_ && node_.IsMap() && node_[key].IsDefined();
  }
  YAML::Node Child(const std::string& key) {
    known_.insert(key);
    return node_ && node_.IsMap() ? node_[key] : YAML::Node();
  }

  double Number(const std::string& key, const Range& range, std::optional<double> fallback,
                const std::string& meaning) {
    if (!Has(key)) return Missing(key, fallback, meaning + ", a number in " + range.Text());
    const YAML::Node v = node_[key];
    double x = 0.0;
    const bool ok = ScalarAsDouble(v, &x);
    if (!ok || !std::isfinite(x)) {
      Fail(Name(key),
           "expected a number in " + range.Text() + " (" + meaning + "), got " + ScalarText(v));
    }
    if (!range.Contains(x)) {
      Fail(Name(key),
           "= " + v.Scalar() + " is out of range: accepted " + range.Text() + " (" + meaning + ")");
    }
    return x;
  }

  long Integer(const std::string& key, long lo, long hi, std::optional<long> fallback,
               const std::string& meaning) {
    const std::string range = "[" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
    if (!Has(key)) {
      return static_cast<long>(Missing(key,
                                       fallback ? std::optional<double>(*fallback) : std::nullopt,
                                       meaning + ", an integer in " + range));
    }
    const YAML::Node v = node_[key];
    double x = 0.0;
    const bool ok = ScalarAsDouble(v, &x);
    if (!ok || !std::isfinite(x) || x != std::floor(x)) {
      Fail(Name(key),
           "expected an integer in " + range + " (" + meaning + "), got " + ScalarText(v));
    }
    if (x < lo || x > hi) {
      Fail(Name(key),
           "= " + v.Scalar() + " is out of range: accepted " + range + " (" + meaning + ")");
    }
    return static_cast<long>(x);
  }

  std::string Choice(const std::string& key, const std::vector<std::string>& choices,
                     std::optional<std::string> fallback, const std::string& meaning) {
    std::string list;
    for (const auto& c : choices) list += (list.empty() ? "" : " | ") + c;
    if (!Has(key)) {
      if (fallback) return *fallback;
      Fail(Name(key), "missing (" + meaning + ": one of " + list + ")");
    }
    const YAML::Node v = node_[key];
    if (!v.IsScalar() || std::find(choices.begin(), choices.end(), v.Scalar()) == choices.end()) {
      Fail(Name(key), "expected one of " + list + " (" + meaning + "), got " + ScalarText(v));
    }
    return v.Scalar();
  }

  std::string Text(const std::string& key, const std::string& fallback) {
    if (!Has(key)) return fallback;
    const YAML::Node v = node_[key];
    if (!v.IsScalar()) Fail(Name(key), "expected text, got " + ScalarText(v));
    return v.Scalar();
  }

  // A key that must not be given in this configuration.
  void Forbid(const std::string& key, const std::string& why) {
    if (Has(key)) Fail(Name(key), "= " + ScalarText(node_[key]) + " is not accepted here: " + why);
  }

  void RejectUnknown() const {
    if (!node_ || !node_.IsMap()) return;
    for (const auto& entry : node_) {
      const std::string key = entry.first.as<std::string>();
      if (known_.count(key)) continue;
      std::string list;
      for (const auto& k : known_) list += (list.empty() ? "" : ", ") + k;
      Fail("'" + (prefix_.empty() ? key : prefix_ + "." + key) + "'",
           "unknown key (value " + ScalarText(entry.second) + "); accepted keys" +
               (prefix_.empty() ? "" : " in '" + prefix_ + "'") + ": " + list);
    }
  }

  [[noreturn]] void Fail(const std::string& what, const std::string& message) const {
    throw SceneError("scene " + origin_ + ": " + what + " " + message);
  }

 private:
  std::string Name(const std::string& key) const {
    return "'" + (prefix_.empty() ? key : prefix_ + "." + key) + "'";
  }
  double Missing(const std::string& key, std::optional<double> fallback,
                 const std::string& meaning) {
    if (fallback) return *fallback;
    Fail(Name(key), "missing (" + meaning + ")");
  }

  YAML::Node node_;
  std::string prefix_;
  std::string origin_;
  std::set<std::string> known_;
};

std::vector<std::string> SplitPath(const std::string& key) {
  std::vector<std::string> parts;
  std::string part;
  std::istringstream in(key);
  while (std::getline(in, part, '.')) parts.push_back(part);
  return parts;
}

void SetPath(YAML::Node node, const std::vector<std::string>& path, std::size_t i,
             const YAML::Node& value, const std::string& override_text) {
  if (i + 1 == path.size()) {
    // An empty value ("electric=") removes the key; a YAML null would still count as present
    // for blocks such as `electric:`.
    if (value.IsNull()) {
      node.remove(path[i]);
    } else {
      node[path[i]] = value;
    }
    return;
  }
  YAML::Node child = node[path[i]];
  if (child.IsDefined() && !child.IsNull() && !child.IsMap()) {
    throw SceneError("override '" + override_text + "': '" + path[i] + "' is not a block");
  }
  if (!child.IsDefined() || child.IsNull()) {
    node[path[i]] = YAML::Node(YAML::NodeType::Map);
    child = node[path[i]];
  }
  SetPath(child, path, i + 1, value, override_text);
}

void ApplyOverride(YAML::Node& root, const std::string& text) {
  const std::size_t eq = text.find('=');
  if (eq == std::string::npos || eq == 0) {
    throw SceneError("override '" + text + "': expected key=value (e.g. Ca=0.05)");
  }
  const std::string key = text.substr(0, eq);
  const std::string value_text = text.substr(eq + 1);
  const std::vector<std::string> path = SplitPath(key);
  for (const auto& p : path) {
    if (p.empty()) throw SceneError("override '" + text + "': empty key part in '" + key + "'");
  }
  YAML::Node value;
  try {
    value = YAML::Load(value_text);
  } catch (const YAML::Exception& e) {
    throw SceneError("override '" + text + "': value is not valid YAML: " + e.what());
  }
  SetPath(root, path, 0, value, text);
}

Scene Validate(const YAML::Node& root, const std::string& origin) {
  Scene s;
  BlockReader top(root, "", origin);
  s.description = top.Text("description", "");
  if (top.Has("name")) s.name = top.Text("name", "");

  s.dimension = static_cast<int>(top.Integer("dimension", 2, 3, 2, "spatial dimension"));
  const bool three_d = s.dimension == 3;
  s.N = static_cast<int>(top.Integer(
      "N", 16, three_d ? 512 : 4096, std::nullopt,
      three_d ? "grid cells along each axis (N^3 nodes)" : "grid cells across the domain"));
  if (three_d) {
    top.Forbid("M", "a 3D membrane is a triangulated surface: set mesh_subdivisions instead");
    s.mesh_subdivisions = static_cast<int>(top.Integer(
        "mesh_subdivisions", 1, 6, std::nullopt,
        "icosphere subdivisions of the membrane mesh: 3 = 642, 4 = 2562, 5 = 10242 vertices"));
    s.M = 10 * (1 << (2 * s.mesh_subdivisions)) + 2;
  } else {
    top.Forbid("mesh_subdivisions", "only dimension: 3 has a triangulated membrane (2D: M)");
    s.M = static_cast<int>(top.Integer("M", 8, 100000, std::nullopt, "markers on the membrane"));
  }

  // Geometry.
  {
    BlockReader g(top.Child("geometry"), "geometry", origin);
    if (!top.Has("geometry")) top.Fail("'geometry'", "missing (block with shape, half_width)");
    const std::string shape =
        three_d
            ? g.Choice("shape", {"sphere", "biconcave"}, std::nullopt, "initial 3D shape")
            : g.Choice("shape", {"circle", "ellipse", "biconcave"}, std::nullopt, "initial shape");
    s.geometry.shape = shape == "circle"    ? InitialShape::kCircle
                       : shape == "ellipse" ? InitialShape::kEllipse
                       : shape == "sphere"  ? InitialShape::kSphere
                                            : InitialShape::kBiconcave;
    s.geometry.half_width = g.Number("half_width", LeftOpen(1.0, 1000.0), std::nullopt,
                                     three_d ? "half the box edge L in units of the radius a"
                                             : "domain half-width L in units of the radius a");
    if (three_d) {
      s.geometry.half_length =
          g.Number("half_length", LeftOpen(1.0, 1000.0), s.geometry.half_width,
                   "half the box's x and z edges in units of a (default half_width: a cube)");
    } else {
      g.Forbid("half_length", "a 2D scene's box is [-L, L]^2 (half_width)");
    }
    if (s.geometry.shape == InitialShape::kEllipse) {
      s.geometry.aspect_ratio = g.Number("aspect_ratio", LeftOpen(0.0, 1.0), std::nullopt,
                                         "minor/major semi-axis of the initial ellipse");
    } else {
      g.Forbid("aspect_ratio", "only shape: ellipse has an aspect ratio");
    }
    s.geometry.center_x = g.Number("center_x", Closed(-1000, 1000), 0.0, "x offset / a");
    s.geometry.center_y = g.Number("center_y", Closed(-1000, 1000), 0.0, "y offset / a");
    if (three_d) {
      s.geometry.center_z = g.Number("center_z", Closed(-1000, 1000), 0.0, "z offset / a");
    } else {
      g.Forbid("center_z", "a 2D scene has no z axis");
    }
    g.RejectUnknown();
  }

  const std::string membrane =
      top.Choice("membrane", {"capsule", "drop"}, std::nullopt,
                 "membrane model: capsule (Hookean + Kelvin-Voigt + bending) or drop (tension)");
  s.membrane = membrane == "drop" ? MembraneKind::kDrop : MembraneKind::kCapsule;
  const std::string flow =
      top.Choice("flow", {"shear", "none"}, std::nullopt, "imposed flow: shear walls or none");
  s.flow = flow == "none" ? FlowKind::kNone : FlowKind::kShear;

  const std::string tension = s.membrane == MembraneKind::kDrop ? "gamma" : three_d ? "G_s" : "E_s";
  if (s.has_shear()) {
    s.Ca =
        top.Number("Ca", LeftOpen(0.0, 10.0), std::nullopt, "capillary number mu k a / " + tension);
    s.Re = top.Number("Re", LeftOpen(0.0, 100.0), std::nullopt, "Reynolds number rho k a^2 / mu");
    s.max_Ca = top.Number("max_Ca", LeftOpen(0.0, 10.0), 10.0,
                          "largest Ca accepted at run time (the scene's measured limit)");
    if (s.Ca > s.max_Ca) {
      top.Fail("'Ca'", "= " + FormatNumber(s.Ca) + " is out of range: accepted (0, " +
                           FormatNumber(s.max_Ca) + "] (max_Ca)");
    }
    top.Forbid("Oh", "Oh sets the time scale only without shear (flow: none); use Ca and Re");
  } else {
    s.Oh = top.Number("Oh", LeftOpen(0.0, 100.0), std::nullopt,
                      "Ohnesorge number mu / sqrt(rho a " + tension + ")");
    top.Forbid("Ca", "there is no shear rate with flow: none (use Oh)");
    top.Forbid("max_Ca", "there is no shear rate with flow: none");
    top.Forbid("Re", "there is no shear rate with flow: none (use Oh)");
  }
  if (three_d && s.membrane == MembraneKind::kDrop) {
    for (const char* key : {"law", "C", "c0"}) {
      top.Forbid(key, "a drop has a surface tension only (law, C and c0 are capsule keys)");
    }
  } else if (three_d) {
    const std::string law = top.Choice("law", {"neo_hookean", "zero_thickness", "skalak"},
                                       std::nullopt, "3D membrane law (song2019 eqs. 137-139)");
    s.law = law == "skalak"           ? SurfaceLawKind::kSkalak
            : law == "zero_thickness" ? SurfaceLawKind::kZeroThickness
                                      : SurfaceLawKind::kNeoHookean;
    if (s.law == SurfaceLawKind::kSkalak) {
      s.area_dilation = top.Number("C", LeftOpen(0.0, 1e6), std::nullopt,
                                   "Skalak area-dilation to shear modulus ratio");
    } else {
      top.Forbid("C", "only law: skalak has an area-dilation modulus");
    }
    s.c0 = top.Number("c0", Closed(-100.0, 100.0), 0.0,
                      "spontaneous curvature times a (Helfrich bending)");
    for (const char* key : {"eta", "prestress"}) {
      if (top.Has(key)) {
        const double v = top.Number(key, Closed(0.0, 0.0), 0.0,
                                    "membrane viscosity and prestress are not built in 3D yet");
        (void)v;
      }
    }
  } else {
    for (const char* key : {"law", "C", "c0"}) {
      top.Forbid(key,
                 "2D capsules have their own law (Hookean fibre, E_b, eta); law, C and c0 "
                 "are for dimension: 3");
    }
  }
  const std::string modulus = three_d ? "G_s" : "E_s";
  if (s.membrane == MembraneKind::kCapsule) {
    s.E_b = top.Number("E_b", Closed(0.0, 10.0), std::nullopt,
                       "bending modulus E_B / (a^2 " + modulus + ")");
    if (!three_d) {
      s.eta = top.Number("eta", Closed(0.0, 100.0), std::nullopt,
                         "membrane viscosity ratio mu_s / (a mu)");
      s.prestress = top.Number("prestress", Closed(0.0, 10.0), 0.0,
                               "isotropic membrane pre-tension tau_p / E_s");
    }
  } else {
    for (const char* key : {"E_b", "eta", "prestress"}) {
      if (top.Has(key)) {
        const double v = top.Number(key, Closed(0.0, 0.0), 0.0,
                                    "a drop has no bending, membrane viscosity or prestress; needs "
                                    "membrane: capsule");
        (void)v;
      }
    }
  }
  s.V =
      top.Number("V", Closed(0.01, 100.0), std::nullopt, "viscosity ratio mu_inside / mu_outside");
  if (three_d && s.V != 1.0) {
    top.Fail("'V'", "= " + FormatNumber(s.V) +
                        ": a viscosity contrast is not built in 3D yet (dimension: 3 accepts 1)");
  }

  // Electric field: present iff Ca_E > 0 or an explicit `electric:` block. With the block, Ca_E
  // is required (0 builds the field to be turned up live): a field scene whose Ca_E was deleted
  // must not run silently without its field.
  const bool electric_block = top.Present("electric");
  s.Ca_E = top.Number("Ca_E", Closed(0.0, 100.0),
                      electric_block ? std::nullopt : std::optional<double>(0.0),
                      "electric capillary number eps+ a E^2 / " + tension +
                          (electric_block ? " (required with an electric: block; 0 starts the "
                                            "field off, to be turned up live)"
                                          : ""));
  s.electric_field = s.Ca_E > 0.0 || electric_block;
  {
    BlockReader e(top.Child("electric"), "electric", origin);
    s.electric.max_ca_e =
        e.Number("max_Ca_E", LeftOpen(0.0, 100.0), 5.0, "largest Ca_E accepted at run time");
    e.RejectUnknown();
  }
  if (s.electric_field) {
    s.sigma_r = top.Number("sigma_r", Closed(1e-4, 1e4), std::nullopt,
                           "conductivity ratio sigma- / sigma+ (inside / outside)");
    s.eps_r = top.Number("eps_r", Closed(1e-4, 1e4), std::nullopt,
                         "permittivity ratio eps- / eps+ (inside / outside)");
    // The 3D fast IIM refuses sigma-/sigma+ above its max_inner_ratio (1000: beyond, the flux
    // balance that fixes the near-null mode of a more conducting inside is not shown to hold);
    // say so at load, not at step 1.
    if (three_d && s.sigma_r > 1000.0) {
      top.Fail("'sigma_r'", "= " + FormatNumber(s.sigma_r) +
                                " is out of range in 3D: accepted [1e-4, 1000] (the 3D immersed "
                                "interface solver's max_inner_ratio; docs/electric_solver_3d.md)");
    }
    if (s.Ca_E > s.electric.max_ca_e) {
      top.Fail("'Ca_E'", "= " + FormatNumber(s.Ca_E) + " is out of range: accepted [0, " +
                             FormatNumber(s.electric.max_ca_e) + "] (electric.max_Ca_E)");
    }
  } else {
    // Accepted (so a scene can be switched on with --set Ca_E=...), checked for range.
    s.sigma_r = top.Number("sigma_r", Closed(1e-4, 1e4), 1.0, "conductivity ratio");
    s.eps_r = top.Number("eps_r", Closed(1e-4, 1e4), 1.0, "permittivity ratio");
  }

  {
    BlockReader n(top.Child("numerics"), "numerics", origin);
    s.numerics.tau = n.Number("tau", LeftOpen(0.5, 20.0), 1.0,
                              "LBM relaxation time of the outer fluid, nu = (tau - 1/2)/3");
    // 3D default Adams-Bashforth 2: forward Euler turns a tank-treading vertex outwards by
    // (omega dt)^2 / 2 of its radius per step, which inflated sphere_shear's volume by 7e-5 per
    // time unit (1.4 % by t = 200); AB2 by 2e-5 (docs/validation_3d.md, "Long runs"). 2D keeps
    // forward Euler, with which its tables were made.
    const std::string integrator = n.Choice(
        "integrator", {"forward_euler", "adams_bashforth2"},
        std::string(three_d ? "adams_bashforth2" : "forward_euler"), "marker time integration");
    s.numerics.integrator = integrator == "adams_bashforth2" ? MarkerTimeScheme::kAdamsBashforth2
                                                             : MarkerTimeScheme::kForwardEuler;
    s.numerics.membrane_substeps = static_cast<int>(
        n.Integer("membrane_substeps", 1, 1000, 1, "time-step refinement for a stiff membrane"));
    s.numerics.electric_every = static_cast<int>(
        n.Integer("electric_every", 1, 1000000, 1, "solve the potential every n steps"));
    s.numerics.electric_move_tolerance =
        n.Number("electric_move_tolerance", Closed(0.0, 10.0), 0.0,
                 "re-solve when a marker moved more than this (cells); 0 = off");
    s.numerics.electric_shape_tolerance = n.Number(
        "electric_shape_tolerance", Closed(0.0, 1.0), 0.0,
        "3D: re-interpolate the last solve's traction at moved vertices while the surface stays "
        "within this distance (cells) of that solve's surface; 0 = off");
    if (!three_d && s.numerics.electric_shape_tolerance > 0.0) {
      throw SceneError("scene " + origin + ": numerics.electric_shape_tolerance = " +
                       FormatNumber(s.numerics.electric_shape_tolerance) +
                       " is built in 3D only (accepted in 2D: 0)");
    }
    s.numerics.max_steps = n.Integer("max_steps", 1, 1000000000000L, 1000000, "step cap");
    s.numerics.t_end = n.Number("t_end", LeftOpen(0.0, 1e6), 10.0,
                                "default run length in units of the scene's time scale");
    s.numerics.area_drift_limit =
        n.Number("area_drift_limit", LeftOpen(0.0, 1.0), 0.05, "watchdog on |A/A0 - 1|");
    s.numerics.max_mach = n.Number("max_mach", LeftOpen(0.0, 0.5), 0.1,
                                   "watchdog on the lattice Mach number |u|/c_s");
    s.numerics.threads =
        static_cast<int>(n.Integer("threads", 0, 256, 0, "LBM OpenMP threads, 0 = OpenMP default"));
    s.numerics.redistribute_markers =
        n.Number("redistribute_markers", Closed(0.0, 1e6), 0.0,
                 "drops: re-space the markers evenly when max/min spacing exceeds this; 0 = off");
    s.numerics.marker_filter_every = static_cast<int>(
        n.Integer("marker_filter_every", 0, 1000000000, 100,
                  three_d ? "remove the mesh-scale part of the membrane's deformation every n "
                            "steps (ib/mesh_scale_filter.h); 0 = off"
                          : "smooth the markers' sawtooth mode every n steps; 0 = off"));
    s.numerics.mesh_filter_order = static_cast<int>(
        n.Integer("mesh_filter_order", 1, 32, 8,
                  "3D: order p of the mesh-scale filter's high-pass (A/mu_max)^p; lower removes "
                  "longer modes (ib/mesh_scale_filter.h)"));
    if (!three_d && s.numerics.mesh_filter_order != 8) {
      throw SceneError("scene " + origin +
                       ": numerics.mesh_filter_order is 3D only (2D filters the markers' "
                       "sawtooth mode, ib/sawtooth_filter.h)");
    }
    s.numerics.volume_correction_every = static_cast<int>(
        n.Integer("volume_correction_every", 0, 1000000000, 0,
                  "3D: restore the enclosed volume to its initial value every n steps by a uniform "
                  "normal displacement of the vertices (the immersed boundary's leak); 0 = off"));
    if (!three_d && s.numerics.volume_correction_every > 0) {
      throw SceneError("scene " + origin +
                       ": numerics.volume_correction_every is 3D only (the 2D markers' area "
                       "leak is 1e-5 per unit: docs/validation_3d.md)");
    }
    const bool drop_3d = three_d && s.membrane == MembraneKind::kDrop;
    s.numerics.relax_mesh_every =
        static_cast<int>(n.Integer("relax_mesh_every", 0, 1000000000, drop_3d ? 100 : 0,
                                   "3D drops: relax the vertices along the surface every n steps "
                                   "(geometry/mesh_relaxation.h); 0 = off"));
    if (s.numerics.relax_mesh_every > 0 && !drop_3d) {
      throw SceneError("scene " + origin +
                       ": numerics.relax_mesh_every needs dimension: 3 and membrane: drop (a "
                       "capsule's vertices are material points of its elastic reference; a 2D "
                       "drop uses numerics.redistribute_markers)");
    }
    if (three_d && s.numerics.redistribute_markers != 0.0) {
      throw SceneError("scene " + origin +
                       ": numerics.redistribute_markers is 2D only (a 3D drop's mesh is relaxed "
                       "along its surface every numerics.relax_mesh_every steps)");
    }
    if (s.numerics.redistribute_markers != 0.0 && s.numerics.redistribute_markers <= 1.0) {
      throw SceneError("scene " + origin + ": numerics.redistribute_markers = " +
                       std::to_string(s.numerics.redistribute_markers) +
                       " is out of range: 0 (off) or a spacing ratio > 1");
    }
    if (s.numerics.redistribute_markers > 0.0 && s.membrane != MembraneKind::kDrop) {
      throw SceneError("scene " + origin +
                       ": numerics.redistribute_markers needs membrane: drop (a capsule's "
                       "markers are material points of its elastic reference)");
    }
    n.RejectUnknown();
  }
  top.RejectUnknown();
  return s;
}

}  // namespace

const char* ToString(InitialShape shape) {
  switch (shape) {
    case InitialShape::kCircle:
      return "circle";
    case InitialShape::kEllipse:
      return "ellipse";
    case InitialShape::kBiconcave:
      return "biconcave";
    case InitialShape::kSphere:
      return "sphere";
  }
  return "?";
}
const char* ToString(MembraneKind kind) { return kind == MembraneKind::kDrop ? "drop" : "capsule"; }
const char* ToString(FlowKind kind) { return kind == FlowKind::kShear ? "shear" : "none"; }
const char* ToString(SurfaceLawKind law) {
  switch (law) {
    case SurfaceLawKind::kNeoHookean:
      return "neo_hookean";
    case SurfaceLawKind::kZeroThickness:
      return "zero_thickness";
    case SurfaceLawKind::kSkalak:
      return "skalak";
  }
  return "?";
}
const char* ToString(MarkerTimeScheme scheme) {
  return scheme == MarkerTimeScheme::kAdamsBashforth2 ? "adams_bashforth2" : "forward_euler";
}

std::string SceneDirectory() { return EHD_SCENE_DIR; }

std::vector<std::string> ListScenes() {
  std::vector<std::string> names;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(SceneDirectory(), ec)) {
    if (entry.path().extension() == ".yaml") names.push_back(entry.path().stem().string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

// yaml-cpp keeps both pairs of a repeated key and lookups return the first, so a scene that
// sets a key twice would silently ignore the second value: refuse it, naming both lines.
void RejectDuplicateKeys(const YAML::Node& node, const std::string& prefix,
                         const std::string& origin) {
  if (node.IsSequence()) {
    for (const auto& item : node) RejectDuplicateKeys(item, prefix, origin);
    return;
  }
  if (!node.IsMap()) return;
  std::map<std::string, int> first_line;
  for (auto it = node.begin(); it != node.end(); ++it) {
    const std::string key = it->first.IsScalar() ? it->first.Scalar() : std::string("?");
    const int line = it->first.Mark().line + 1;
    const auto [seen, inserted] = first_line.emplace(key, line);
    if (!inserted) {
      throw SceneError("scene " + origin + ": key '" + prefix + key + "' is given twice (lines " +
                       std::to_string(seen->second) + " and " + std::to_string(line) +
                       "); keep one");
    }
    RejectDuplicateKeys(it->second, prefix + key + ".", origin);
  }
}

Scene ParseScene(const std::string& yaml_text, const std::vector<std::string>& overrides,
                 const std::string& origin) {
  YAML::Node root;
  try {
    root = YAML::Load(yaml_text);
  } catch (const YAML::Exception& e) {
    throw SceneError("scene " + origin + ": not valid YAML: " + e.what());
  }
  if (root.IsNull()) root = YAML::Node(YAML::NodeType::Map);
  if (!root.IsMap()) throw SceneError("scene " + origin + ": expected a block of key: value lines");
  RejectDuplicateKeys(root, "", origin);
  for (const auto& o : overrides) ApplyOverride(root, o);
  Scene scene = Validate(root, origin);
  if (scene.name.empty()) scene.name = "inline";
  scene.source = origin;
  scene.overrides = overrides;
  std::ostringstream text;
  text << "# scene " << scene.name << " (" << origin << ")";
  if (!overrides.empty()) {
    text << ", overrides:";
    for (const auto& o : overrides) text << ' ' << o;
  }
  text << '\n' << YAML::Dump(root) << '\n';
  scene.yaml_text = text.str();
  return scene;
}

Scene LoadScene(const std::string& name_or_path, const std::vector<std::string>& overrides) {
  const bool is_path =
      name_or_path.find('/') != std::string::npos ||
      (name_or_path.size() > 5 && name_or_path.compare(name_or_path.size() - 5, 5, ".yaml") == 0);
  const std::string path = is_path ? name_or_path : SceneDirectory() + "/" + name_or_path + ".yaml";
  std::ifstream in(path);
  if (!in) {
    std::string known;
    for (const auto& n : ListScenes()) known += (known.empty() ? "" : ", ") + n;
    std::string where;
    if (is_path && !path.empty() && path.front() != '/') {
      std::error_code ec;
      where = " (a relative path, resolved from " + std::filesystem::current_path(ec).string() +
              "; roslaunch runs nodes in ROS_HOME: give an absolute path)";
    }
    throw SceneError("scene '" + name_or_path + "': cannot read " + path + where +
                     (is_path ? "" : " (shipped scenes: " + known + ")"));
  }
  std::stringstream buffer;
  buffer << in.rdbuf();
  Scene scene = ParseScene(buffer.str(), overrides, path);
  if (scene.name == "inline") scene.name = std::filesystem::path(path).stem().string();
  return scene;
}

std::string DescribeScene(const Scene& s) {
  std::ostringstream out;
  out << "scene " << s.name << (s.description.empty() ? "" : ": " + s.description) << '\n';
  if (s.dimension == 3) {
    if (s.membrane == MembraneKind::kDrop) {
      out << "  3D: surface tension";
    } else {
      out << "  3D: " << ToString(s.law) << " membrane";
      if (s.law == SurfaceLawKind::kSkalak) out << " (C = " << s.area_dilation << ")";
    }
    out << ", mesh " << s.M << " vertices (subdivision " << s.mesh_subdivisions << ")";
    if (s.c0 != 0.0) out << ", c0 a = " << s.c0;
    out << '\n';
  }
  out << "  membrane " << ToString(s.membrane) << ", shape " << ToString(s.geometry.shape)
      << ", flow " << ToString(s.flow) << ", electric field " << (s.electric_field ? "on" : "off")
      << '\n';
  if (s.has_shear())
    out << "  Ca = " << s.Ca << ", Re = " << s.Re;
  else
    out << "  Oh = " << s.Oh;
  if (s.membrane == MembraneKind::kCapsule) {
    out << ", E_b = " << s.E_b << ", eta = " << s.eta;
    if (s.prestress > 0.0) out << ", prestress = " << s.prestress;
  }
  out << ", V = " << s.V << '\n';
  if (s.electric_field) {
    out << "  Ca_E = " << s.Ca_E << ", sigma_r = " << s.sigma_r << ", eps_r = " << s.eps_r << '\n';
  }
  const bool cube = s.dimension != 3 || s.geometry.half_length == s.geometry.half_width;
  out << "  N = " << s.N << (s.dimension == 3 && cube ? " (N^3)" : "") << ", M = " << s.M
      << ", L/a = " << s.geometry.half_width;
  if (!cube) out << ", L_x/a = L_z/a = " << s.geometry.half_length;
  if (s.geometry.shape == InitialShape::kEllipse) out << ", b/a = " << s.geometry.aspect_ratio;
  out << '\n';
  for (const auto& o : s.overrides) out << "  override " << o << '\n';
  return out.str();
}

}  // namespace ehd
