// Scene parsing, overrides, validation messages and the units conversion.
#include "ehd_capsule/scene/scene.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "ehd_capsule/scene/units.h"

namespace ehd {
namespace {

const char* kMinimalCapsule = R"(
name: tiny
Ca: 0.05
Re: 0.1
E_b: 0
eta: 0
V: 1
N: 32
M: 32
geometry: {shape: circle, half_width: 4}
membrane: capsule
flow: shear
)";

// The error must name the key, the offending value and the accepted range.
void ExpectSceneError(const std::string& text, const std::vector<std::string>& overrides,
                      const std::vector<std::string>& must_contain) {
  try {
    ParseScene(text, overrides, "test");
    FAIL() << "expected SceneError";
  } catch (const SceneError& e) {
    const std::string what = e.what();
    for (const auto& piece : must_contain) {
      EXPECT_NE(what.find(piece), std::string::npos) << "'" << piece << "' not in: " << what;
    }
  }
}

TEST(Scene, ParsesMinimalCapsule) {
  const Scene s = ParseScene(kMinimalCapsule);
  EXPECT_EQ(s.name, "tiny");
  EXPECT_DOUBLE_EQ(s.Ca, 0.05);
  EXPECT_EQ(s.N, 32);
  EXPECT_EQ(s.membrane, MembraneKind::kCapsule);
  EXPECT_FALSE(s.electric_field);  // no Ca_E and no electric block
  EXPECT_FALSE(s.has_bending());
  EXPECT_FALSE(s.has_viscosity_contrast());
}

TEST(Scene, UnknownKeyIsNamed) {
  ExpectSceneError(std::string(kMinimalCapsule) + "Caa: 1\n", {}, {"'Caa'", "unknown", "Ca"});
  ExpectSceneError(kMinimalCapsule, {"geometry.radius=2"}, {"'geometry.radius'", "unknown"});
}

TEST(Scene, DuplicateKeyIsRefusedWithBothLines) {
  // yaml-cpp would keep the first value; the second must not be dropped silently. kMinimalCapsule
  // starts with an empty line, so "Ca: 0.05" is line 3; the appended copy is line 13.
  ExpectSceneError(std::string(kMinimalCapsule) + "Ca: 0.2\n", {},
                   {"'Ca'", "twice", "lines 3 and 13"});
  ExpectSceneError(std::string(kMinimalCapsule) + "numerics:\n  tau: 1\n  tau: 2\n", {},
                   {"'numerics.tau'", "twice"});
}

TEST(Scene, MissingKeyIsNamed) {
  std::string text = kMinimalCapsule;
  text.replace(text.find("N: 32\n"), 6, "");
  ExpectSceneError(text, {}, {"'N'", "missing", "[16, 4096]"});
}

TEST(Scene, WrongTypeIsNamed) {
  ExpectSceneError(kMinimalCapsule, {"Ca=fast"}, {"'Ca'", "'fast'", "(0, 10]"});
  ExpectSceneError(kMinimalCapsule, {"N=64.5"}, {"'N'", "integer", "64.5"});
  ExpectSceneError(kMinimalCapsule, {"membrane=gel"}, {"'membrane'", "capsule | drop", "'gel'"});
  ExpectSceneError(kMinimalCapsule, {"geometry=3"}, {"'geometry'", "block"});
}

TEST(Scene, OutOfRangeIsNamed) {
  ExpectSceneError(kMinimalCapsule, {"Ca=-0.1"}, {"'Ca'", "-0.1", "(0, 10]"});
  ExpectSceneError(kMinimalCapsule, {"numerics.tau=0.5"}, {"'numerics.tau'", "0.5", "(0.5, 20]"});
  ExpectSceneError(kMinimalCapsule, {"V=0"}, {"'V'", "[0.01, 100]"});
  // A drop has no bending stiffness.
  ExpectSceneError(kMinimalCapsule, {"membrane=drop", "E_b=0.1"}, {"'E_b'", "0.1", "capsule"});
  // Without shear there is no Ca.
  ExpectSceneError(kMinimalCapsule, {"flow=none", "Oh=1"}, {"'Ca'", "flow: none"});
}

TEST(Scene, ElectricFieldNeedsRatios) {
  ExpectSceneError(kMinimalCapsule, {"Ca_E=0.3"}, {"'sigma_r'", "missing"});
  const Scene s = ParseScene(kMinimalCapsule, {"Ca_E=0.3", "sigma_r=1.75", "eps_r=3.5"});
  EXPECT_TRUE(s.electric_field);
  // An explicit (empty) electric block with Ca_E = 0 builds the field so it can be switched on;
  // without Ca_E it is refused (a field scene whose Ca_E was deleted would otherwise run with a
  // zero field and the solver built).
  const Scene block =
      ParseScene(std::string(kMinimalCapsule) + "electric: {}\nCa_E: 0\nsigma_r: 2\neps_r: 1\n");
  EXPECT_TRUE(block.electric_field);
  EXPECT_DOUBLE_EQ(block.Ca_E, 0.0);
  ExpectSceneError(std::string(kMinimalCapsule) + "electric: {}\nsigma_r: 2\neps_r: 1\n", {},
                   {"'Ca_E'", "missing", "electric: block"});
  ExpectSceneError(kMinimalCapsule, {"Ca_E=6", "sigma_r=1", "eps_r=1"}, {"'Ca_E'", "[0, 5]"});
}

TEST(Scene, OverridesApplyAndAreKeptInTheText) {
  const Scene s = ParseScene(kMinimalCapsule, {"Ca=0.2", "geometry.shape=ellipse",
                                               "geometry.aspect_ratio=0.5", "numerics.tau=0.8"});
  EXPECT_DOUBLE_EQ(s.Ca, 0.2);
  EXPECT_EQ(s.geometry.shape, InitialShape::kEllipse);
  EXPECT_DOUBLE_EQ(s.geometry.aspect_ratio, 0.5);
  EXPECT_DOUBLE_EQ(s.numerics.tau, 0.8);
  // The published text re-parses to the same scene.
  const Scene again = ParseScene(s.yaml_text);
  EXPECT_DOUBLE_EQ(again.Ca, 0.2);
  EXPECT_EQ(again.geometry.shape, InitialShape::kEllipse);
  ExpectSceneError(kMinimalCapsule, {"Ca"}, {"key=value"});
}

// An empty override removes a key: `--set electric= --set Ca_E=0` turns a field scene into one
// that builds no electric solver (docs/scenes.md), even though `electric:` with an empty block
// in a file does count as present.
TEST(Scene, EmptyOverrideRemovesTheKey) {
  const Scene with = LoadScene("shear_field", {"Ca_E=0"});
  EXPECT_TRUE(with.electric_field);  // the file has an electric: block
  const Scene without = LoadScene("shear_field", {"Ca_E=0", "electric="});
  EXPECT_FALSE(without.electric_field);
  EXPECT_THROW(LoadScene("shear_field", {"N="}), SceneError);  // N is required
}

// Bad input the reader once hung on or read silently wrong (issue 44, items 8 and 9): each is
// refused with the key or the limit named, in milliseconds.
std::string AliasBomb() {
  std::string text = "a: &a [x, x, x, x, x, x, x, x, x]\n";
  for (char c = 'b'; c <= 'i'; ++c) {
    text += std::string(1, c) + ": &" + c + " [";
    for (int k = 0; k < 9; ++k) text += std::string(k ? ", *" : "*") + char(c - 1);
    text += "]\n";
  }
  return text;
}

TEST(Scene, BadInputIsRefusedNamingTheKeyOrLimit) {
  const std::string base = kMinimalCapsule;
  auto replaced = [&](const std::string& from, const std::string& to) {
    std::string text = base;
    text.replace(text.find(from), from.size(), to);
    return text;
  };
  const struct {
    const char* what;
    std::string text;
    std::vector<std::string> must_contain;
  } cases[] = {
      {"alias bomb", base + AliasBomb(), {"more than 100000 YAML nodes", "aliases"}},
      {"alias inside its anchor", base + "x: &x [*x]\n", {"deeper than 64 levels", "'x'"}},
      {"deep nesting",
       base + "x: " + std::string(600, '[') + std::string(600, ']'),
       {"nested deeper than 500 levels at line 13"}},
      {"second document",
       base + "---\nCa: 5\n",
       {"second YAML document at line 14", "one document per scene file"}},
      {"leading zero", replaced("N: 32", "N: 0100"), {"'N'", "0100", "leading zero"}},
      {"negative leading zero", replaced("V: 1", "V: -01"), {"'V'", "leading zero"}},
      {"!!str on a number", replaced("Ca: 0.05", "Ca: !!str 0.04"), {"'Ca'", "!!str", "(0, 10]"}},
      {"quoted number", replaced("Ca: 0.05", "Ca: \"0.04\""), {"'Ca'", "quoted", "(0, 10]"}},
      {"list as a key", base + "? [a, b]\n: 1\n", {"line 13", "a list, not a name"}},
      {"block as a key in a block",
       base + "numerics: {{a: 1}: 2}\n",
       {"in 'numerics'", "a block (map), not a name"}},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.what);
    ExpectSceneError(c.text, {}, c.must_contain);
  }
  // What stays accepted: an empty document after a trailing '---', explicit numeric tags, a
  // decimal 0.5.
  EXPECT_NO_THROW(ParseScene(base + "---\n"));
  EXPECT_NO_THROW(ParseScene(replaced("Ca: 0.05", "Ca: !!float 0.05")));
  EXPECT_NO_THROW(ParseScene(replaced("Ca: 0.05", "Ca: 0.5")));
  EXPECT_NO_THROW(ParseScene(replaced("N: 32", "N: !!int 32")));
}

