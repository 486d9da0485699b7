#include "ehd_capsule/ros/state_messages.h"

#include <cmath>
#include <cstdio>

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
    forces.points.push_back(ToPoint(x, y));
    forces.points.push_back(
        ToPoint(x + settings.force_arrow_scale * s.electric_force(0, k) / fscale,
                y + settings.force_arrow_scale * s.electric_force(1, k) / fscale));
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

  // Text overlay above the domain.
  visualization_msgs::Marker text =
      BaseMarker(settings, stamp, "status", 3, visualization_msgs::Marker::TEXT_VIEW_FACING);
  const double half = 0.5 * sim.grid().ny * sim.grid().h / a;
  text.pose.position = ToPoint(0.0, half + 0.3);
  text.scale.z = 0.25;
  text.color = Color(1.0f, 1.0f, 1.0f);
  char line[200];
  std::snprintf(line, sizeof(line),
                "step %ld  t = %.3f  D_xy = %.4f  theta/pi = %.4f  Ca = %.4g  Ca_E = %.4g", s.step,
                s.time, s.dxy, s.inclination / M_PI, s.ca, s.ca_e);
  text.text = line;
  array.markers.push_back(text);
  return array;
}

}  // namespace ehd::ros_node
