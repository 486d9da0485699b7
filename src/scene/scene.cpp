// Scene files: parsing, overrides and validation (see scene.h for the keys and their meaning).
#include "ehd_capsule/scene/scene.h"

#include <yaml-cpp/depthguard.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <type_traits>

namespace ehd {
namespace {

std::string FormatNumber(double v) {
  std::ostringstream out;
  out << v;
  return out.str();
}

std::string ScalarText(const YAML::Node& node) {
  if (node.IsScalar()) return "'" + node.Scalar() + "'";
  if (node.IsMap()) return "a block (map)";
  if (node.IsSequence()) return "a list";
  return "nothing";
}

// A YAML scalar that reads as a finite number; false for blocks, lists and text.
bool ScalarAsDouble(const YAML::Node& v, double* x) {
  if (!v.IsScalar()) return false;
  try {
    *x = v.as<double>();
    return std::isfinite(*x);
  } catch (const YAML::Exception&) {
    return false;
  }
}

// Reads a scene's YAML tree key by key from the modules' declarations (scene/scene_keys.h).
class SceneReader {
 public:
  SceneReader(const YAML::Node& root, std::string origin)
      : root_(root), origin_(std::move(origin)) {}

  [[noreturn]] void Fail(const std::string& what, const std::string& message) const {
    throw SceneError("scene " + origin_ + ": " + what + " " + message);
  }

  // Every key of the tree is declared (a block's keys as "block.key"); checked before any value
  // is read, so that a misspelt key is reported as such and not as the missing key it stands for.
  void RejectUnknown(const std::vector<SceneModule>& modules) const {
    std::map<std::string, std::vector<std::string>> accepted;  // block ("" = top) -> keys
    std::set<std::string> blocks;
    for (const SceneModule& m : modules) {
      for (const SceneKey& k : m.keys) {
        const std::size_t dot = k.path.rfind('.');
        const std::string block = dot == std::string::npos ? "" : k.path.substr(0, dot);
        const std::string leaf = dot == std::string::npos ? k.path : k.path.substr(dot + 1);
        auto& list = accepted[block];
        if (std::find(list.begin(), list.end(), leaf) == list.end()) list.push_back(leaf);
        if (k.type == KeyType::kBlock) blocks.insert(k.path);
      }
    }
    for (auto& [block, list] : accepted) std::sort(list.begin(), list.end());
    CheckKeys(root_, "", accepted, blocks);
  }

  // Reads one declared key that applies here: its value, its default, or the error.
  void Read(const SceneKey& key, Scene& s) const {
    const YAML::Node v = Find(key.path);
    std::optional<SceneValue> value;
    if (key.type == KeyType::kBlock) {
      if (!v.IsDefined()) {
        if (key.required) Fail(Name(key), "missing (" + key.doc + ")");
      } else {
        if (!v.IsNull() && !v.IsMap()) {
          Fail(Name(key), "must be a block of 'key: value' lines, got " + ScalarText(v));
        }
        value = SceneValue{1.0, {}};
      }
    } else if (!v.IsDefined()) {
      if (key.required) {
        Fail(Name(key), key.type == KeyType::kChoice
                            ? "missing (" + key.doc + ": " + key.TypeText() + ")"
                            : "missing (" + key.doc + ", " + key.TypeText() + ")");
      }
      if (key.fallback) value = key.fallback;
      if (key.fallback_from) value = key.fallback_from(s);
    } else if (v.IsNull()) {
      Fail(Name(key),
           "is empty: give " + key.TypeText() + " (" + key.doc + ")" +
               (key.required ? ""
                             : ", or delete the line for the default (" + key.DefaultText() + ")"));
    } else {
      value = Parse(key, v);
    }
    if (!value) return;
    s.values[key.path] = *value;
    if (key.store) key.store(s, *value);
  }

  // A key given where its declaration does not apply: refused with the reason, unless it holds
  // the one value accepted there.
  void Refuse(const SceneKey& key) const {
    const YAML::Node v = Find(key.path);
    if (!v.IsDefined() || v.IsNull()) return;
    if (key.otherwise && key.type != KeyType::kBlock) {
      double x = 0;
      const bool same = key.type == KeyType::kChoice || key.type == KeyType::kText
                            ? v.IsScalar() && v.Scalar() == key.otherwise->text
                            : ScalarAsDouble(v, &x) && x == key.otherwise->number;
      if (same) return;
      const std::string accepted = key.type == KeyType::kChoice || key.type == KeyType::kText
                                       ? key.otherwise->text
                                       : FormatNumber(key.otherwise->number);
      Fail(Name(key), "= " + ScalarText(v) + " is not accepted here: " + key.refusal +
                          " (accepted here: " + accepted + ")");
    }
    Fail(Name(key), "= " + ScalarText(v) + " is not accepted here: " + key.refusal);
  }

  // The keys of the tree (and the choice values) that only a 3D scene accepts, "key" or "key:
  // value": the evidence that a scene read as 2D lacks `dimension: 3`.
  std::vector<std::string> OnlyThreeD(const std::vector<SceneModule>& modules) const {
    std::map<std::string, std::vector<const SceneKey*>> declarations;
    std::vector<std::string> order;
    for (const SceneModule& m : modules) {
      for (const SceneKey& k : m.keys) {
        if (declarations[k.path].empty()) order.push_back(k.path);
        declarations[k.path].push_back(&k);
      }
    }
    auto three_d = [](const SceneKey* k) { return k->when.text.compare(0, 2, "3D") == 0; };
    std::vector<std::string> found;
    for (const std::string& path : order) {
      const YAML::Node v = Find(path);
      if (!v.IsDefined() || v.IsNull()) continue;
      const std::vector<const SceneKey*>& keys = declarations[path];
      if (std::all_of(keys.begin(), keys.end(), three_d)) {
        found.push_back(path);
        continue;
      }
      if (!v.IsScalar()) continue;
      bool in_3d = false, in_other = false;
      for (const SceneKey* k : keys) {
        if (k->type != KeyType::kChoice) continue;
        const bool listed =
            std::find(k->choices.begin(), k->choices.end(), v.Scalar()) != k->choices.end();
        (three_d(k) ? in_3d : in_other) |= listed;
      }
      if (in_3d && !in_other) found.push_back(path + ": " + v.Scalar());
    }
    return found;
  }