// A directory or an endless file as the scene path is named as such.
TEST(Scene, DirectoryOrHugeFileIsRefused) {
  try {
    LoadScene(SceneDirectory() + "/");
    FAIL() << "expected SceneError";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("is a directory"), std::string::npos) << e.what();
  }
  try {
    LoadScene("/dev/zero");
    FAIL() << "expected SceneError";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("larger than 1048576 bytes"), std::string::npos)
        << e.what();
  }
}

// Every shipped scene loads and gives usable lattice values.
TEST(Scene, ShippedScenesLoad) {
  const auto names = ListScenes();
  EXPECT_GE(names.size(), 10u);
  for (const auto& name : names) {
    SCOPED_TRACE(name);
    const Scene s = LoadScene(name);
    EXPECT_EQ(s.name, name);
    const LatticeUnits u = DeriveLatticeUnits(s);
    EXPECT_GT(u.tau, 0.5);
    EXPECT_LT(u.wall_mach, 0.1);
  }
  EXPECT_THROW(LoadScene("no_such_scene"), SceneError);
}

// Round trip: the lattice values put back into the definitions give the scene's numbers again
// (Ca = mu k a / E_s, Re = rho k a^2 / mu, E_b = E_B / (a^2 E_s), eta = mu_s / (a mu),
// Ca_E = eps+ a E^2 / E_s; Oh = mu / sqrt(rho a gamma)).
TEST(Units, RoundTripOfTheDimensionlessNumbers) {
  const Scene s = ParseScene(kMinimalCapsule, {"E_b=0.1", "eta=2", "Ca_E=0.3", "sigma_r=1.75",
                                               "eps_r=3.5", "V=5", "numerics.tau=0.9"});
  const LatticeUnits u = DeriveLatticeUnits(s);
  const double mu = u.viscosity, a = u.radius, k = u.shear_rate;
  EXPECT_DOUBLE_EQ(a, 4.0);  // N/2 / (L/a) = 16/4
  EXPECT_NEAR(mu, (0.9 - 0.5) / 3.0, 1e-15);
  EXPECT_NEAR(mu * k * a / u.tension, s.Ca, 1e-14);
  EXPECT_NEAR(k * a * a / mu, s.Re, 1e-14);
  EXPECT_NEAR(u.bending_modulus / (a * a * u.tension), s.E_b, 1e-14);
  EXPECT_NEAR(u.membrane_viscosity / (a * mu), s.eta, 1e-14);
  EXPECT_NEAR(u.eps_plus * a * u.field * u.field / u.tension, s.Ca_E, 1e-14);
  EXPECT_NEAR(u.viscosity_inner / u.viscosity, 5.0, 1e-14);
  EXPECT_NEAR(u.dt, k, 1e-18);  // one step is k dt = k in units of 1/k
  EXPECT_NEAR(ShearRateForCa(u, 2 * s.Ca), 2 * k, 1e-15);

  const Scene drop = ParseScene(
      kMinimalCapsule, {"membrane=drop", "E_b=0", "eta=0", "flow=none", "Ca=", "Re=", "Oh=1"});
  const LatticeUnits d = DeriveLatticeUnits(drop);
  EXPECT_NEAR(d.viscosity / std::sqrt(d.radius * d.tension), 1.0, 1e-14);
  EXPECT_DOUBLE_EQ(d.shear_rate, 0.0);
  EXPECT_NEAR(d.steps_per_time_unit, d.viscosity * d.radius / d.tension, 1e-12);
}

