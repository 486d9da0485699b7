// TinyScene: the small scenes the tests run, built in code instead of copied YAML.
//
//   Scene s = TinyScene(2).With("Ca", 0.05).Field(0.3).Build();
//
// TinyScene(2) is a 2D Hookean capsule (no bending, no membrane viscosity, V = 1) in shear, a = 4
// cells on a 32^2 grid with 32 markers (a step is well under a millisecond); TinyScene(3) is a
// neo-Hookean sphere in shear on 24^3 with 642 vertices (a = 4 cells). The builder writes YAML
// text and Build() reads it with ParseScene, so every scene is validated exactly as a scene file
// is (a key the scene library refuses throws SceneError from Build()). Keys are paths as in an
// override ("geometry.shape"); numbers are written in their shortest exact form, so
// With("Ca", 0.05) is the scene `Ca: 0.05`.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "ehd_capsule/scene/scene.h"

namespace ehd::test {

class TinyScene {
 public:
  explicit TinyScene(int dimension = 2);

  // Sets (or adds) a key; a nested key as "geometry.half_width" or "numerics.threads".
  TinyScene& With(const std::string& path, double value);
  TinyScene& With(const std::string& path, int value) { return With(path, double(value)); }
  TinyScene& With(const std::string& path, const char* value) {
    return With(path, std::string(value));
  }
  TinyScene& With(const std::string& path, const std::string& value);  // written as given
  TinyScene& Without(const std::string& path);  // removes a key (and a block's keys)
  TinyScene& Name(const std::string& name) { return With("name", name); }
  // N grid cells across (2D: and N markers).
  TinyScene& Grid(int n);
  // A leaky-dielectric field: Ca_E, sigma_r, eps_r and the `electric: {}` block.
  TinyScene& Field(double ca_e, double sigma_r = 1.75, double eps_r = 3.5);
  // A drop (interfacial tension only): membrane drop, no E_b, eta or (3D) law.
  TinyScene& Drop();
  // A closed box at rest: flow none, Oh instead of Ca and Re.
  TinyScene& AtRest(double oh = 1.0);

  std::string Yaml() const;
  // ParseScene(Yaml(), overrides); throws SceneError.
  // The small-Ca 2D capsule of the small-Ca law and the kernel stability tests (a = 4 cells, 32
  // markers, Re = 0.2, one thread) at Ca = ca.
  static TinyScene SmallCaCapsule(double ca);
  Scene Build(const std::vector<std::string>& overrides = {}) const;

 private:
  int dimension_;
  std::vector<std::pair<std::string, std::string>> entries_;  // path, YAML value, in order
};

// The shortest decimal text that reads back as exactly `value` ("0.05", "1e-07", "48").
std::string ExactNumber(double value);

}  // namespace ehd::test
