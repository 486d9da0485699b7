#include "ehd_capsule/ros/state_messages.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace ehd::ros_node {
namespace {

geometry_msgs::Point ToPoint(double x, double y) {
  geometry_msgs::Point p;
  p.x = x;
  p.y = y;
  p.z = 0.0;
  return p;
}

std_msgs::ColorRGBA Color(float r, float g, float b, float a = 1.0f) {
  std_msgs::ColorRGBA c;
  c.r = r;
  c.g = g;
  c.b = b;
  c.a = a;
  return c;
}

visualization_msgs::Marker BaseMarker(const StateMessageSettings& settings, const ros::Time& stamp,
                                      const std::string& ns, int id, int type) {
  visualization_msgs::Marker m;
  m.header.frame_id = settings.frame_id;
  m.header.stamp = stamp;
  m.ns = ns;
  m.id = id;
  m.type = type;
  m.action = visualization_msgs::Marker::ADD;
  m.pose.orientation.w = 1.0;
  return m;
}

}  // namespace

double LatticeRadius(const Simulation& sim) { return sim.units().radius; }

double LatticeForceDensityScale(const Simulation& sim) {
  // Force density has units of tension / length: T / a. The tension scale T stays fixed when Ca
  // changes at run time (only the shear rate does), so this scale is constant for a run.
  return sim.units().tension / sim.units().radius;
}

ehd_capsule::CapsuleState MakeCapsuleState(const Simulation& sim,
                                           const StateMessageSettings& settings,
                                           const ros::Time& stamp) {
  const SimulationState& s = sim.state();
  const double a = LatticeRadius(sim);
  const double fscale = LatticeForceDensityScale(sim);
  ehd_capsule::CapsuleState msg;
  msg.header.frame_id = settings.frame_id;
  msg.header.stamp = stamp;
  msg.step = s.step;
  msg.time = s.time;
  msg.markers.reserve(s.markers.cols());
  for (int k = 0; k < s.markers.cols(); ++k) {
    msg.markers.push_back(ToPoint(s.markers(0, k) / a, s.markers(1, k) / a));
  }
  msg.electric_force.reserve(s.electric_force.cols());
  for (int k = 0; k < s.electric_force.cols(); ++k) {
    geometry_msgs::Vector3 f;
    f.x = s.electric_force(0, k) / fscale;
    f.y = s.electric_force(1, k) / fscale;
    msg.electric_force.push_back(f);
  }
  // The total is an integral of force density over length: force / (T) in units of T.
  msg.electric_force_total.x = s.electric_force_total.x() / (fscale * a);
  msg.electric_force_total.y = s.electric_force_total.y() / (fscale * a);
  msg.dxy = s.dxy;
  msg.inclination = s.inclination;
  msg.area = s.area / (M_PI * a * a);
  msg.area_drift = s.area_drift;
  msg.tt_phase = s.tt_phase;
  msg.ca_e = s.ca_e;
  msg.ca = s.ca;
  msg.gmres_iterations = s.gmres_iterations;
  msg.gmres_residual = s.gmres_residual;
  msg.max_mach = s.max_mach;
  return msg;
}

geometry_msgs::PolygonStamped MakeShape(const Simulation& sim, const StateMessageSettings& settings,
                                        const ros::Time& stamp) {
  const SimulationState& s = sim.state();
  const double a = LatticeRadius(sim);
  geometry_msgs::PolygonStamped poly;
  poly.header.frame_id = settings.frame_id;
  poly.header.stamp = stamp;
  poly.polygon.points.reserve(s.markers.cols());
  for (int k = 0; k < s.markers.cols(); ++k) {
    geometry_msgs::Point32 p;
    p.x = static_cast<float>(s.markers(0, k) / a);
    p.y = static_cast<float>(s.markers(1, k) / a);
    p.z = 0.0f;
    poly.polygon.points.push_back(p);
  }
  return poly;
}