// A 3D box longer along x and z than across the walls (geometry.half_length): round(N L_x / L)
// cells there, a and the walls as in the cube; 2D has no such key, and a box too short is named.
TEST(Units, ThreeDimensionalBoxMayBeLongerThanItsWallGap) {
  const std::string sphere =
      "name: box\ndimension: 3\nCa: 0.05\nRe: 0.1\nE_b: 0\nV: 1\nN: 21\nmesh_subdivisions: 3\n"
      "law: neo_hookean\ngeometry: {shape: sphere, half_width: 1.3}\nmembrane: capsule\n"
      "flow: shear\n";
  const LatticeUnits cube = DeriveLatticeUnits(ParseScene(sphere));
  EXPECT_EQ(cube.nx, 21);
  EXPECT_EQ(cube.nz, 21);
  const Scene long_box = ParseScene(sphere, {"geometry.half_length=3"});
  const LatticeUnits u = DeriveLatticeUnits(long_box);
  EXPECT_EQ(u.nx, 48);  // 21 * 3 / 1.3 = 48.5 rounds to 48
  EXPECT_EQ(u.ny, 21);
  EXPECT_EQ(u.nz, 48);
  EXPECT_DOUBLE_EQ(u.radius, cube.radius);
  EXPECT_DOUBLE_EQ(u.wall_speed, cube.wall_speed);
  EXPECT_NE(DescribeUnits(long_box, u).find("grid 48 x 21 x 48"), std::string::npos);
  ExpectSceneError(kMinimalCapsule, {"geometry.half_length=3"}, {"'geometry.half_length'", "2D"});
  try {
    DeriveLatticeUnits(ParseScene(sphere, {"geometry.half_length=1.01", "geometry.half_width=3"}));
    FAIL() << "7 cells along x were accepted";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("geometry.half_length"), std::string::npos) << e.what();
  }
}

