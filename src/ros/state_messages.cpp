#include "ehd_capsule/ros/state_messages.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "ehd_capsule/geometry/triangle_mesh.h"

namespace ehd::ros_node {
namespace {

geometry_msgs::Point ToPoint(double x, double y, double z = 0.0) {
  geometry_msgs::Point p;
  p.x = x;
  p.y = y;
  p.z = z;
  return p;
}

// The shear plane x-y of the fluid grid: the 2D grid, or in 3D the node layer through the
// capsule's centroid.
struct ShearPlane {
  int nx = 0, ny = 0;
  double h = 1, x0 = 0, y0 = 0;
  std::size_t offset = 0;  // flat index of node (0, 0) of the plane
  int k = 0;               // 3D: the layer's z index
  double z = 0;            // 3D: its z coordinate (lattice), 0 in 2D
  std::size_t Index(int i, int j) const {
    return offset + static_cast<std::size_t>(j) * static_cast<std::size_t>(nx) +
           static_cast<std::size_t>(i);
  }
  double X(int i) const { return x0 + (i + 0.5) * h; }
  double Y(int j) const { return y0 + (j + 0.5) * h; }
};

ShearPlane PlaneOf(const Simulation& sim) {
  ShearPlane p;
  auto in_plane = [&p](const auto& g) {  // Grid2D or Grid3D: the x-y extent
    p.nx = g.nx;
    p.ny = g.ny;
    p.h = g.h;
    p.x0 = g.x0;
    p.y0 = g.y0;
  };
  if (sim.state().dimension == 3) {
    const Grid3D& g = sim.grid3d();
    in_plane(g);
    const double zc = sim.state().markers.cols() > 0 ? sim.state().markers.row(2).mean() : 0.0;
    p.k = std::min(g.nz - 1, std::max(0, static_cast<int>(std::floor((zc - g.z0) / g.h))));
    p.offset = g.index(0, 0, p.k);
    p.z = g.z(p.k);
  } else {
    in_plane(sim.grid());
  }
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
  const bool three_d = s.dimension == 3;
  for (int k = 0; k < s.markers.cols(); ++k) {
    msg.markers.push_back(
        ToPoint(s.markers(0, k) / a, s.markers(1, k) / a, three_d ? s.markers(2, k) / a : 0.0));
  }
  msg.electric_force.reserve(s.electric_force.cols());
  for (int k = 0; k < s.electric_force.cols(); ++k) {
    geometry_msgs::Vector3 f;
    f.x = s.electric_force(0, k) / fscale;
    f.y = s.electric_force(1, k) / fscale;
    f.z = three_d ? s.electric_force(2, k) / fscale : 0.0;
    msg.electric_force.push_back(f);
  }
  // The total is an integral of force density over length (2D: force / T) or over area (3D:
  // force / (T a)).
  msg.electric_force_total.x = s.electric_force_total.x() / (fscale * a);
  msg.electric_force_total.y = s.electric_force_total.y() / (fscale * a);
  msg.electric_force_total.z = three_d ? s.electric_force_total.z() / (fscale * a * a) : 0.0;
  if (three_d) {
    msg.electric_force_total.x /= a;
    msg.electric_force_total.y /= a;
  }
  msg.dxy = s.dxy;
  msg.inclination = s.inclination;
  msg.area = three_d ? s.area / (4.0 / 3.0 * M_PI * a * a * a) : s.area / (M_PI * a * a);
  msg.area_drift = s.area_drift;
  msg.tt_phase = s.tt_phase;
  msg.ca_e = s.ca_e;
  msg.ca = s.ca;
  msg.gmres_iterations = s.gmres_iterations;
  msg.gmres_residual = s.gmres_residual;
  msg.max_mach = s.max_mach;
  return msg;
}

ehd_capsule::SurfaceMesh MakeSurfaceMesh(const Simulation& sim,
                                         const StateMessageSettings& settings,
                                         const ros::Time& stamp) {
  if (sim.dimension() != 3) throw std::logic_error("MakeSurfaceMesh: a 3D simulation only");
  ehd_capsule::SurfaceMesh msg;
  msg.header.frame_id = settings.frame_id;
  msg.header.stamp = stamp;
  msg.vertex_count = static_cast<int>(sim.state().markers.cols());
  const auto& triangles = sim.triangles();
  msg.triangles.reserve(3 * triangles.size());
  for (const auto& t : triangles) msg.triangles.insert(msg.triangles.end(), t.begin(), t.end());
  return msg;
}

ehd_capsule::SurfaceState MakeSurfaceState(const Simulation& sim,
                                           const StateMessageSettings& settings,
                                           const ros::Time& stamp) {
  if (sim.dimension() != 3) throw std::logic_error("MakeSurfaceState: a 3D simulation only");
  const SimulationState& s = sim.state();
  ehd_capsule::SurfaceState msg;
  msg.header.frame_id = settings.frame_id;
  msg.header.stamp = stamp;
  msg.step = s.step;
  msg.surface_drift = s.surface_drift;
  msg.d_field = s.d_field;
  msg.surface_flow = s.surface_flow;
  return msg;
}

geometry_msgs::PolygonStamped MakeShape(const Simulation& sim, const StateMessageSettings& settings,
                                        const ros::Time& stamp) {
  const SimulationState& s = sim.state();
  const double a = LatticeRadius(sim);
  geometry_msgs::PolygonStamped poly;
  poly.header.frame_id = settings.frame_id;
  poly.header.stamp = stamp;
  if (s.dimension == 3) {
    // The cross-section in the shear plane through the centroid.
    const double zc = s.markers.row(2).mean();
    const TriangleMesh mesh(s.markers, sim.triangles());
    for (const Eigen::Vector2d& q : CrossSectionZ(mesh, zc)) {
      geometry_msgs::Point32 p;
      p.x = static_cast<float>(q.x() / a);
      p.y = static_cast<float>(q.y() / a);
      p.z = static_cast<float>(zc / a);
      poly.polygon.points.push_back(p);
    }
    return poly;
  }
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

SurfaceColour ParseSurfaceColour(const std::string& name) {
  if (name == "traction") return SurfaceColour::kTraction;
  if (name == "tension") return SurfaceColour::kTension;
  if (name == "speed") return SurfaceColour::kSpeed;
  if (name == "none") return SurfaceColour::kNone;
  throw std::invalid_argument("~surface_colour must be traction, tension, speed or none (got '" +
                              name + "')");
}

namespace {

// The per-vertex value the 3D surface is coloured by; empty for one colour (kNone, or the
// traction without a field).
std::vector<double> SurfaceColourQuantity(const Simulation& sim, SurfaceColour colour) {
  const SimulationState& s = sim.state();
  switch (colour) {
    case SurfaceColour::kTraction: {
      if (s.electric_force.cols() != s.markers.cols()) return {};
      const Eigen::Vector3d centroid = s.markers.rowwise().mean();
      std::vector<double> normal_traction(s.markers.cols());
      for (int k = 0; k < s.markers.cols(); ++k) {
        const Eigen::Vector3d n = (s.markers.col(k) - centroid).normalized();
        normal_traction[k] = s.electric_force.col(k).dot(n);
      }
      return normal_traction;
    }
    case SurfaceColour::kTension:
      return sim.VertexTension();
    case SurfaceColour::kSpeed: {
      const Eigen::Matrix3Xd u = sim.VertexVelocity();
      std::vector<double> speed(u.cols());
      for (int k = 0; k < u.cols(); ++k) speed[k] = u.col(k).norm();
      return speed;
    }
    case SurfaceColour::kNone:
      break;
  }
  return {};
}

// The membrane as a closed line strip (3D: its cross-section in the shear plane).
visualization_msgs::Marker MembraneMarker(const Simulation& sim,
                                          const StateMessageSettings& settings,
                                          const ros::Time& stamp) {
  const SimulationState& s = sim.state();
  const double a = LatticeRadius(sim);
  const bool three_d = s.dimension == 3;
  visualization_msgs::Marker membrane =
      BaseMarker(settings, stamp, "membrane", 0, visualization_msgs::Marker::LINE_STRIP);
  membrane.scale.x = 0.02;
  membrane.color = Color(0.1f, 0.4f, 0.9f);
  if (three_d) {
    const geometry_msgs::PolygonStamped section = MakeShape(sim, settings, stamp);
    for (std::size_t k = 0; k <= section.polygon.points.size() && !section.polygon.points.empty();
         ++k) {
      const auto& p = section.polygon.points[k % section.polygon.points.size()];
      membrane.points.push_back(ToPoint(p.x, p.y, p.z + 0.01));
    }
    if (membrane.points.empty()) membrane.action = visualization_msgs::Marker::DELETE;
  } else {
    for (int k = 0; k <= s.markers.cols(); ++k) {
      const int kk = k % s.markers.cols();
      membrane.points.push_back(ToPoint(s.markers(0, kk) / a, s.markers(1, kk) / a));
    }
  }
  return membrane;
}

// 3D: the surface as a shaded triangle list, coloured by ~surface_colour (dark blue: lowest,
// yellow: highest): the normal electric traction where there is a field (pulled inwards most to
// outwards most), the membrane tension, or the vertex speed; else one colour.
visualization_msgs::Marker SurfaceMarker(const Simulation& sim,
                                         const StateMessageSettings& settings,
                                         const ros::Time& stamp) {
  const SimulationState& s = sim.state();
  const double a = LatticeRadius(sim);
  visualization_msgs::Marker surface =
      BaseMarker(settings, stamp, "surface", 5, visualization_msgs::Marker::TRIANGLE_LIST);
  surface.scale.x = surface.scale.y = surface.scale.z = 1.0;
  surface.color = Color(0.55f, 0.7f, 0.95f, 1.0f);
  const std::vector<double> quantity = SurfaceColourQuantity(sim, settings.surface_colour);
  const bool coloured = !quantity.empty();
  double lo = 0, hi = 0;
  if (coloured) {
    // The ramp spans the 2nd to the 98th percentile, so a few extreme vertices do not leave
    // the rest of the surface in one colour.
    std::vector<double> sorted = quantity;
    std::sort(sorted.begin(), sorted.end());
    lo = sorted[static_cast<std::size_t>(0.02 * (sorted.size() - 1))];
    hi = sorted[static_cast<std::size_t>(0.98 * (sorted.size() - 1))];
  }
  for (const auto& t : sim.triangles()) {
    for (int c = 0; c < 3; ++c) {
      const int v = t[c];
      surface.points.push_back(
          ToPoint(s.markers(0, v) / a, s.markers(1, v) / a, s.markers(2, v) / a));
      if (coloured) {
        // Opaque: rviz does not sort a list's triangles, so a translucent surface shows its
        // back half through the front in patches.
        std_msgs::ColorRGBA colour = Ramp(hi > lo ? (quantity[v] - lo) / (hi - lo) : 0.5);
        colour.a = 1.0f;
        surface.colors.push_back(colour);
      }
    }
  }
  return surface;
}

// Electric force arrows: one LINE_LIST segment per point (a single marker keeps it cheap).
visualization_msgs::Marker ForceArrows(const Simulation& sim, const StateMessageSettings& settings,
                                       const ros::Time& stamp) {
  const SimulationState& s = sim.state();
  const double a = LatticeRadius(sim);
  const double fscale = LatticeForceDensityScale(sim);
  const bool three_d = s.dimension == 3;
  visualization_msgs::Marker forces =
      BaseMarker(settings, stamp, "electric_force", 1, visualization_msgs::Marker::LINE_LIST);
  forces.scale.x = 0.01;
  forces.color = Color(0.9f, 0.2f, 0.1f);
  for (int k = 0; k < s.electric_force.cols() && three_d; ++k) {
    // 3D: the shaft and a head of two strokes in the plane of the arrow and the radial
    // direction from the centroid.
    const Eigen::Vector3d x = s.markers.col(k) / a;
    const Eigen::Vector3d d = settings.force_arrow_scale * s.electric_force.col(k) / fscale;
    const double length = d.norm();
    if (!(length > 1e-12)) continue;
    forces.points.push_back(ToPoint(x.x(), x.y(), x.z()));
    forces.points.push_back(ToPoint(x.x() + d.x(), x.y() + d.y(), x.z() + d.z()));
    const Eigen::Vector3d u = d / length;
    Eigen::Vector3d side = u.cross(s.markers.col(k) - s.markers.rowwise().mean());
    side = side.norm() > 1e-12 ? side.normalized() : u.unitOrthogonal();
    const Eigen::Vector3d tip = x + d;
    for (double sign : {1.0, -1.0}) {
      const Eigen::Vector3d end =
          tip - 0.25 * length * (std::cos(0.4363) * u + sign * std::sin(0.4363) * side);
      forces.points.push_back(ToPoint(tip.x(), tip.y(), tip.z()));
      forces.points.push_back(ToPoint(end.x(), end.y(), end.z()));
    }
  }
  for (int k = 0; k < s.electric_force.cols() && !three_d; ++k) {
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
  return forces;
}

// Velocity arrows on a coarse grid, in units of the largest speed.
visualization_msgs::Marker VelocityArrows(const Simulation& sim,
                                          const StateMessageSettings& settings,
                                          const ros::Time& stamp) {
  const double a = LatticeRadius(sim);
  visualization_msgs::Marker vel =
      BaseMarker(settings, stamp, "velocity", 2, visualization_msgs::Marker::LINE_LIST);
  vel.scale.x = 0.01;
  vel.color = Color(0.3f, 0.3f, 0.3f, 0.8f);
  const ShearPlane g = PlaneOf(sim);
  const auto& ux = sim.ux();
  const auto& uy = sim.uy();
  double umax = 0.0;
  for (int j = 0; j < g.ny; ++j) {
    for (int i = 0; i < g.nx; ++i) {
      umax = std::max(umax, std::hypot(ux[g.Index(i, j)], uy[g.Index(i, j)]));
    }
  }
  const double cell = settings.velocity_stride * g.h / a;  // arrow of the fastest = one cell
  for (int j = settings.velocity_stride / 2; j < g.ny; j += settings.velocity_stride) {
    for (int i = settings.velocity_stride / 2; i < g.nx; i += settings.velocity_stride) {
      const std::size_t n = g.Index(i, j);
      const double x = g.X(i) / a, y = g.Y(j) / a;
      const double sx = umax > 0.0 ? ux[n] / umax * cell : 0.0;
      const double sy = umax > 0.0 ? uy[n] / umax * cell : 0.0;
      vel.points.push_back(ToPoint(x, y));
      vel.points.push_back(ToPoint(x + sx, y + sy));
    }
  }
  return vel;
}

// The walls: y = +-L moving (shear), or the whole closed box (3D: their traces in the shear
// plane).
visualization_msgs::Marker WallsMarker(const Simulation& sim, const StateMessageSettings& settings,
                                       const ros::Time& stamp) {
  const double a = LatticeRadius(sim);
  const ShearPlane plane = PlaneOf(sim);
  const double half = 0.5 * plane.ny * plane.h / a;
  const double half_x = 0.5 * plane.nx * plane.h / a;
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
  return walls;
}

// The text overlay above the domain, two short lines (the step count grows to 7 digits).
visualization_msgs::Marker StatusText(const Simulation& sim, const StateMessageSettings& settings,
                                      const ros::Time& stamp) {
  const SimulationState& s = sim.state();
  const bool three_d = s.dimension == 3;
  const ShearPlane plane = PlaneOf(sim);
  const double half = 0.5 * plane.ny * plane.h / LatticeRadius(sim);
  visualization_msgs::Marker text =
      BaseMarker(settings, stamp, "status", 3, visualization_msgs::Marker::TEXT_VIEW_FACING);
  text.pose.position = ToPoint(0.0, half + 0.45);
  text.scale.z = 0.22;
  text.color = Color(1.0f, 1.0f, 1.0f);
  char line[240];
  if (three_d) {
    std::snprintf(line, sizeof(line),
                  "step %ld   t = %.3f\nD_xy = %.4f   theta/pi = %.4f   D_z = %.4f   Ca = %.4g   "
                  "Ca_E = %.4g",
                  s.step, s.time, s.dxy, s.inclination / M_PI, s.d_field, s.ca, s.ca_e);
  } else {
    std::snprintf(line, sizeof(line),
                  "step %ld   t = %.3f\nD_xy = %.4f   theta/pi = %.4f   Ca = %.4g   Ca_E = %.4g",
                  s.step, s.time, s.dxy, s.inclination / M_PI, s.ca, s.ca_e);
  }
  text.text = line;
  return text;
}

}  // namespace

visualization_msgs::MarkerArray MakeMarkerArray(const Simulation& sim,
                                                const StateMessageSettings& settings,
                                                const ros::Time& stamp) {
  visualization_msgs::MarkerArray array;
  array.markers.push_back(MembraneMarker(sim, settings, stamp));
  if (sim.state().dimension == 3) array.markers.push_back(SurfaceMarker(sim, settings, stamp));
  array.markers.push_back(ForceArrows(sim, settings, stamp));
  if (settings.velocity_arrows) array.markers.push_back(VelocityArrows(sim, settings, stamp));
  array.markers.push_back(WallsMarker(sim, settings, stamp));
  array.markers.push_back(StatusText(sim, settings, stamp));
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
  const ShearPlane g = PlaneOf(sim);
  const bool three_d = sim.state().dimension == 3;
  const double a = LatticeRadius(sim);
  stride = std::max(1, stride);
  // The quantity per node of the plane (index j nx + i).
  const auto at = [&g](int i, int j) { return static_cast<std::size_t>(j) * g.nx + i; };
  std::vector<double> q(static_cast<std::size_t>(g.nx) * g.ny);
  double scale = 1.0;
  const char* name = "";
  if (layer == FieldLayer::kSpeed) {
    const auto& ux = sim.ux();
    const auto& uy = sim.uy();
    for (int j = 0; j < g.ny; ++j) {
      for (int i = 0; i < g.nx; ++i) {
        const std::size_t n = g.Index(i, j);
        q[at(i, j)] = three_d ? std::sqrt(ux[n] * ux[n] + uy[n] * uy[n] + sim.uz()[n] * sim.uz()[n])
                              : std::hypot(ux[n], uy[n]);
      }
    }
    scale = sim.units().wall_speed > 0.0 ? sim.units().wall_speed : 1.0;
    name = sim.units().wall_speed > 0.0 ? "|u| / kL" : "|u| (lattice)";
  } else {
    const auto& phi = sim.potential();
    const std::size_t expected = three_d ? sim.grid3d().size() : sim.grid().size();
    if (phi.size() != expected) {
      // No potential yet (before the first solve, or Ca_E = 0): nothing to colour.
      cells.action = visualization_msgs::Marker::DELETE;
      array.markers.push_back(cells);
      return array;
    }
    if (layer == FieldLayer::kPotential) {
      for (int j = 0; j < g.ny; ++j) {
        for (int i = 0; i < g.nx; ++i) q[at(i, j)] = phi[g.Index(i, j)];
      }
      scale = sim.units().field * a;  // |E_inf| a
      name = "phi / (E_inf a)";
    } else {
      for (int j = 0; j < g.ny; ++j) {
        for (int i = 0; i < g.nx; ++i) {
          const int il = std::max(0, i - 1), ir = std::min(g.nx - 1, i + 1);
          const int jl = std::max(0, j - 1), jr = std::min(g.ny - 1, j + 1);
          const double ex = (phi[g.Index(ir, j)] - phi[g.Index(il, j)]) / ((ir - il) * g.h);
          const double ey = (phi[g.Index(i, jr)] - phi[g.Index(i, jl)]) / ((jr - jl) * g.h);
          double ez = 0;
          if (three_d) {
            // Across the plane: the layers above and below (one-sided at the box faces).
            const Grid3D& g3 = sim.grid3d();
            const int kl = std::max(0, g.k - 1), kr = std::min(g3.nz - 1, g.k + 1);
            ez = (phi[g3.index(i, j, kr)] - phi[g3.index(i, j, kl)]) / ((kr - kl) * g.h);
          }
          q[at(i, j)] = std::sqrt(ex * ex + ey * ey + ez * ez);
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
          sum += q[at(i, j)];
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
      p.z = g.z / a - 0.05;  // under the shape and arrows
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