  bool Has(const std::string& path) const { return Find(path).IsDefined(); }

 private:
  static std::string Name(const SceneKey& key) { return "'" + key.path + "'"; }

  // The node at a dotted path; undefined where a part is missing. (Handles are re-pointed with
  // reset: assigning one YAML::Node to another would write into the tree.)
  YAML::Node Find(const std::string& path) const {
    YAML::Node node;
    node.reset(root_);
    std::size_t start = 0;
    while (true) {
      const std::size_t dot = path.find('.', start);
      const std::string part = path.substr(start, dot - start);
      if (!node.IsMap()) return YAML::Node(YAML::NodeType::Undefined);
      const YAML::Node& parent = node;  // const: a lookup does not insert
      const YAML::Node child = parent[part];
      if (dot == std::string::npos || !child.IsDefined()) return child;
      node.reset(child);
      start = dot + 1;
    }
  }

  SceneValue Parse(const SceneKey& key, const YAML::Node& v) const {
    const std::string meaning = " (" + key.doc + ")";
    switch (key.type) {
      case KeyType::kNumber:
      case KeyType::kInteger: {
        double x = 0.0;
        const bool integer = key.type == KeyType::kInteger;
        RejectNumberSpelling(key, v);
        if (!ScalarAsDouble(v, &x) || (integer && x != std::floor(x))) {
          Fail(Name(key), "expected " + key.TypeText() + meaning + ", got " + ScalarText(v));
        }
        if (!key.range.Contains(x)) {
          Fail(Name(key),
               "= " + v.Scalar() + " is out of range: accepted " + key.range.Text() + meaning);
        }
        return {x, {}};
      }
      case KeyType::kChoice:
        if (!v.IsScalar() ||
            std::find(key.choices.begin(), key.choices.end(), v.Scalar()) == key.choices.end()) {
          Fail(Name(key), "expected " + key.TypeText() + meaning + ", got " + ScalarText(v));
        }
        return {0.0, v.Scalar()};
      case KeyType::kText:
        if (!v.IsScalar()) Fail(Name(key), "expected text, got " + ScalarText(v));
        return {0.0, v.Scalar()};
      case KeyType::kBlock:
        break;
    }
    return {};
  }

  // Text where a number belongs (quoted, or tagged !!str or a custom tag), and a leading zero
  // on an integer (YAML 1.1 reads 0100 as octal 64, yaml-cpp as 100): refused, not guessed.
  void RejectNumberSpelling(const SceneKey& key, const YAML::Node& v) const {
    if (!v.IsScalar()) return;
    const std::string& tag = v.Tag();
    const std::string yaml_tag = "tag:yaml.org,2002:";
    if (tag != "?" && tag != yaml_tag + "int" && tag != yaml_tag + "float") {
      const std::string shown = tag == "!" ? "quoted text"
                                : tag.compare(0, yaml_tag.size(), yaml_tag) == 0
                                    ? "text tagged !!" + tag.substr(yaml_tag.size())
                                    : "text tagged " + tag;
      Fail(Name(key), "expected " + key.TypeText() + " (" + key.doc + "), got " + shown + " " +
                          ScalarText(v) + ": write the number without quotes or tag");
    }
    const std::string& text = v.Scalar();
    const std::size_t digits = text.find_first_not_of("+-");
    if (digits != std::string::npos && digits <= 1 && text.size() > digits + 1 &&
        text[digits] == '0' && std::isdigit(static_cast<unsigned char>(text[digits + 1])) &&
        text.find('.') == std::string::npos) {
      Fail(Name(key), "= " + text +
                          " has a leading zero (YAML 1.1 reads it as an octal number): write the "
                          "number without it");
    }
  }

  void CheckKeys(const YAML::Node& node, const std::string& block,
                 const std::map<std::string, std::vector<std::string>>& accepted,
                 const std::set<std::string>& blocks) const {
    if (!node.IsMap()) return;
    static const std::vector<std::string> kNone;
    const auto found = accepted.find(block);
    const std::vector<std::string>& keys = found == accepted.end() ? kNone : found->second;
    for (const auto& entry : node) {
      const std::string key = entry.first.as<std::string>();
      const std::string path = block.empty() ? key : block + "." + key;
      if (std::find(keys.begin(), keys.end(), key) == keys.end()) {
        std::string list;
        for (const auto& k : keys) list += (list.empty() ? "" : ", ") + k;
        Fail("'" + path + "'", "unknown key (value " + ScalarText(entry.second) +
                                   "); accepted keys" +
                                   (block.empty() ? "" : " in '" + block + "'") + ": " + list);
      }
      if (blocks.count(path)) CheckKeys(entry.second, path, accepted, blocks);
    }
  }