visualization_msgs::MarkerArray MakeMarkerArray(const Simulation& sim,
                                                const StateMessageSettings& settings,
                                                const ros::Time& stamp) {
  const SimulationState& s = sim.state();
  const double a = LatticeRadius(sim);
  const double fscale = LatticeForceDensityScale(sim);
  visualization_msgs::MarkerArray array;

  // Membrane as a closed line strip.
  visualization_msgs::Marker membrane =
      BaseMarker(settings, stamp, "membrane", 0, visualization_msgs::Marker::LINE_STRIP);
  membrane.scale.x = 0.02;
  membrane.color = Color(0.1f, 0.4f, 0.9f);
  for (int k = 0; k <= s.markers.cols(); ++k) {
    const int kk = k % s.markers.cols();
    membrane.points.push_back(ToPoint(s.markers(0, kk) / a, s.markers(1, kk) / a));
  }
  array.markers.push_back(membrane);

  // Electric force arrows: one LINE_LIST segment per marker (a single marker keeps it cheap).
  visualization_msgs::Marker forces =
      BaseMarker(settings, stamp, "electric_force", 1, visualization_msgs::Marker::LINE_LIST);
  forces.scale.x = 0.01;
  forces.color = Color(0.9f, 0.2f, 0.1f);
  for (int k = 0; k < s.electric_force.cols(); ++k) {
    const double x = s.markers(0, k) / a, y = s.markers(1, k) / a;
    const double dx = settings.force_arrow_scale * s.electric_force(0, k) / fscale;
    const double dy = settings.force_arrow_scale * s.electric_force(1, k) / fscale;
    forces.points.push_back(ToPoint(x, y));
    forces.points.push_back(ToPoint(x + dx, y + dy));
    // Head: two strokes of a quarter of the shaft at +-25 degrees back from the tip.
    const double length = std::hypot(dx, dy);
    if (length > 1e-12) {
      const double ux = dx / length, uy = dy / length, head = 0.25 * length;
      const double c = std::cos(0.4363), sn = std::sin(0.4363);
      for (double side : {1.0, -1.0}) {
        const double hx = -(ux * c - side * uy * sn) * head;
        const double hy = -(uy * c + side * ux * sn) * head;
        forces.points.push_back(ToPoint(x + dx, y + dy));
        forces.points.push_back(ToPoint(x + dx + hx, y + dy + hy));
      }
    }
  }
  if (forces.points.empty()) forces.action = visualization_msgs::Marker::DELETE;
  array.markers.push_back(forces);

  // Optional velocity arrows on a coarse grid, in units of the wall speed k L (or of the max).
  if (settings.velocity_arrows) {
    visualization_msgs::Marker vel =
        BaseMarker(settings, stamp, "velocity", 2, visualization_msgs::Marker::LINE_LIST);
    vel.scale.x = 0.01;
    vel.color = Color(0.3f, 0.3f, 0.3f, 0.8f);
    const Grid2D& g = sim.grid();
    const auto& ux = sim.ux();
    const auto& uy = sim.uy();
    double umax = 0.0;
    for (std::size_t n = 0; n < ux.size(); ++n) umax = std::max(umax, std::hypot(ux[n], uy[n]));
    const double cell = settings.velocity_stride * g.h / a;  // arrow of the fastest = one cell
    for (int j = settings.velocity_stride / 2; j < g.ny; j += settings.velocity_stride) {
      for (int i = settings.velocity_stride / 2; i < g.nx; i += settings.velocity_stride) {
        const std::size_t n = g.index(i, j);
        const double x = g.x(i) / a, y = g.y(j) / a;
        const double sx = umax > 0.0 ? ux[n] / umax * cell : 0.0;
        const double sy = umax > 0.0 ? uy[n] / umax * cell : 0.0;
        vel.points.push_back(ToPoint(x, y));
        vel.points.push_back(ToPoint(x + sx, y + sy));
      }
    }
    array.markers.push_back(vel);
  }

  // The walls: y = +-L moving (shear), or the whole closed box.
  const double half = 0.5 * sim.grid().ny * sim.grid().h / a;
  const double half_x = 0.5 * sim.grid().nx * sim.grid().h / a;
  visualization_msgs::Marker walls =
      BaseMarker(settings, stamp, "walls", 4, visualization_msgs::Marker::LINE_LIST);
  walls.scale.x = 0.04;
  walls.color = Color(0.75f, 0.75f, 0.75f);
  for (double y : {-half, half}) {
    walls.points.push_back(ToPoint(-half_x, y));
    walls.points.push_back(ToPoint(half_x, y));
  }
  if (!sim.scene().has_shear()) {
    for (double x : {-half_x, half_x}) {
      walls.points.push_back(ToPoint(x, -half));
      walls.points.push_back(ToPoint(x, half));
    }
  }
  array.markers.push_back(walls);

  // Text overlay above the domain, two short lines (the step count grows to 7 digits).
  visualization_msgs::Marker text =
      BaseMarker(settings, stamp, "status", 3, visualization_msgs::Marker::TEXT_VIEW_FACING);
  text.pose.position = ToPoint(0.0, half + 0.45);
  text.scale.z = 0.22;
  text.color = Color(1.0f, 1.0f, 1.0f);
  char line[240];
  std::snprintf(line, sizeof(line),
                "step %ld   t = %.3f\nD_xy = %.4f   theta/pi = %.4f   Ca = %.4g   Ca_E = %.4g",
                s.step, s.time, s.dxy, s.inclination / M_PI, s.ca, s.ca_e);
  text.text = line;
  array.markers.push_back(text);
  return array;
}