TEST(Units, MachLimitFailsEarly) {
  // k L = Re nu L / a^2 = 50 * (1/6) * 16 / 16 = 8.3: far above 0.1 c_s.
  const Scene s = ParseScene(kMinimalCapsule, {"Re=50"});
  try {
    DeriveLatticeUnits(s);
    FAIL();
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("Mach"), std::string::npos) << e.what();
  }
}

// The typed declarations (scene/scene_keys.h): each rule a key follows can fail.
TEST(SceneKeys, TypesNullsConditionsAndOffValues) {
  // An integer key refuses 3.5, a number refuses text, a choice refuses another word.
  ExpectSceneError(kMinimalCapsule, {"numerics.membrane_substeps=3.5"},
                   {"'numerics.membrane_substeps'", "expected an integer in [1, 1000]", "'3.5'"});
  ExpectSceneError(kMinimalCapsule, {"Ca=fast"}, {"'Ca'", "expected a number in (0, 10]"});
  ExpectSceneError(kMinimalCapsule, {"flow=couette"}, {"'flow'", "one of shear | none"});
  // A scalar written without a value is an error, not its default.
  ExpectSceneError(std::string(kMinimalCapsule) + "numerics:\n  tau:\n", {},
                   {"'numerics.tau'", "is empty", "delete the line for the default (1)"});
  // Where a key does not apply it is refused with its reason, except its "off" value.
  ExpectSceneError(kMinimalCapsule, {"membrane=drop", "E_b=0.1"},
                   {"'E_b'", "not accepted here", "a drop has no bending", "(accepted here: 0)"});
  EXPECT_NO_THROW(ParseScene(kMinimalCapsule, {"membrane=drop", "E_b=0", "eta=0"}));
  ExpectSceneError(kMinimalCapsule, {"Oh=1"}, {"'Oh'", "not accepted here", "use Ca and Re"});
  // Rows of one key under disjoint conditions: N's range follows the dimension.
  EXPECT_NO_THROW(ParseScene(kMinimalCapsule, {"N=1024"}));
  ExpectSceneError(kMinimalCapsule,
                   {"dimension=3", "M=", "mesh_subdivisions=2", "N=1024", "geometry.shape=sphere",
                    "law=neo_hookean", "eta=0"},
                   {"'N'", "accepted [16, 512]"});
  // A field scene's Ca_E cannot be lost: with an electric: block it is required.
  ExpectSceneError(kMinimalCapsule, {"electric={}", "sigma_r=2", "eps_r=1"},
                   {"'Ca_E' missing", "required with an electric: block"});
  const Scene off = ParseScene(kMinimalCapsule, {"electric={}", "Ca_E=0", "sigma_r=2", "eps_r=1"});
  EXPECT_TRUE(off.electric_field);
  EXPECT_EQ(off.Ca_E, 0.0);
  // Every key read is in Scene::values, defaults included.
  EXPECT_EQ(off.Number("numerics.tau"), 1.0);
  EXPECT_EQ(off.Number("electric.max_Ca_E"), 5.0);
  EXPECT_THROW(off.Number("no.such.key"), std::logic_error);
}

TEST(SceneKeys, AModuleCannotRedeclareAKey) {
  SceneModule m;
  m.name = "test_duplicate";
  m.doc = "declares a key the flow module owns";
  m.keys.push_back(NumberKey("Ca", LeftOpen(0, 1), "1", "again"));
  try {
    RegisterSceneModule(m);
    FAIL() << "registered a second 'Ca'";
  } catch (const std::logic_error& e) {
    EXPECT_NE(std::string(e.what()).find("'Ca'"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace ehd
