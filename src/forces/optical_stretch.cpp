// Optical-tweezers stretching (the force term of docs/architecture.md's worked example): two
// equal and opposite forces +-F along x on two patches of the membrane at the body's x ends, as
// two beads pull a red cell (Mills, Qie, Dao, Lim & Suresh, Mech. Chem. Biosyst. 1, 169 (2004);
// Suresh et al., Acta Biomater. 1, 15 (2005)), the standard test of cell models since.
//
// The patches are material: the points within a distance r_c of the x axis through the initial
// centroid, on either side (chosen once, from the initial shape). The force is spread over each
// patch as a uniform traction: in 2D a load per unit length F / (patch length), in 3D a force per
// vertex F A_i / (patch area) with A_i a third of the areas of the triangles around vertex i. The
// net force is zero and each patch carries exactly F. F is given as f = F / T in 2D and
// f = F / (T a) in 3D (T the scene's tension scale: E_s, G_s or gamma).
//
// Exact check (2D, test/forces/optical_stretch_test.cpp): a tension-only ring (E_b = 0) of
// enclosed area pi a^2 under two point forces is at rest as two circular arcs of radius R and
// half-angle beta meeting at the loads, with uniform stretch lambda: area R^2 (2 beta -
// sin 2 beta) = pi a^2, length 4 R beta = 2 pi a lambda, and at each load F = 2 T cos(beta),
// T = E_s (lambda - 1), so that f = 2 (lambda - 1) cos(beta); D_A = 2 R sin(beta), D_T =
// 2 R (1 - cos(beta)).
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "ehd_capsule/coupling/force_term.h"
#include "ehd_capsule/ib/marker_update.h"

namespace ehd {
namespace {

template <int D>
class OpticalStretch : public ForceTerm<D> {
 public:
  OpticalStretch(const Scene& scene, const LatticeUnits& units, const Body<D>& body)
      : f_(scene.Number("stretch.force")), contact_(scene.Number("stretch.contact_radius")) {
    force_ = f_ * units.tension * (D == 3 ? units.radius : 1.0);
    const Eigen::Matrix<double, D, 1> centre = body.initial.rowwise().mean();
    const double r_c = contact_ * units.radius;
    side_.assign(body.size(), 0);
    int left = 0, right = 0;
    for (int i = 0; i < body.size(); ++i) {
      const Eigen::Matrix<double, D, 1> d = body.initial.col(i) - centre;
      if (d.tail(D - 1).norm() >= r_c) continue;  // distance from the x axis
      side_[i] = d(0) > 0 ? 1 : -1;
      ++(d(0) > 0 ? right : left);
    }
    if (left < 2 || right < 2) {
      throw SceneError("scene " + scene.name + ": 'stretch.contact_radius' = " + Format(contact_) +
                       " holds " + std::to_string(std::min(left, right)) +
                       " points on one end: at least 2 are needed (raise it, or refine the "
                       "membrane)");
    }
    patch_points_ = std::min(left, right);
  }

  std::string Describe() const override {
    std::ostringstream out;
    out << "optical stretch (Mills et al. 2004): +-F along x on the " << patch_points_
        << "+ points within " << contact_ << " a of the axis at each end, f = " << f_
        << " (F = " << force_ << " lattice)";
    return out.str();
  }

  void Compute(const Body<D>& body, PointsOf<D>& load) override {
    // The weights: arc elements (2D) or vertex areas (3D); each patch's sum carries F.
    if constexpr (D == 2) {
      MarkerArcElements(body.shape.curve, weight_);
    } else {
      weight_ = VertexThirdAreas(body.shape.mesh);
    }
    double sum[2] = {0.0, 0.0};
    for (int i = 0; i < body.size(); ++i) {
      if (side_[i] != 0) sum[side_[i] > 0] += weight_[i];
    }
    for (int i = 0; i < body.size(); ++i) {
      if (side_[i] == 0) continue;
      // 2D: the load is per unit length (the spread multiplies by dl), so the traction F / L;
      // 3D: the force per vertex F A_i / A.
      const double per = force_ / sum[side_[i] > 0];
      load(0, i) = side_[i] * (D == 2 ? per : per * weight_[i]);
    }
  }

 private:
  static std::string Format(double v) {
    std::ostringstream out;
    out << v;
    return out.str();
  }

  double f_;
  double contact_;
  double force_ = 0;       // F, lattice units
  std::vector<int> side_;  // +1 right patch, -1 left patch, 0 free
  int patch_points_ = 0;   // the smaller patch's point count
  std::vector<double> weight_;
};

SceneModule StretchKeys() {
  const KeyCondition stretch{"with a stretch: block",
                             [](const Scene& s) { return s.Has("stretch"); }};
  const KeyCondition capsule{"capsule",
                             [](const Scene& s) { return s.membrane == MembraneKind::kCapsule; }};
  SceneModule m;
  m.name = "stretch";
  m.doc =
      "Optical-tweezers stretching (Mills et al. 2004): +-F along x on two material patches at "
      "the body's x ends (src/forces/optical_stretch.cpp). A capsule only: a drop's points are "
      "not material.";
  m.keys = {BlockKey("stretch", "the stretching force; its presence builds the term")
                .When(capsule, "a drop's points are not material (needs membrane: capsule)"),
            NumberKey("stretch.force", Closed(0.0, 100.0), "T (2D), T a (3D)",
                      "F / T in 2D, F / (T a) in 3D: the force on each end")
                .Required()
                .When(stretch, ""),
            NumberKey("stretch.contact_radius", LeftOpen(0.0, 1.0), "a",
                      "the patches: the points within this distance of the x axis through the "
                      "initial centroid (Mills et al.: a contact diameter of 2 um on a cell of "
                      "radius 3.91 um, 0.26)")
                .Default(0.26)
                .When(stretch, "")};
  m.stages = {"stretch"};
  m.publishes = {"the force source 'stretch' (Body::DescribeLargestLoads, the pipeline line)"};
  return m;
}

[[maybe_unused]] const bool kRegistered = RegisterForceTerm<OpticalStretch>(
    StretchKeys(),
    [](const Scene& s) { return s.Has("stretch") && s.Number("stretch.force") > 0; });

}  // namespace
}  // namespace ehd