FieldLayer ParseFieldLayer(const std::string& text, const Simulation& sim) {
  FieldLayer layer;
  if (text == "none") {
    layer = FieldLayer::kNone;
  } else if (text == "speed") {
    layer = FieldLayer::kSpeed;
  } else if (text == "potential") {
    layer = FieldLayer::kPotential;
  } else if (text == "field") {
    layer = FieldLayer::kFieldStrength;
  } else {
    throw std::invalid_argument("~field_layer = '" + text +
                                "': accepted none, speed, potential, field");
  }
  if ((layer == FieldLayer::kPotential || layer == FieldLayer::kFieldStrength) &&
      !sim.has_electric_field()) {
    throw std::invalid_argument("~field_layer = '" + text +
                                "' needs the electric field, but scene " + sim.scene().name +
                                " has none (accepted: none, speed)");
  }
  return layer;
}

namespace {

// A dark-blue -> teal -> yellow ramp (viridis-like), v in [0, 1].
std_msgs::ColorRGBA Ramp(double v) {
  static const float stops[5][3] = {{0.27f, 0.00f, 0.33f},
                                    {0.23f, 0.32f, 0.55f},
                                    {0.13f, 0.57f, 0.55f},
                                    {0.37f, 0.79f, 0.38f},
                                    {0.99f, 0.91f, 0.14f}};
  v = std::min(1.0, std::max(0.0, v)) * 4.0;
  const int i = std::min(3, static_cast<int>(v));
  const float t = static_cast<float>(v - i);
  return Color(stops[i][0] + t * (stops[i + 1][0] - stops[i][0]),
               stops[i][1] + t * (stops[i + 1][1] - stops[i][1]),
               stops[i][2] + t * (stops[i + 1][2] - stops[i][2]), 0.85f);
}

}  // namespace

