// Closed triangulated surfaces for the 3D membranes and the 3D electric solver: the mesh, the
// shapes the scenes start from, and the discrete differential geometry on it.
//
// TriangleMesh: vertices (3 x V, lattice or physical units) and triangles (three vertex indices,
// counter-clockwise seen from outside, so face normals (b - a) x (c - a) point outwards), with
// the topology built once (HemoCell's CommonCellConstants idea): the edges, the triangles around
// each vertex and, per edge, its two triangles and opposite vertices. Vertex positions may then
// change freely (the membrane moves); the topology does not.
//
// Shapes: the icosphere (icosahedron subdivided k times, each edge split at its midpoint,
// projected on the sphere: V = 10 4^k + 2, F = 20 4^k: 12, 42, 162, 642, 2562, 10242 vertices for
// k = 0..5; song2019 ch. 6 uses k = 4), the ellipsoid (the icosphere scaled along the axes, so
// every vertex lies on the exact surface), and the biconcave red-cell surface of revolution of
// song2019 eq. (152) (Evans & Fung's profile): a sphere point at polar angle chi from the
// symmetry axis maps to distance a alpha sin(chi) from the axis and height
// (a alpha / 2)(c0 + c1 sin^2 chi + c2 sin^4 chi) cos(chi) along it. The symmetry axis is y, so
// the cross-section in the shear plane z = 0 is the 2D profile of BiconcaveMarkers.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <string>
#include <vector>

#include "ehd_capsule/geometry/initial_shapes.h"

namespace ehd {

class TriangleMesh {
 public:
  using Triangle = std::array<int, 3>;

  TriangleMesh() = default;
  // Builds the topology; throws std::invalid_argument unless the surface is closed and
  // consistently oriented (every edge in exactly two triangles, traversed once each way) with
  // vertex indices in range and no isolated vertex. (A doubly covered triangle, the smallest such
  // surface, is accepted: the membrane tests use it as a flat element.)
  TriangleMesh(Eigen::Matrix3Xd vertices, std::vector<Triangle> triangles);

  int vertex_count() const { return static_cast<int>(vertices_.cols()); }
  int triangle_count() const { return static_cast<int>(triangles_.size()); }
  int edge_count() const { return static_cast<int>(edges_.size()); }

  const Eigen::Matrix3Xd& vertices() const { return vertices_; }
  // Moves the vertices (same count); the topology stays.
  void SetVertices(const Eigen::Matrix3Xd& vertices);
  const std::vector<Triangle>& triangles() const { return triangles_; }

  struct Edge {
    int a, b;                           // a < b
    int left, right;                    // triangles on either side (left: the one with a -> b)
    int opposite_left, opposite_right;  // their vertices opposite the edge
  };
  const std::vector<Edge>& edges() const { return edges_; }
  // Triangles that contain vertex v.
  const std::vector<int>& vertex_triangles(int v) const { return vertex_triangles_[v]; }
  // Edges that contain vertex v.
  const std::vector<int>& vertex_edges(int v) const { return vertex_edges_[v]; }

  // Euler characteristic V - E + F (2 for a sphere).
  int EulerCharacteristic() const { return vertex_count() - edge_count() + triangle_count(); }

