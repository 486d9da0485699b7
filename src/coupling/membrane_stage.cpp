// The membrane stage (coupling/stages/membrane_stage.h): one MembraneMechanics per body, its
// dimension's laws, writing the body's membrane force sources.
#include "ehd_capsule/coupling/stages/membrane_stage.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <sstream>

#include "ehd_capsule/ib/delta_kernel.h"
#include "ehd_capsule/membrane/helfrich_bending.h"
#include "ehd_capsule/membrane/membrane_model.h"
#include "ehd_capsule/membrane/membrane_stability.h"
#include "ehd_capsule/membrane/surface_elasticity.h"
#include "ehd_capsule/scene/scene_keys.h"

namespace ehd {
namespace {

// The explicit limit applies to AB2 as estimated; forward Euler allows twice the step
// (membrane_stability.h). The lattice step is 1; numerics.membrane_substeps = n divides the
// physical step by n (units.h), which multiplies the limit by n.
double StableLatticeStep(const Scene& scene, const MembraneStabilityLimits& limits) {
  return limits.min_dt() *
         (scene.numerics.integrator == MarkerTimeScheme::kForwardEuler ? 2.0 : 1.0);
}

// The Fourier transform of the immersed boundary's kernel (numerics.ib_kernel), which sets how
// strongly the fluid damps a membrane mode (membrane_stability.h).
KernelTransform KernelTransformOf(const Scene& scene) {
  switch (ParseDeltaKernel(scene.numerics.ib_kernel)) {
    case DeltaKernel::kRoma3:
    case DeltaKernel::kRoma3EvenOdd:  // roma3 across the membrane
      return Roma3DeltaTransform;
    case DeltaKernel::kTrapezoid3:
      return Trapezoid3DeltaTransform;
    default:
      return CosineDeltaTransform;
  }
}

// The smallest spline arc length between neighbouring markers (as MembraneModel::Stability).
double MinSpacing(const ClosedCurve& curve) {
  double least = curve.SegmentArcLength(0);
  for (int k = 1; k < curve.size(); ++k) least = std::min(least, curve.SegmentArcLength(k));
  return least;
}

// The key that sets the tension scale T: Ca with shear, Oh without.
std::string TensionKey(const Scene& scene) { return scene.has_shear() ? "Ca" : "Oh"; }

// "raise 'Ca' (now 1e-300)": the change of a key that lowers the membrane's stiffness.
std::string Change(const char* verb, const std::string& key, double now) {
  return std::string(verb) + " '" + key + "' (now " + FormatValue(now) + ")";
}
std::string SofterTension(const Scene& scene) {
  return Change("raise", TensionKey(scene), scene.has_shear() ? scene.Ca : scene.Oh);
}

// The advice when the explicit limit is exceeded: the substeps needed (in double: a tiny Ca or
// Oh needs more than an int holds) or, beyond numerics.membrane_substeps's maximum, the keys
// that make the membrane softer (`softer`).
// `power`: the limit grows as n^power with the substeps n (1 for the viscous limits, whose
// dt_max ~ mu / S ~ n; 5/3 for the grid-Nyquist one, S_c / S ~ n^2 (tau - 1/2)^(1/3)).
std::string SubstepAdvice(const Scene& scene, double dt_stable, const std::string& softer,
                          double power = 1.0) {
  const int now = scene.numerics.membrane_substeps;
  const double needed = std::ceil(now * std::pow(dt_stable, -1.0 / power) - 1e-9);
  const double most = DeclaredSceneKey("numerics.membrane_substeps").range.hi;
  if (needed <= most) {
    return "set numerics.membrane_substeps >= " + std::to_string(static_cast<int>(needed)) +
           " (now " + std::to_string(now) + ")";
  }
  return "out of reach: it would need numerics.membrane_substeps >= " +
         (std::isfinite(needed) ? FormatValue(needed) : std::string("infinity")) +
         ", beyond the key's maximum " + FormatValue(most) + " (now " + std::to_string(now) +
         "); " + softer;
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// 2D: MembraneModel on the marker curve (tension, Hookean, Kelvin-Voigt, bending in one density).
template <>
struct MembraneMechanics<2> {
  MembraneMechanics(const Scene& scene, const LatticeUnits& units, Body<2>& body)
      : scene_(scene), body_(body), source_(body.AddForceSource("membrane")) {
    MembraneParameters& mp = parameters_;
    if (scene.membrane == MembraneKind::kDrop) {
      mp.tension = units.tension;
    } else {
      mp.shear_modulus = units.tension;
      mp.tension = scene.prestress * units.tension;  // tau = tau_p + E_s (lambda - 1)
      mp.membrane_viscosity = units.membrane_viscosity;
      mp.bending_modulus = units.bending_modulus;
    }
    const ClosedCurve reference(body.initial);
    model_ = std::make_unique<MembraneModel>(mp, reference);
    MembraneStabilityLimits limits =
        model_->Stability(reference, units.viscosity, 1.0, KernelTransformOf(scene));
    // The tangential grid-Nyquist limit of a kernel that transmits that mode (roma3; measured on
    // D2Q9 only, so 2D only): membrane_stability.h.
    // roma3_even_odd does not couple to that mode (trapezoid3 along each component's axis).
    if (ParseDeltaKernel(scene.numerics.ib_kernel) != DeltaKernel::kRoma3EvenOdd) {
      limits.compression_dt = LatticeCompressionStep(
          mp.shear_modulus, units.tau, 1.0, MinSpacing(reference), KernelTransformOf(scene));
    }
    const double dt_stable = StableLatticeStep(scene, limits);
    if (dt_stable < 1.0) {
      const bool bending = limits.bending_dt == limits.min_dt();
      const bool compression = limits.compression_dt == limits.min_dt();
      const std::string key = TensionKey(scene);
      const std::string term = bending ? "bending (E_b)"
                               : compression
                                   ? "tangential grid-Nyquist (" + key + ", numerics.ib_kernel " +
                                         scene.numerics.ib_kernel + ")"
                               : limits.elastic_dt == limits.min_dt() ? "elasticity (" + key + ")"
                                                                      : "tension (" + key + ")";
      throw SceneError(
          "scene " + scene.name + ": membrane explicit limit exceeded by the " + term +
          " term: stable lattice dt " + FormatValue(dt_stable) + " < 1 (" + model_->Describe() +
          "); " +
          SubstepAdvice(scene, dt_stable,
                        bending ? Change("lower", "E_b", scene.E_b) : SofterTension(scene),
                        compression ? 5.0 / 3.0 : 1.0));
    }
    viscous_number_ = limits.viscous_number;
  }

  std::string Describe() const {
    std::ostringstream out;
    out << model_->Describe();
    if (scene_.numerics.membrane_substeps > 1) {
      out << " (time step refined " << scene_.numerics.membrane_substeps << "x)";
    }
    if (viscous_number_ >= 0.5) {
      out << "\nwarning: Kelvin-Voigt stability number " << viscous_number_
          << " >= 1/2 (explicit membrane viscosity may be unstable; lower eta)";
    }
    return out.str();
  }

  void Reset() {
    model_ = std::make_unique<MembraneModel>(parameters_, ClosedCurve(body_.positions()));
    history_ = 0;
  }

  void Run(long) {
    model_->ComputeForce(body_.shape.curve, 1.0, source_.load);
    previous2_ = previous1_;
    previous1_ = body_.positions();
    history_ = std::min(history_ + 1, 2);
  }

  // Kelvin-Voigt keeps a stretch history: the markers of the last two force evaluations are
  // saved and replayed on a fresh model, which rebuilds it bit for bit.
  void Save(CheckpointWriter& w) const {
    w.Pod(static_cast<std::int32_t>(history_));
    w.Mat(previous1_);
    w.Mat(previous2_);
  }

  void Restore(CheckpointReader& r) {
    history_ = r.Pod<std::int32_t>();
    previous1_ = r.Mat<2>();
    previous2_ = r.Mat<2>();
    model_ = std::make_unique<MembraneModel>(parameters_, ClosedCurve(body_.initial));
    Eigen::Matrix2Xd scratch;
    if (history_ >= 2) model_->ComputeForce(ClosedCurve(previous2_), 1.0, scratch);
    if (history_ >= 1) model_->ComputeForce(ClosedCurve(previous1_), 1.0, scratch);
  }

  std::vector<double> VertexTension() const {
    throw std::logic_error("MembraneStage: a 2D simulation has no surface mesh");
  }

  const Scene& scene_;
  Body<2>& body_;
  ForceSource<2>& source_;
  MembraneParameters parameters_;
  std::unique_ptr<MembraneModel> model_;  // rebuilt by Reset and Restore
  double viscous_number_ = 0;             // Kelvin-Voigt stability indicator
  Eigen::Matrix2Xd previous1_, previous2_;
  int history_ = 0;
};

// ---------------------------------------------------------------------------------------------
// 3D: finite elements on the triangle mesh (+ Helfrich bending), or a drop's surface tension.
namespace {

SurfaceLaw LawOf(const Scene& s) {
  switch (s.law) {
    case SurfaceLawKind::kSkalak:
      return SurfaceLaw::kSkalak;
    case SurfaceLawKind::kZeroThickness:
      return SurfaceLaw::kZeroThickness;
    case SurfaceLawKind::kNeoHookean:
      break;
  }
  return SurfaceLaw::kNeoHookean;
}

}  // namespace

template <>
struct MembraneMechanics<3> {
  MembraneMechanics(const Scene& scene, const LatticeUnits& units, Body<3>& body)
      : body_(body), source_(body.AddForceSource("membrane")), modulus_(units.tension) {
    const TriangleMesh& mesh = body.shape.mesh;
    // Vertices farther apart than 2 h leave holes the immersed boundary leaks through (the
    // 4-point kernel's support is 4 h): refuse the scene, naming the subdivision that closes them
    // (each level halves the edges).
    const MeshQuality q = MeasureQuality(mesh);
    if (q.max_edge > 2.0) {
      int need = scene.mesh_subdivisions;
      double edge = q.max_edge;
      while (edge > 2.0 && need < 6) {
        edge *= 0.5;
        ++need;
      }
      throw SceneError("scene " + scene.name +
                       ": the membrane mesh is too coarse for the grid: " + "longest edge " +
                       FormatValue(q.max_edge) + " h > 2 h (a = " + FormatValue(units.radius) +
                       " cells); set mesh_subdivisions >= " + std::to_string(need) + " (now " +
                       std::to_string(scene.mesh_subdivisions) + ")");
    }
    if (scene.membrane == MembraneKind::kDrop) {
      tension_ = units.tension;
      const MembraneStabilityLimits limits = EstimateMembraneStability(
          tension_, 0.0, 0.0, 0.0, units.viscosity, 1.0, q.min_edge, KernelTransformOf(scene));
      const double dt_stable = StableLatticeStep(scene, limits);
      if (dt_stable < 1.0) {
        throw SceneError("scene " + scene.name +
                         ": membrane explicit limit exceeded by the tension (" + TensionKey(scene) +
                         ") term: stable lattice dt " + FormatValue(dt_stable) + " < 1; " +
                         SubstepAdvice(scene, dt_stable, SofterTension(scene)));
      }
      stability_ = "explicit limit dt <= " + FormatValue(dt_stable);
      return;
    }
    SurfaceLawParameters law;
    law.law = LawOf(scene);
    law.shear_modulus = units.tension;  // G_s
    law.area_dilation = scene.law == SurfaceLawKind::kSkalak ? scene.area_dilation : 1.0;
    elasticity_ = std::make_unique<SurfaceElasticity>(law, mesh);
    if (scene.E_b > 0.0) {
      bending_ = std::make_unique<HelfrichBending>(
          HelfrichParameters{units.bending_modulus, scene.c0 / units.radius});
      bending_source_ = &body.AddForceSource("bending");
    }
    // Explicit limit at the initial shape (membrane_stability.h): a planar membrane mode of
    // wavenumber k relaxes at S k^(p-1) phi_hat(k h)^2 / (4 mu) in 3D as in 2D, with the
    // in-plane stiffness S = 4 G_s (neo-Hookean, zero-thickness: tension G_s (4 e_1 + 2 e_2)) or
    // (2 + 2C) G_s (Skalak), and S = E_B for bending (p = 4); k up to pi / (shortest edge).
    const double stiffness =
        units.tension *
        (scene.law == SurfaceLawKind::kSkalak ? 2.0 + 2.0 * scene.area_dilation : 4.0);
    const MembraneStabilityLimits limits =
        EstimateMembraneStability(0.0, stiffness, bending_ ? units.bending_modulus : 0.0, 0.0,
                                  units.viscosity, 1.0, q.min_edge, KernelTransformOf(scene));
    const double dt_stable = StableLatticeStep(scene, limits);
    if (dt_stable < 1.0) {
      const bool bending = limits.bending_dt == limits.min_dt();
      const bool skalak = scene.law == SurfaceLawKind::kSkalak;
      const std::string key = TensionKey(scene);
      const std::string term =
          bending ? "bending (E_b)" : "elasticity (" + key + (skalak ? ", C)" : ")");
      const std::string softer =
          bending  ? Change("lower", "E_b", scene.E_b)
          : skalak ? Change("lower", "C", scene.area_dilation) + " or " + SofterTension(scene)
                   : SofterTension(scene);
      throw SceneError("scene " + scene.name + ": membrane explicit limit exceeded by the " + term +
                       " term: stable lattice dt " + FormatValue(dt_stable) + " < 1 (" +
                       elasticity_->Describe() + ", shortest edge " + FormatValue(q.min_edge) +
                       " h); " + SubstepAdvice(scene, dt_stable, softer));
    }
    stability_ = "explicit limit dt <= " + FormatValue(dt_stable);
  }

  std::string Describe() const {
    const std::string mesh = "\nmesh: " + MeasureQuality(body_.shape.mesh).Describe();
    if (!elasticity_) {
      return "drop: surface tension gamma = " + FormatValue(tension_) +
             ", force gamma (Delta x)_i A_i (cotangent mean-curvature normal); " + stability_ +
             mesh;
    }
    std::string d = elasticity_->Describe();
    if (bending_) d += ", " + bending_->Describe();
    return d + "; " + stability_ + mesh;
  }

  void Reset() {}

  void Run(long step) {
    const TriangleMesh& mesh = body_.shape.mesh;
    if (!elasticity_) {
      const SurfaceGeometry g = MeasureSurface(mesh);
      for (int v = 0; v < mesh.vertex_count(); ++v) {
        source_.load.col(v) = tension_ * g.vertex_area[v] * g.laplace_position.col(v);
      }
      return;
    }
    try {
      elasticity_->ComputeForces(mesh.vertices(), source_.load);
    } catch (const std::exception& e) {
      FailStep(step, std::string("membrane: ") + e.what());
    }
    if (bending_) bending_->ComputeForces(mesh, bending_source_->load);
  }

  void Save(CheckpointWriter&) const {}  // a function of the vertex positions
  void Restore(CheckpointReader&) {}

  std::vector<double> VertexTension() const {
    if (!elasticity_) return std::vector<double>(body_.size(), 1.0);
    std::vector<double> tension = elasticity_->VertexMeanTension(body_.positions());
    for (double& t : tension) t /= modulus_;
    return tension;
  }

  Body<3>& body_;
  ForceSource<3>& source_;
  ForceSource<3>* bending_source_ = nullptr;
  double modulus_ = 1;                             // units.tension (lattice)
  std::unique_ptr<SurfaceElasticity> elasticity_;  // capsule
  std::unique_ptr<HelfrichBending> bending_;       // capsule with E_b > 0
  double tension_ = 0;                             // drop: surface tension gamma
  std::string stability_;
};

// ---------------------------------------------------------------------------------------------

template <int D>
MembraneStage<D>::MembraneStage(const Scene& scene, const LatticeUnits& units, StepData<D>& data) {
  for (Body<D>& body : data.bodies) {
    bodies_.push_back(std::make_unique<MembraneMechanics<D>>(scene, units, body));
  }
}

template <int D>
MembraneStage<D>::~MembraneStage() = default;

template <int D>
std::string MembraneStage<D>::Describe() const {
  return bodies_.front()->Describe();
}

template <int D>
void MembraneStage<D>::Reset() {
  for (auto& b : bodies_) b->Reset();
}

template <int D>
void MembraneStage<D>::Run(long step) {
  for (auto& b : bodies_) b->Run(step);
}

template <int D>
void MembraneStage<D>::Save(CheckpointWriter& w) const {
  for (const auto& b : bodies_) b->Save(w);
}

template <int D>
void MembraneStage<D>::Restore(CheckpointReader& r) {
  for (auto& b : bodies_) b->Restore(r);
}

template <int D>
std::vector<double> MembraneStage<D>::VertexTension(int body) const {
  return bodies_.at(body)->VertexTension();
}

template class MembraneStage<2>;
template class MembraneStage<3>;

}  // namespace ehd