visualization_msgs::MarkerArray MakeFieldLayer(const Simulation& sim, FieldLayer layer, int stride,
                                               const StateMessageSettings& settings,
                                               const ros::Time& stamp) {
  visualization_msgs::MarkerArray array;
  visualization_msgs::Marker cells =
      BaseMarker(settings, stamp, "field", 0, visualization_msgs::Marker::CUBE_LIST);
  if (layer == FieldLayer::kNone) {
    cells.action = visualization_msgs::Marker::DELETE;
    array.markers.push_back(cells);
    return array;
  }
  const Grid2D& g = sim.grid();
  const double a = LatticeRadius(sim);
  stride = std::max(1, stride);
  // The quantity per node.
  std::vector<double> q(g.size());
  double scale = 1.0;
  const char* name = "";
  if (layer == FieldLayer::kSpeed) {
    const auto& ux = sim.ux();
    const auto& uy = sim.uy();
    for (std::size_t n = 0; n < q.size(); ++n) q[n] = std::hypot(ux[n], uy[n]);
    scale = sim.units().wall_speed > 0.0 ? sim.units().wall_speed : 1.0;
    name = sim.units().wall_speed > 0.0 ? "|u| / kL" : "|u| (lattice)";
  } else {
    const auto& phi = sim.potential();
    if (phi.size() != g.size()) {
      // No potential yet (before the first solve, or Ca_E = 0): nothing to colour.
      cells.action = visualization_msgs::Marker::DELETE;
      array.markers.push_back(cells);
      return array;
    }
    if (layer == FieldLayer::kPotential) {
      q = phi;
      scale = sim.units().field * a;  // |E_inf| a
      name = "phi / (E_inf a)";
    } else {
      for (int j = 0; j < g.ny; ++j) {
        for (int i = 0; i < g.nx; ++i) {
          const int il = std::max(0, i - 1), ir = std::min(g.nx - 1, i + 1);
          const int jl = std::max(0, j - 1), jr = std::min(g.ny - 1, j + 1);
          const double ex = (phi[g.index(ir, j)] - phi[g.index(il, j)]) / ((ir - il) * g.h);
          const double ey = (phi[g.index(i, jr)] - phi[g.index(i, jl)]) / ((jr - jl) * g.h);
          q[g.index(i, j)] = std::hypot(ex, ey);
        }
      }
      scale = sim.units().field > 0.0 ? sim.units().field : 1.0;
      name = "|E| / E_inf";
    }
  }
  // Block averages and their range.
  std::vector<double> block;
  std::vector<geometry_msgs::Point> centres;
  double lo = 1e300, hi = -1e300;
  for (int j0 = 0; j0 < g.ny; j0 += stride) {
    for (int i0 = 0; i0 < g.nx; i0 += stride) {
      double sum = 0;
      int count = 0;
      for (int j = j0; j < std::min(g.ny, j0 + stride); ++j) {
        for (int i = i0; i < std::min(g.nx, i0 + stride); ++i) {
          sum += q[g.index(i, j)];
          ++count;
        }
      }
      const double v = sum / count / scale;
      block.push_back(v);
      lo = std::min(lo, v);
      hi = std::max(hi, v);
      geometry_msgs::Point p;
      p.x = (g.x0 + (i0 + 0.5 * std::min(stride, g.nx - i0)) * g.h) / a;
      p.y = (g.y0 + (j0 + 0.5 * std::min(stride, g.ny - j0)) * g.h) / a;
      p.z = -0.05;  // under the shape and arrows
      centres.push_back(p);
    }
  }
  cells.scale.x = cells.scale.y = stride * g.h / a;
  cells.scale.z = 0.01;
  cells.color = Color(1.0f, 1.0f, 1.0f, 0.85f);
  cells.points = centres;
  for (double v : block) cells.colors.push_back(Ramp(hi > lo ? (v - lo) / (hi - lo) : 0.0));
  array.markers.push_back(cells);
  // The range, as text beside the domain.
  visualization_msgs::Marker label =
      BaseMarker(settings, stamp, "field_range", 1, visualization_msgs::Marker::TEXT_VIEW_FACING);
  label.pose.position = ToPoint(0.0, -0.5 * g.ny * g.h / a - 0.35);
  label.scale.z = 0.2;
  label.color = Color(1.0f, 1.0f, 1.0f);
  char text[160];
  std::snprintf(text, sizeof text, "%s: %.3g (blue) .. %.3g (yellow)", name, lo, hi);
  label.text = text;
  array.markers.push_back(label);
  return array;
}

}  // namespace ehd::ros_node