 private:
  Eigen::Matrix3Xd vertices_;
  std::vector<Triangle> triangles_;
  std::vector<Edge> edges_;
  std::vector<std::vector<int>> vertex_triangles_, vertex_edges_;
};

// Shapes (centred at the origin).
TriangleMesh IcosphereMesh(int subdivisions, double radius = 1.0);
TriangleMesh EllipsoidMesh(int subdivisions, double a, double b, double c);
TriangleMesh BiconcaveMesh(int subdivisions, const BiconcaveParameters& p = {});
// Exact enclosed volume of the biconcave surface: 2 pi R^3 (c0/3 + 2 c1/15 + 8 c2/105),
// R = a alpha (from V = 2 int_0^R 2 pi r z(r) dr).
double BiconcaveVolume(const BiconcaveParameters& p = {});

// Geometry of the current vertex positions.
double SurfaceArea(const TriangleMesh& mesh);
// A third of the area of each triangle around each vertex (they sum to the surface area): a
// cheap vertex weight where the mixed Voronoi areas of MeasureSurface (a cotangent pass) are not
// needed.
std::vector<double> VertexThirdAreas(const TriangleMesh& mesh);
// The same for the first `vertex_count` columns of x with a triangle list (no mesh built).
std::vector<double> VertexThirdAreas(const Eigen::Matrix3Xd& x,
                                     const std::vector<TriangleMesh::Triangle>& triangles,
                                     int vertex_count);
// The vertex-area-weighted (VertexThirdAreas) mean of a per-vertex field (one column each).
Eigen::Vector3d AreaWeightedMean(const TriangleMesh& mesh, const std::vector<double>& area,
                                 const Eigen::Matrix3Xd& field);
double EnclosedVolume(const TriangleMesh& mesh);     // (1/6) sum x_a . (x_b x x_c)
Eigen::Vector3d Centroid(const TriangleMesh& mesh);  // of the enclosed volume
// Unit outward vertex normals: the area-weighted average of the face normals.
Eigen::Matrix3Xd AreaWeightedVertexNormals(const TriangleMesh& mesh);
// The volume (1/6) sum x_a . (x_b x x_c) of the closed surface with vertices x and `triangles`.
double EnclosedVolume(const Eigen::Matrix3Xd& x,
                      const std::vector<TriangleMesh::Triangle>& triangles);
// Moves every vertex of x by one common distance delta along the unit direction of its volume
// gradient dV/dx_i (the area-weighted vertex normal; a uniform inflation or deflation of the
// surface, its shape kept to first order) so that the enclosed volume becomes `volume`: Newton
// on delta (V is a cubic in delta), to a relative 1e-14 or 8 iterations. Returns delta. Throws
// std::invalid_argument for volume <= 0 or a surface with a vanishing volume gradient.
double RestoreEnclosedVolume(const std::vector<TriangleMesh::Triangle>& triangles, double volume,
                             Eigen::Matrix3Xd& x);

// Discrete differential geometry (Meyer, Desbrun, Schroeder & Barr, "Discrete differential-
// geometry operators for triangulated 2-manifolds", 2003):
//   mixed Voronoi area A_i of each vertex (Voronoi region, or the triangle's half/quarter for
//   obtuse triangles), sum A_i = surface area;
//   the cotangent Laplace-Beltrami operator
//     (Delta f)_i = 1/(2 A_i) sum_j (cot alpha_ij + cot beta_ij)(f_j - f_i);
//   the mean curvature normal Delta x = -2 H n (H = 1/R on a sphere, n outward), so
//     H_i = -(Delta x)_i . n_i / 2;
//   the Gaussian curvature by the angle deficit K_i = (2 pi - sum theta) / A_i (sum K_i A_i =
//   2 pi chi exactly: Gauss-Bonnet);
//   vertex normals: the area-weighted average of the face normals.
struct SurfaceGeometry {
  std::vector<double> vertex_area;         // A_i
  Eigen::Matrix3Xd normal;                 // unit outward vertex normals
  Eigen::Matrix3Xd laplace_position;       // (Delta x)_i
  std::vector<double> mean_curvature;      // H_i
  std::vector<double> gaussian_curvature;  // K_i
};
SurfaceGeometry MeasureSurface(const TriangleMesh& mesh);
// (Delta f)_i for a scalar f per vertex, with the areas of MeasureSurface.
std::vector<double> LaplaceBeltrami(const TriangleMesh& mesh, const std::vector<double>& area,
                                    const std::vector<double>& f);

// Pointwise curvatures by a local fit (for what needs them vertex by vertex: the 3D immersed
// interface corrections). At each vertex, in the frame of its area-weighted normal, the height
// z = c_1 x + c_2 y + c_3 x^2 + c_4 x y + c_5 y^2 of the vertices within `rings` edge rings is
// fitted by least squares through the vertex (weights 1/|x_j - x_i|^2); from the fitted graph
// (gradient g = (c_1, c_2), Hessian [[2 c_3, c_4], [c_4, 2 c_5]]) the first and second
// fundamental forms give the shape operator, whose eigenvalues are the principal curvatures
// (sign: positive on a sphere with the outward normal, as H above), the tilt g corrects the
// normal, and its eigenvectors are the principal directions. Converges pointwise (the cotangent
// H and the angle-deficit K do not on irregular meshes; docs/geometry_3d.md).
struct FittedCurvatures {
  Eigen::Matrix3Xd normal;                     // corrected unit outward normals
  std::vector<double> kappa1, kappa2;          // principal curvatures, kappa1 >= kappa2
  Eigen::Matrix3Xd direction1, direction2;     // principal directions (unit, tangent)
  std::vector<double> mean_curvature() const;  // (kappa1 + kappa2) / 2
  std::vector<double> gaussian_curvature() const;
};
FittedCurvatures FitCurvatures(const TriangleMesh& mesh, int rings = 1);

// The section of the surface by the plane z = z0 (the shear-plane cross-section the node draws):
// the points where mesh edges cross the plane (a vertex on the plane counts as above it), chained
// through the triangles into closed loops; the longest loop, counter-clockwise seen from +z, as
// (x, y) points. Empty if the plane misses the surface.
std::vector<Eigen::Vector2d> CrossSectionZ(const TriangleMesh& mesh, double z0);

// Mesh quality: edge lengths, triangle angles, the largest aspect ratio circumradius /
// (2 inradius) (1 for an equilateral triangle) and the vertex valences.
struct MeshQuality {
  double min_edge = 0, max_edge = 0, mean_edge = 0;
  double min_angle_deg = 0, max_angle_deg = 0;
  double max_aspect_ratio = 0;
  int min_valence = 0, max_valence = 0;
  std::string Describe() const;
};
MeshQuality MeasureQuality(const TriangleMesh& mesh);

}  // namespace ehd
