// The scene keys, declared by the modules that own them (docs/architecture.md, "Modules").
//
// A module (the box, the flow, the membrane, the electric field, the numerics, or a physics module
// outside the scene library such as a force term) declares in one place each of its keys: its
// path ("numerics.tau"), type (a number, an integer, one of a list of words, text, a block), its
// range, units, default or that it is required, where it applies (a condition on the keys read
// before it: "3D", "capsule", "with a field", ...) and why it is refused elsewhere, and one doc
// line; plus the stages it builds and what it publishes. LoadScene reads the scene from these
// declarations alone (scene.cpp), and `ehd_sim keys --markdown` prints them as the key table of
// docs/scene_keys.md (a test fails when that file and the declarations disagree).
//
// Rules every key follows (so a scene means what it says):
//   - a required key that is missing is an error, a key given twice is an error, an unknown key
//     is an error listing the keys accepted there;
//   - an integer key refuses 3.5, a number refuses text, a choice refuses any other word;
//   - a scalar key written with no value (`Ca:`, YAML null) is an error, not its default: delete
//     the line for the default; a block may be empty (`electric:` or `electric: {}`);
//   - where a key does not apply it is refused with its reason, except for the one value
//     (`otherwise`) that means "off" there (eta: 0 in 3D, V: 1 in 3D, ...).
// Several declarations may share a path under disjoint conditions (N in 2D and in 3D): the first
// whose condition holds is read.
#pragma once

#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace ehd {

struct Scene;

// An interval of accepted values, printed as "(0, 10]".
struct KeyRange {
  double lo = 0;
  double hi = 0;
  bool lo_open = false;
  bool hi_open = false;
  bool Contains(double v) const {
    return (lo_open ? v > lo : v >= lo) && (hi_open ? v < hi : v <= hi);
  }
  std::string Text() const;
};
inline KeyRange Closed(double lo, double hi) { return {lo, hi, false, false}; }
inline KeyRange LeftOpen(double lo, double hi) { return {lo, hi, true, false}; }

// Where a key applies: a test on the scene as read so far (the keys declared before it), and
// its text for the table and the messages ("" and no test: everywhere).
struct KeyCondition {
  std::string text;
  std::function<bool(const Scene&)> holds;
  bool Holds(const Scene& s) const { return !holds || holds(s); }
};
// Both conditions ("3D, capsule").
KeyCondition operator&&(const KeyCondition& a, const KeyCondition& b);

// The value of one key as read: a number (integers too) or a word / text.
struct SceneValue {
  double number = 0;
  std::string text;
};

enum class KeyType { kNumber, kInteger, kChoice, kText, kBlock };

struct SceneKey {
  std::string path;  // "Ca", "numerics.tau"; a block: "numerics"
  KeyType type = KeyType::kNumber;
  KeyRange range;                    // numbers and integers
  std::vector<std::string> choices;  // kChoice
  std::string units;                 // "1" (dimensionless), "a", "cells", "steps", ...
  std::string doc;                   // one line: what it is, the equation it comes from
  bool required = false;
  std::optional<SceneValue> fallback;  // the default where not given (not with required)
  // A default that depends on keys read before (half_length: half_width); its text for the table.
  std::function<SceneValue(const Scene&)> fallback_from;
  std::string fallback_text;
  KeyCondition when;                    // where it applies
  std::string refusal;                  // why it is refused where `when` does not hold
  std::optional<SceneValue> otherwise;  // the one value accepted where it does not apply
  std::function<void(Scene&, const SceneValue&)> store;  // into the Scene's fields (core keys)

  // Builders, so a declaration reads as one line of the table.
  SceneKey& Required() { return required = true, *this; }
  SceneKey& Default(double v) { return fallback = SceneValue{v, {}}, *this; }
  SceneKey& Default(const std::string& word) { return fallback = SceneValue{0, word}, *this; }
  SceneKey& DefaultFrom(std::string text, std::function<SceneValue(const Scene&)> f) {
    fallback_text = std::move(text);
    fallback_from = std::move(f);
    return *this;
  }
  SceneKey& When(KeyCondition c, std::string why_not) {
    when = std::move(c);
    refusal = std::move(why_not);
    return *this;
  }
  SceneKey& Otherwise(double v) { return otherwise = SceneValue{v, {}}, *this; }
  SceneKey& Store(std::function<void(Scene&, const SceneValue&)> f) {
    store = std::move(f);
    return *this;
  }
  std::string TypeText() const;     // "a number in (0, 10]", "one of circle | ellipse", ...
  std::string DefaultText() const;  // "required", "1", "half_width", "" (blocks)
};

SceneKey NumberKey(std::string path, KeyRange range, std::string units, std::string doc);
SceneKey IntegerKey(std::string path, long lo, long hi, std::string units, std::string doc);
SceneKey ChoiceKey(std::string path, std::vector<std::string> choices, std::string doc);
SceneKey TextKey(std::string path, std::string doc);
SceneKey BlockKey(std::string path, std::string doc);

// A module's check reports through this (it throws SceneError; the message is given without the
// "scene <origin>: " prefix).
using SceneFail = std::function<void(const std::string& message)>;

struct SceneModule {
  std::string name;  // "box", "flow", "membrane", "electric", "numerics", "stretch", ...
  std::string doc;   // one line
  std::vector<SceneKey> keys;
  std::vector<std::string> stages;     // the coupled-step stages it builds (docs)
  std::vector<std::string> publishes;  // what it adds to the state, CSV, topics (docs)
  // Checks between its keys after they are read (Ca <= max_Ca, ...): throw through `fail`.
  std::function<void(const Scene&, const SceneFail& fail)> check;
};

// The modules in the order their keys are read: the scene library's own (CoreSceneModules,
// scene.cpp) first, then those registered from other libraries (force terms), in registration
// order.
const std::vector<SceneModule>& SceneModules();
std::vector<SceneModule> CoreSceneModules();
// The first declaration of a key (its range, for messages that name the key's limits); throws
// std::logic_error when no module declares it.
const SceneKey& DeclaredSceneKey(const std::string& path);
// Adds a module (at static initialisation: a force term's file registers itself). Throws
// std::logic_error when one of its keys is declared already by another module.
bool RegisterSceneModule(SceneModule module);

// The key table (docs/scene_keys.md): one section per module, one row per declaration.
std::string SceneKeysMarkdown();

}  // namespace ehd