  YAML::Node root_;
  std::string origin_;
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
  const std::vector<SceneModule>& modules = SceneModules();
  SceneReader reader(root, origin);
  reader.RejectUnknown(modules);
  // The last declaration of each path: where none of its declarations applied, that one refuses.
  std::map<std::string, const SceneKey*> last;
  for (const SceneModule& m : modules) {
    for (const SceneKey& k : m.keys) last[k.path] = &k;
  }
  Scene s;
  std::set<std::string> read;
  try {
    for (const SceneModule& m : modules) {
      for (const SceneKey& k : m.keys) {
        if (read.count(k.path)) continue;
        if (k.when.Holds(s)) {
          reader.Read(k, s);
          read.insert(k.path);
        } else if (last.at(k.path) == &k) {
          reader.Refuse(k);
        }
      }
      if (m.check) {
        m.check(s, [&](const std::string& message) {
          throw SceneError("scene " + origin + ": " + message);
        });
      }
    }
  } catch (const SceneError& e) {
    // A 3D scene without its `dimension: 3` is read as 2D and fails on a 2D key ('M' missing):
    // say what it looks like.
    if (s.dimension != 2 || reader.Has("dimension")) throw;
    const std::vector<std::string> evidence = reader.OnlyThreeD(modules);
    if (evidence.empty()) throw;
    std::string list;
    for (const std::string& e3 : evidence) list += (list.empty() ? "" : ", ") + e3;
    throw SceneError(
        std::string(e.what()) + "; the scene looks 3D (" + list +
        ") but has no 'dimension: 3' (the default is 2): add it, or remove those keys");
  }
  return s;
}

// The conditions the core keys apply under (a condition reads only keys declared above it).
struct CoreConditions {
  KeyCondition two_d{"2D", [](const Scene& s) { return s.dimension == 2; }};
  KeyCondition three_d{"3D", [](const Scene& s) { return s.dimension == 3; }};
  KeyCondition capsule{"capsule",
                       [](const Scene& s) { return s.membrane == MembraneKind::kCapsule; }};
  KeyCondition drop{"drop", [](const Scene& s) { return s.membrane == MembraneKind::kDrop; }};
  KeyCondition shear{"flow: shear", [](const Scene& s) { return s.has_shear(); }};
  KeyCondition no_flow{"flow: none", [](const Scene& s) { return !s.has_shear(); }};
  KeyCondition field{"with a field", [](const Scene& s) { return s.electric_field; }};
  KeyCondition no_field{"without a field", [](const Scene& s) { return !s.electric_field; }};
  KeyCondition block{"with an electric: block",
                     [](const Scene& s) { return s.values.count("electric") > 0; }};
  KeyCondition no_block{"without an electric: block",
                        [](const Scene& s) { return s.values.count("electric") == 0; }};
  KeyCondition ellipse{"shape: ellipse",
                       [](const Scene& s) { return s.geometry.shape == InitialShape::kEllipse; }};
  KeyCondition skalak{"law: skalak",
                      [](const Scene& s) { return s.law == SurfaceLawKind::kSkalak; }};
};

// Stores into a Scene field.
auto StoreNumber(double Scene::*field) {
  return [field](Scene& s, const SceneValue& v) { s.*field = v.number; };
}
auto StoreInteger(int Scene::*field) {
  return [field](Scene& s, const SceneValue& v) { s.*field = static_cast<int>(v.number); };
}
auto StoreGeometry(double SceneGeometry::*field) {
  return [field](Scene& s, const SceneValue& v) { s.geometry.*field = v.number; };
}
template <typename T>
auto StoreNumerics(T SceneNumerics::*field) {
  return [field](Scene& s, const SceneValue& v) { s.numerics.*field = static_cast<T>(v.number); };
}

SceneModule ResolutionModule(const CoreConditions& c) {
  return {
      "scene",
      "The dimension and the resolution.",
      {TextKey("name", "the scene's name (default: the file stem)")
           .Store([](Scene& s, const SceneValue& v) { s.name = v.text; }),
       TextKey("description", "one line on what the scene is")
           .Store([](Scene& s, const SceneValue& v) { s.description = v.text; }),
       IntegerKey("dimension", 2, 3, "1", "spatial dimension")
           .Default(2)
           .Store(StoreInteger(&Scene::dimension)),
       IntegerKey("N", 16, 4096, "cells", "grid cells across the domain (N^2 nodes)")
           .Required()
           .When(c.two_d, "")
           .Store(StoreInteger(&Scene::N)),
       IntegerKey("N", 16, 512, "cells",
                  "grid cells along each axis (N^3 nodes; geometry.half_length sets x and z)")
           .Required()
           .When(c.three_d, "")
           .Store(StoreInteger(&Scene::N)),
       IntegerKey("M", 8, 100000, "1", "markers on the membrane curve")
           .Required()
           .When(c.two_d, "a 3D membrane is a triangulated surface: set mesh_subdivisions instead")
           .Store(StoreInteger(&Scene::M)),
       IntegerKey("mesh_subdivisions", 1, 6, "1",
                  "icosphere subdivisions of the membrane mesh: 3 = 642, 4 = 2562, 5 = 10242 "
                  "vertices (10 4^k + 2)")
           .Required()
           .When(c.three_d, "only dimension: 3 has a triangulated membrane (2D: M)")
           .Store([](Scene& s, const SceneValue& v) {
             s.mesh_subdivisions = static_cast<int>(v.number);
             s.M = 10 * (1 << (2 * s.mesh_subdivisions)) + 2;
           })},
      {},
      {},
      {}};
}

SceneModule GeometryModule(const CoreConditions& c) {
  auto shape = [](Scene& s, const SceneValue& v) {
    s.geometry.shape = v.text == "circle"    ? InitialShape::kCircle
                       : v.text == "ellipse" ? InitialShape::kEllipse
                       : v.text == "sphere"  ? InitialShape::kSphere
                                             : InitialShape::kBiconcave;
  };
  return {
      "geometry",
      "The body's initial shape and place, and the box. With shear a body off the centre line "
      "drifts along x (periodic); the potential's box is not periodic, so with a field the run "
      "stops, naming the marker and the face, when the body comes within 1 h of an x side.",
      {BlockKey("geometry",
                "the initial shape, its place and the box: a block with shape, "
                "half_width")
           .Required(),
       ChoiceKey("geometry.shape", {"circle", "ellipse", "biconcave"},
                 "initial shape (biconcave: song2019 eq. (152))")
           .Required()
           .When(c.two_d, "")
           .Store(shape),
       ChoiceKey("geometry.shape", {"sphere", "biconcave"},
                 "initial 3D shape (biconcave: eq. (152) as a surface of revolution about y)")
           .Required()
           .When(c.three_d, "")
           .Store(shape),
       NumberKey("geometry.half_width", LeftOpen(1.0, 1000.0), "a",
                 "L / a: the domain is [-L, L]^2 (3D: the y extent, between the walls)")
           .Required()
           .Store(StoreGeometry(&SceneGeometry::half_width)),
       NumberKey("geometry.half_length", LeftOpen(1.0, 1000.0), "a",
                 "L_x / a = L_z / a, the half box along the flow and the vorticity; the grid has "
                 "round(N half_length / half_width) cells there (16 to 4096)")
           .DefaultFrom("half_width (a cube)",
                        [](const Scene& s) {
                          return SceneValue{s.geometry.half_width, {}};
                        })
           .When(c.three_d, "a 2D scene's box is [-L, L]^2 (half_width)")
           .Store(StoreGeometry(&SceneGeometry::half_length)),
       NumberKey("geometry.aspect_ratio", LeftOpen(0.0, 1.0), "1",
                 "minor / major semi-axis of the initial ellipse (x-major, area pi a^2)")
           .Required()
           .When(c.ellipse, "only shape: ellipse has an aspect ratio")
           .Store(StoreGeometry(&SceneGeometry::aspect_ratio)),
       NumberKey("geometry.center_x", Closed(-1000, 1000), "a", "initial x offset of the centre")
           .Default(0.0)
           .Store(StoreGeometry(&SceneGeometry::center_x)),
       NumberKey("geometry.center_y", Closed(-1000, 1000), "a", "initial y offset of the centre")
           .Default(0.0)
           .Store(StoreGeometry(&SceneGeometry::center_y)),
       NumberKey("geometry.center_z", Closed(-1000, 1000), "a", "initial z offset of the centre")
           .Default(0.0)
           .When(c.three_d, "a 2D scene has no z axis")
           .Otherwise(0.0)
           .Store(StoreGeometry(&SceneGeometry::center_z))},
      {},
      {},
      {}};
}

SceneModule MembraneModule(const CoreConditions& c) {
  return {
      "membrane",
      "The membrane's law and the inner fluid. T below is the scene's tension scale: E_s for a 2D "
      "capsule, the shear modulus G_s for a 3D capsule (song2019 and Ramanujan & Pozrikidis "
      "write "
      "E_s = 3 G_s; docs/validation_3d.md), gamma for a drop.",
      {ChoiceKey("membrane", {"capsule", "drop"},
                 "membrane model: capsule (2D: Hookean E_s, plus Kelvin-Voigt when eta > 0 and "
                 "bending when E_b > 0; 3D: `law`) or drop (interfacial tension gamma)")
           .Required()
           .Store([](Scene& s, const SceneValue& v) {
             s.membrane = v.text == "drop" ? MembraneKind::kDrop : MembraneKind::kCapsule;
           }),
       ChoiceKey("law", {"neo_hookean", "zero_thickness", "skalak"},
                 "3D membrane law (song2019 eqs. (137)-(139); membrane/surface_elasticity.h)")
           .Required()
           .When(c.three_d && c.capsule,
                 "only a 3D capsule has a finite-element law (a drop has a surface tension only; "
                 "a 2D capsule has its own: Hookean fibre, E_b, eta)")
           .Store([](Scene& s, const SceneValue& v) {
             s.law = v.text == "skalak"           ? SurfaceLawKind::kSkalak
                     : v.text == "zero_thickness" ? SurfaceLawKind::kZeroThickness
                                                  : SurfaceLawKind::kNeoHookean;
           }),
       NumberKey("C", LeftOpen(0.0, 1e6), "1",
                 "Skalak area-dilation to shear modulus ratio (song2019: 15 for the red cell)")
           .Required()
           .When(c.three_d && c.capsule && c.skalak,
                 "only law: skalak has an area-dilation modulus")
           .Store(StoreNumber(&Scene::area_dilation)),
       NumberKey("c0", Closed(-100.0, 100.0), "1/a",
                 "spontaneous curvature times a (Helfrich bending, eq. (144))")
           .Default(0.0)
           .When(c.three_d && c.capsule, "only a 3D capsule has a spontaneous curvature")
           .Otherwise(0.0)
           .Store(StoreNumber(&Scene::c0)),
       NumberKey("E_b", Closed(0.0, 10.0), "1", "bending modulus E_B / (a^2 T), eq. (120)")
           .Required()
           .When(c.capsule, "a drop has no bending (needs membrane: capsule)")
           .Otherwise(0.0)
           .Store(StoreNumber(&Scene::E_b)),
       NumberKey("eta", Closed(0.0, 100.0), "1",
                 "membrane viscosity mu_s / (a mu), eq. (121) (Kelvin-Voigt)")
           .Required()
           .When(c.two_d && c.capsule,
                 "membrane viscosity is built for 2D capsules only (a drop has none; 3D not yet)")
           .Otherwise(0.0)
           .Store(StoreNumber(&Scene::eta)),
       NumberKey("prestress", Closed(0.0, 10.0), "1",
                 "isotropic pre-tension tau_p / E_s: tau = tau_p + E_s (lambda - 1) (not in "
                 "song2019)")
           .Default(0.0)
           .When(c.two_d && c.capsule,
                 "a prestress is built for 2D capsules only (a drop has none; 3D not yet)")
           .Otherwise(0.0)
           .Store(StoreNumber(&Scene::prestress)),
       NumberKey("V", Closed(0.01, 100.0), "1", "viscosity ratio mu_inside / mu_outside (sec. 5.4)")
           .Required()
           .When(c.two_d, "a viscosity contrast is not built in 3D yet")
           .Otherwise(1.0)
           .Store(StoreNumber(&Scene::V))},
      {"membrane", "viscosity (V != 1)"},
      {"the membrane force source; D, theta, the area or volume drift in the state and CSV"},
      {}};
}

SceneModule FlowModule(const CoreConditions& c) {
  return {
      "flow",
      "The imposed flow and the time scale.",
      {ChoiceKey("flow", {"shear", "none"},
                 "imposed flow: shear (walls at y = +-L moving at +-k L, fluid initially "
                 "u = (k y, 0), periodic in x) or none (closed box at rest)")
           .Required()
           .Store([](Scene& s, const SceneValue& v) {
             s.flow = v.text == "none" ? FlowKind::kNone : FlowKind::kShear;
           }),
       NumberKey("Ca", LeftOpen(0.0, 10.0), "1", "capillary number mu k a / T, eq. (119)")
           .Required()
           .When(c.shear, "there is no shear rate with flow: none (use Oh)")
           .Store(StoreNumber(&Scene::Ca)),
       NumberKey("Re", LeftOpen(0.0, 100.0), "1", "Reynolds number rho k a^2 / mu (sec. 4.1: 0.05)")
           .Required()
           .When(c.shear, "there is no shear rate with flow: none (use Oh)")
           .Store(StoreNumber(&Scene::Re)),
       NumberKey("max_Ca", LeftOpen(0.0, 10.0), "1",
                 "largest Ca accepted at run time (SetCa, the node's live Ca): the scene's "
                 "measured limit; the scene's own Ca must not exceed it")
           .Default(10.0)
           .When(c.shear, "there is no shear rate with flow: none")
           .Store(StoreNumber(&Scene::max_Ca)),
       NumberKey("Oh", LeftOpen(0.0, 100.0), "1",
                 "Ohnesorge number mu / sqrt(rho a T) (sec. 4.2.2: 1)")
           .Required()
           .When(c.no_flow, "Oh sets the time scale only without shear (flow: none); use Ca and Re")
           .Store(StoreNumber(&Scene::Oh))},
      {"fluid"},
      {"the velocity field (~field), Ca in the state"},
      [](const Scene& s, const SceneFail& fail) {
        if (s.has_shear() && s.Ca > s.max_Ca) {
          fail("'Ca' = " + FormatNumber(s.Ca) + " is out of range: accepted (0, " +
               FormatNumber(s.max_Ca) + "] (max_Ca)");
        }
      }};
}

SceneModule ElectricModule(const CoreConditions& c) {
  const KeyCondition ac{"waveform: ac",
                        [](const Scene& s) { return s.electric.waveform == FieldWaveform::kAc; }};
  const KeyCondition pulses{"waveform: pulses", [](const Scene& s) {
                              return s.electric.waveform == FieldWaveform::kPulses;
                            }};
  auto store_ca_e = [](Scene& s, const SceneValue& v) {
    s.Ca_E = v.number;
    s.electric_field = s.Ca_E > 0.0 || s.values.count("electric") > 0;
  };
  return {
      "electric",
      "The leaky-dielectric field (song2019 sec. 4.2, ch. 6): built iff Ca_E > 0 or an electric: "
      "block is present (an empty block with Ca_E: 0 builds it off, to be turned up live). 2D: "
      "E_inf along y; 3D: along z, phi = E z on the z faces, Neumann on the others.",
      {BlockKey("electric", "the field's run-time limits; its presence builds the field"),
       NumberKey("electric.max_Ca_E", LeftOpen(0.0, 100.0), "1",
                 "largest Ca_E accepted at run time (SetCaE, dynamic_reconfigure)")
           .Default(5.0)
           .Store([](Scene& s, const SceneValue& v) { s.electric.max_ca_e = v.number; }),
       NumberKey("electric.max_fit_disagreement", LeftOpen(0.0, 1.0), "1",
                 "the interface solver refuses a potential whose cubic and quadratic fits of "
                 "phi_n^- differ by more than this fraction of max |phi_n| (unresolved near the "
                 "interface; docs/electric_solver.md, Guarantees); raise it only for a "
                 "qualitative run on a grid known to be too coarse; absent: the solver's "
                 "default, 0.1")
           .Store([](Scene&, const SceneValue&) {}),  // read by the electric stage
       NumberKey("Ca_E", Closed(0.0, 100.0), "1",
                 "electric capillary number eps+ a E^2 / T (sec. 4.2.2, 5.1; required with an "
                 "electric: block: 0 starts the field off, to be turned up live)")
           .Required()
           .When(c.block, "")
           .Store(store_ca_e),
       NumberKey("Ca_E", Closed(0.0, 100.0), "1",
                 "electric capillary number eps+ a E^2 / T (sec. 4.2.2, 5.1)")
           .Default(0.0)
           .When(c.no_block, "")
           .Store(store_ca_e),
       ChoiceKey("electric.waveform", {"dc", "ac", "pulses"},
                 "the field's time dependence E(t) = E f(t), E from Ca_E: dc f = 1; ac f = "
                 "offset + cos(2 pi frequency t + phase); pulses f = 1 for pulse_width of each "
                 "pulse_period, else 0 (issue #45; quasi-static: below the charge relaxation "
                 "frequency)")
           .Default("dc")
           .Store([](Scene& s, const SceneValue& v) {
             s.electric.waveform = v.text == "ac"       ? FieldWaveform::kAc
                                   : v.text == "pulses" ? FieldWaveform::kPulses
                                                        : FieldWaveform::kDc;
           }),
       NumberKey("electric.frequency", LeftOpen(0.0, 1e6), "1/t",
                 "ac: cycles per unit of time (1/k with shear, else mu a / T); a period must "
                 "span at least 20 lattice steps")
           .Required()
           .When(ac, "only electric.waveform: ac has it")
           .Store([](Scene& s, const SceneValue& v) { s.electric.frequency = v.number; }),
       NumberKey("electric.phase", Closed(-10.0, 10.0), "rad", "ac: the phase at t = 0")
           .Default(0.0)
           .When(ac, "only electric.waveform: ac has it")
           .Store([](Scene& s, const SceneValue& v) { s.electric.phase = v.number; }),
       NumberKey("electric.offset", Closed(-10.0, 10.0), "1",
                 "ac: the DC offset in units of the amplitude")
           .Default(0.0)
           .When(ac, "only electric.waveform: ac has it")
           .Store([](Scene& s, const SceneValue& v) { s.electric.offset = v.number; }),
       NumberKey("electric.pulse_width", LeftOpen(0.0, 1e6), "t",
                 "pulses: the time the field is on in each period, from its start (at least 4 "
                 "lattice steps)")
           .Required()
           .When(pulses, "only electric.waveform: pulses has it")
           .Store([](Scene& s, const SceneValue& v) { s.electric.pulse_width = v.number; }),
       NumberKey("electric.pulse_period", LeftOpen(0.0, 1e6), "t",
                 "pulses: the time from one pulse's start to the next's (>= pulse_width)")
           .Required()
           .When(pulses, "only electric.waveform: pulses has it")
           .Store([](Scene& s, const SceneValue& v) { s.electric.pulse_period = v.number; }),
       IntegerKey("electric.pulse_count", 0, 1000000000, "1",
                  "pulses: how many (0: a train without end)")
           .Default(0)
           .When(pulses, "only electric.waveform: pulses has it")
           .Store([](Scene& s, const SceneValue& v) {
             s.electric.pulse_count = static_cast<int>(v.number);
           }),
       NumberKey("sigma_r", Closed(1e-4, 1000.0), "1",
                 "conductivity ratio sigma- / sigma+ (inside / outside); at most the immersed "
                 "interface solver's max_inner_ratio, in both dimensions "
                 "(docs/electric_solver.md)")
           .Required()
           .When(c.field, "")
           .Store(StoreNumber(&Scene::sigma_r)),
       NumberKey("sigma_r", Closed(1e-4, 1e4), "1",
                 "conductivity ratio (read so that --set Ca_E=... can switch the field on)")
           .Default(1.0)
           .When(c.no_field, "")
           .Store(StoreNumber(&Scene::sigma_r)),
       NumberKey("eps_r", Closed(1e-4, 1e4), "1",
                 "permittivity ratio eps- / eps+ (inside / outside)")
           .Required()
           .When(c.field, "")
           .Store(StoreNumber(&Scene::eps_r)),
       NumberKey("eps_r", Closed(1e-4, 1e4), "1", "permittivity ratio (as sigma_r)")
           .Default(1.0)
           .When(c.no_field, "")
           .Store(StoreNumber(&Scene::eps_r))},
      {"electric"},
      {"the electric force source; fe_x, fe_y (fe_z), d_field, gmres_iterations, the potential "
       "(~field potential)"},
      [](const Scene& s, const SceneFail& fail) {
        if (s.electric_field && s.Ca_E > s.electric.max_ca_e) {
          fail("'Ca_E' = " + FormatNumber(s.Ca_E) + " is out of range: accepted [0, " +
               FormatNumber(s.electric.max_ca_e) + "] (electric.max_Ca_E)");
        }
        if (s.electric.waveform == FieldWaveform::kPulses &&
            s.electric.pulse_width > s.electric.pulse_period) {
          fail(
              "'electric.pulse_width' = " + FormatNumber(s.electric.pulse_width) +
              " is longer than 'electric.pulse_period' = " + FormatNumber(s.electric.pulse_period));
        }
      }};
}

SceneModule NumericsModule(const CoreConditions& c) {
  auto integrator = [](Scene& s, const SceneValue& v) {
    s.numerics.integrator = v.text == "adams_bashforth2" ? MarkerTimeScheme::kAdamsBashforth2
                                                         : MarkerTimeScheme::kForwardEuler;
  };
  const KeyCondition drop_3d = c.three_d && c.drop;
  return {
      "numerics",
      "The lattice, the markers' time integration, the electric re-solve policy, the watchdogs.",
      {BlockKey("numerics", "numerical settings (all optional)"),
       NumberKey("numerics.tau", LeftOpen(0.5, 20.0), "1",
                 "LBM relaxation time of the outer fluid, nu = (tau - 1/2) / 3")
           .Default(1.0)
           .Store(StoreNumerics(&SceneNumerics::tau)),
       ChoiceKey("numerics.integrator", {"forward_euler", "adams_bashforth2"},
                 "marker time integration (2D tables were made with forward Euler)")
           .Default("forward_euler")
           .When(c.two_d, "")
           .Store(integrator),
       ChoiceKey("numerics.integrator", {"forward_euler", "adams_bashforth2"},
                 "vertex time integration (Euler's outward drift of a tank-treading vertex "
                 "inflated sphere_shear by 7e-5 per time unit, AB2's by 2e-5)")
           .Default("adams_bashforth2")
           .When(c.three_d, "")
           .Store(integrator),
       IntegerKey("numerics.membrane_substeps", 1, 1000, "1",
                  "time-step refinement n for a stiff membrane: nu -> nu / n, k -> k / n, n "
                  "times the steps per time unit")
           .Default(1)
           .Store(StoreNumerics(&SceneNumerics::membrane_substeps)),
       IntegerKey("numerics.electric_every", 1, 1000000, "steps",
                  "with a field: solve the potential every n steps (docs/validation_ehd.md sec. 5)")
           .Default(1)
           .Store(StoreNumerics(&SceneNumerics::electric_every)),
       NumberKey("numerics.electric_move_tolerance", Closed(0.0, 10.0), "cells",
                 "with a field: ... or as soon as a marker moved more than this since the last "
                 "solve; 0 = off")
           .Default(0.0)
           .Store(StoreNumerics(&SceneNumerics::electric_move_tolerance)),
       NumberKey("numerics.electric_shape_tolerance", Closed(0.0, 1.0), "cells",
                 "with a field: re-interpolate the last solve's traction at moved vertices while "
                 "the surface stays within this distance of that solve's surface (tank-treading); "
                 "0 = off (docs/validation_3d_ehd.md)")
           .Default(0.0)
           .When(c.three_d, "built in 3D only")
           .Otherwise(0.0)
           .Store(StoreNumerics(&SceneNumerics::electric_shape_tolerance)),
       IntegerKey("numerics.max_steps", 1, 1000000000000L, "steps", "step cap of `ehd_sim run`")
           .Default(1000000)
           .Store(StoreNumerics(&SceneNumerics::max_steps)),
       NumberKey("numerics.t_end", LeftOpen(0.0, 1e6), "time unit",
                 "default run length, in the scene's time unit (1/k with shear, mu a / T without)")
           .Default(10.0)
           .Store(StoreNumerics(&SceneNumerics::t_end)),
       NumberKey("numerics.area_drift_limit", LeftOpen(0.0, 1.0), "1",
                 "watchdog on |A/A0 - 1| (3D: the volume)")
           .Default(0.05)
           .Store(StoreNumerics(&SceneNumerics::area_drift_limit)),
       NumberKey("numerics.max_mach", LeftOpen(0.0, 0.5), "1",
                 "watchdog on the lattice Mach number |u| / c_s")
           .Default(0.1)
           .Store(StoreNumerics(&SceneNumerics::max_mach)),
       IntegerKey("numerics.threads", 0, 256, "1",
                  "LBM OpenMP threads, 0 = OpenMP default (1 is often faster for N <= 128 on a "
                  "shared machine)")
           .Default(0)
           .Store(StoreNumerics(&SceneNumerics::threads)),
       NumberKey("numerics.redistribute_markers", Closed(0.0, 1e6), "1",
                 "0 (off) or a spacing ratio r > 1: when the largest / smallest marker spacing "
                 "exceeds r the markers are re-spaced evenly along the curve (docs/coupling.md)")
           .Default(0.0)
           .When(c.two_d && c.drop,
                 "2D drops only (a capsule's markers are material points of its elastic "
                 "reference; a 3D drop's mesh is relaxed along its surface every "
                 "numerics.relax_mesh_every steps)")
           .Otherwise(0.0)
           .Store(StoreNumerics(&SceneNumerics::redistribute_markers)),
       ChoiceKey("numerics.ib_kernel", {"cosine", "roma3", "trapezoid3", "roma3_even_odd"},
                 "the immersed boundary's discrete delta: cosine (song2019 eq. (103), 4 nodes per "
                 "axis), roma3 (Roma, Peskin & Berger 1999, 3 nodes; ib/delta_kernel.h, "
                 "docs/validation_3d.md \"The kernel\"), trapezoid3 (3 nodes with the even-odd "
                 "condition) or roma3_even_odd (trapezoid3 along each component's own axis, "
                 "roma3 along the others; docs/validation_3d.md \"Damping the grid-Nyquist "
                 "mode\")")
           .Default("cosine")
           .Store([](Scene& s, const SceneValue& v) { s.numerics.ib_kernel = v.text; }),
       NumberKey("numerics.ib_retraction", Closed(0.0, 1.5), "cells",
                 "spread the force and interpolate the velocity at the points moved inward along "
                 "their normals by this distance (calibrated per kernel on a spherical capsule's "
                 "exact small-Ca deformation and rotation; coupling/retracted_points.h, "
                 "docs/validation_3d.md); 0 = at the points (song2019)")
           .DefaultFrom("0.5 (cosine), 0.37 (roma3), 0.58 (trapezoid3), 0.33 (roma3_even_odd)",
                        [](const Scene& s) {
                          const std::string& k = s.numerics.ib_kernel;
                          return SceneValue{k == "roma3"            ? 0.37
                                            : k == "trapezoid3"     ? 0.58
                                            : k == "roma3_even_odd" ? 0.33
                                                                    : 0.5,
                                            {}};
                        })
           .Store(StoreNumerics(&SceneNumerics::ib_retraction)),
       IntegerKey("numerics.ib_extrapolate_velocity", 0, 1, "1",
                  "with numerics.ib_retraction > 0: 1 = move the membrane with the velocity "
                  "extrapolated to its own position by the body's velocity gradient, 0 = with the "
                  "velocity at the retracted points (tank-treads slower by (a - delta)/a)")
           .Default(1)
           .Store(StoreNumerics(&SceneNumerics::ib_extrapolate_velocity)),
       IntegerKey("numerics.marker_filter_every", 0, 1000000000, "steps",
                  "2D: remove the markers' sawtooth mode every n steps (ib/sawtooth_filter.h); "
                  "3D: the mesh-scale part of the deformation (ib/mesh_scale_filter.h); 0 = off "
                  "(docs/coupling.md, \"Long runs\")")
           .Default(100)
           .Store(StoreNumerics(&SceneNumerics::marker_filter_every)),
       IntegerKey("numerics.mesh_filter_order", 1, 32, "1",
                  "order p of the mesh-scale filter's high-pass (A/mu_max)^p; lower removes "
                  "longer modes (ib/mesh_scale_filter.h)")
           .Default(8)
           .When(c.three_d, "3D only (2D filters the markers' sawtooth mode, ib/sawtooth_filter.h)")
           .Otherwise(8)
           .Store(StoreNumerics(&SceneNumerics::mesh_filter_order)),
       IntegerKey("numerics.volume_correction_every", 0, 1000000000, "steps",
                  "restore the enclosed volume every n steps by a uniform normal displacement of "
                  "the vertices (the immersed boundary's leak); 0 = off")
           .Default(0)
           .When(c.three_d,
                 "3D only (the 2D markers' area leak is 1e-5 per unit: "
                 "docs/validation_3d.md)")
           .Otherwise(0)
           .Store(StoreNumerics(&SceneNumerics::volume_correction_every)),
       IntegerKey("numerics.relax_mesh_every", 0, 1000000000, "steps",
                  "relax a drop's vertices along its surface every n steps "
                  "(geometry/mesh_relaxation.h); 0 = off")
           .Default(100)
           .When(drop_3d,
                 "needs dimension: 3 and membrane: drop (a capsule's vertices are material points "
                 "of its elastic reference; a 2D drop uses numerics.redistribute_markers)")
           .Otherwise(0)
           .Store(StoreNumerics(&SceneNumerics::relax_mesh_every))},
      {"marker", "diagnostics"},
      {"the CSV and state columns of every scene (docs/scenes.md)"},
      [](const Scene& s, const SceneFail& fail) {
        const double r = s.numerics.redistribute_markers;
        if (r != 0.0 && r <= 1.0) {
          fail("'numerics.redistribute_markers' = " + FormatNumber(r) +
               " is out of range: 0 (off) or a spacing ratio > 1");
        }
      }};
}

// The scene library's own modules, in the order their keys are read.
std::vector<SceneModule> CoreModules() {
  const CoreConditions c;
  return {ResolutionModule(c), GeometryModule(c), MembraneModule(c),
          FlowModule(c),       ElectricModule(c), NumericsModule(c)};
}

}  // namespace

std::vector<SceneModule> CoreSceneModules() { return CoreModules(); }

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

double Scene::Number(const std::string& path) const {
  const auto it = values.find(path);
  if (it == values.end()) {
    throw std::logic_error("scene " + name + ": key '" + path +
                           "' was not read (not declared, "
                           "or it does not apply to this scene)");
  }
  return it->second.number;
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

namespace {

// Limits on a scene's YAML tree with aliases expanded: a shipped scene has about a hundred nodes
// and 3 levels, while nested aliases (a: &a [x, x], b: &b [*a, *a], ...) grow it exponentially
// and an alias inside its own anchor (a: &a [*a]) makes it endless.
constexpr long kMaxSceneNodes = 100000;
constexpr int kMaxSceneDepth = 64;

// yaml-cpp keeps both pairs of a repeated key and lookups return the first, so a scene that
// sets a key twice would silently ignore the second value: refuse it, naming both lines. Also
// refuses a key that is not a name (a list or a block) and a tree beyond the limits above.
void RejectDuplicateKeys(const YAML::Node& node, const std::string& prefix,
                         const std::string& origin, int depth, long& nodes) {
  if (++nodes > kMaxSceneNodes) {
    throw SceneError("scene " + origin + ": more than " + std::to_string(kMaxSceneNodes) +
                     " YAML nodes with aliases (*name) expanded (a scene has about a hundred): "
                     "refused");
  }
  if (depth > kMaxSceneDepth) {
    throw SceneError("scene " + origin + ": YAML nested deeper than " +
                     std::to_string(kMaxSceneDepth) + " levels at '" +
                     prefix.substr(0, prefix.size() - 1) +
                     "' (aliases expanded; a scene has 3): refused");
  }
  if (node.IsSequence()) {
    for (const auto& item : node) RejectDuplicateKeys(item, prefix, origin, depth + 1, nodes);
    return;
  }
  if (!node.IsMap()) return;
  std::map<std::string, int> first_line;
  for (auto it = node.begin(); it != node.end(); ++it) {
    const int line = it->first.Mark().line + 1;
    if (!it->first.IsScalar()) {
      throw SceneError("scene " + origin + ": line " + std::to_string(line) + ": a key " +
                       (prefix.empty() ? "at the top level"
                                       : "in '" + prefix.substr(0, prefix.size() - 1) + "'") +
                       " is " + ScalarText(it->first) + ", not a name");
    }
    const std::string key = it->first.Scalar();
    const auto [seen, inserted] = first_line.emplace(key, line);
    if (!inserted) {
      throw SceneError("scene " + origin + ": key '" + prefix + key + "' is given twice (lines " +
                       std::to_string(seen->second) + " and " + std::to_string(line) +
                       "); keep one");
    }
    RejectDuplicateKeys(it->second, prefix + key + ".", origin, depth + 1, nodes);
  }
}

}  // namespace

Scene ParseScene(const std::string& yaml_text, const std::vector<std::string>& overrides,
                 const std::string& origin) {
  std::vector<YAML::Node> documents;
  try {
    documents = YAML::LoadAll(yaml_text);
  } catch (const YAML::DeepRecursion& e) {  // yaml-cpp's own limit says only "bad file"
    throw SceneError("scene " + origin + ": YAML nested deeper than " + std::to_string(e.depth()) +
                     " levels at line " + std::to_string(e.mark.line + 1) + ": refused");
  } catch (const YAML::Exception& e) {
    throw SceneError("scene " + origin + ": not valid YAML: " + e.what());
  }
  // A second document (after '---') would be ignored; an empty one (a trailing '---') is not.
  for (std::size_t i = 1; i < documents.size(); ++i) {
    if (documents[i].IsNull()) continue;
    throw SceneError("scene " + origin + ": a second YAML document at line " +
                     std::to_string(documents[i].Mark().line + 1) +
                     " (after '---'): one document per scene file");
  }
  YAML::Node root = documents.empty() ? YAML::Node() : documents.front();
  if (root.IsNull()) root = YAML::Node(YAML::NodeType::Map);
  if (!root.IsMap()) throw SceneError("scene " + origin + ": expected a block of key: value lines");
  long nodes = 0;
  RejectDuplicateKeys(root, "", origin, 0, nodes);
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
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) {
    throw SceneError("scene '" + name_or_path + "': " + path +
                     " is a directory, not a scene file (.yaml)");
  }
  std::ifstream in(path);
  if (!in) {
    std::string known;
    for (const auto& n : ListScenes()) known += (known.empty() ? "" : ", ") + n;
    std::string where;
    if (is_path && !path.empty() && path.front() != '/') {
      where = " (a relative path, resolved from " + std::filesystem::current_path(ec).string() +
              "; roslaunch runs nodes in ROS_HOME: give an absolute path)";
    }
    throw SceneError("scene '" + name_or_path + "': cannot read " + path + where +
                     (is_path ? "" : " (shipped scenes: " + known + ")"));
  }
  // Read at most kMaxSceneBytes (+1 to tell): /dev/zero or a huge file is refused, not read.
  constexpr std::size_t kMaxSceneBytes = 1 << 20;
  std::string text(kMaxSceneBytes + 1, '\0');
  in.read(&text[0], static_cast<std::streamsize>(text.size()));
  text.resize(static_cast<std::size_t>(in.gcount()));
  if (text.size() > kMaxSceneBytes) {
    throw SceneError("scene '" + name_or_path + "': " + path + " is larger than " +
                     std::to_string(kMaxSceneBytes) + " bytes (a scene file has a few hundred)");
  }
  Scene scene = ParseScene(text, overrides, path);
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
