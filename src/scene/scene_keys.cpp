// Scene key declarations: builders, the module registry and the generated key table
// (scene/scene_keys.h). The reading itself is in scene.cpp.
#include "ehd_capsule/scene/scene_keys.h"

#include <map>
#include <set>
#include <sstream>
#include <stdexcept>

#include "ehd_capsule/scene/scene.h"

namespace ehd {
namespace {

std::string Format(double v) {
  std::ostringstream out;
  out << v;
  return out.str();
}

std::string ValueText(const SceneKey& key, const SceneValue& v) {
  if (key.type == KeyType::kChoice || key.type == KeyType::kText) return v.text;
  return Format(v.number);
}

std::vector<SceneModule>& AllModules() {
  static std::vector<SceneModule> modules = CoreSceneModules();
  return modules;
}

// Markdown table cells must not break the row.
std::string Cell(std::string text) {
  std::string out;
  for (char c : text) {
    if (c == '|') {
      out += "\\|";
    } else if (c == '\n') {
      out += ' ';
    } else {
      out += c;
    }
  }
  return out;
}

}  // namespace

std::string KeyRange::Text() const {
  return std::string(lo_open ? "(" : "[") + Format(lo) + ", " + Format(hi) + (hi_open ? ")" : "]");
}

KeyCondition operator&&(const KeyCondition& a, const KeyCondition& b) {
  KeyCondition c;
  c.text = a.text.empty() ? b.text : b.text.empty() ? a.text : a.text + ", " + b.text;
  c.holds = [a, b](const Scene& s) { return a.Holds(s) && b.Holds(s); };
  return c;
}

std::string SceneKey::TypeText() const {
  switch (type) {
    case KeyType::kNumber:
      return "a number in " + range.Text();
    case KeyType::kInteger:
      return "an integer in " + range.Text();
    case KeyType::kChoice: {
      std::string list;
      for (const auto& c : choices) list += (list.empty() ? "" : " | ") + c;
      return "one of " + list;
    }
    case KeyType::kText:
      return "text";
    case KeyType::kBlock:
      return "a block";
  }
  return "?";
}

std::string SceneKey::DefaultText() const {
  if (required) return "required";
  if (fallback) return ValueText(*this, *fallback);
  if (fallback_from) return fallback_text;
  return "optional";
}

SceneKey NumberKey(std::string path, KeyRange range, std::string units, std::string doc) {
  SceneKey k;
  k.path = std::move(path);
  k.type = KeyType::kNumber;
  k.range = range;
  k.units = std::move(units);
  k.doc = std::move(doc);
  return k;
}

SceneKey IntegerKey(std::string path, long lo, long hi, std::string units, std::string doc) {
  SceneKey k = NumberKey(std::move(path), Closed(static_cast<double>(lo), static_cast<double>(hi)),
                         std::move(units), std::move(doc));
  k.type = KeyType::kInteger;
  return k;
}

SceneKey ChoiceKey(std::string path, std::vector<std::string> choices, std::string doc) {
  SceneKey k;
  k.path = std::move(path);
  k.type = KeyType::kChoice;
  k.choices = std::move(choices);
  k.doc = std::move(doc);
  return k;
}

SceneKey TextKey(std::string path, std::string doc) {
  SceneKey k;
  k.path = std::move(path);
  k.type = KeyType::kText;
  k.doc = std::move(doc);
  return k;
}

SceneKey BlockKey(std::string path, std::string doc) {
  SceneKey k;
  k.path = std::move(path);
  k.type = KeyType::kBlock;
  k.doc = std::move(doc);
  return k;
}

const std::vector<SceneModule>& SceneModules() { return AllModules(); }

const SceneKey& DeclaredSceneKey(const std::string& path) {
  for (const SceneModule& m : SceneModules()) {
    for (const SceneKey& k : m.keys) {
      if (k.path == path) return k;
    }
  }
  throw std::logic_error("scene key '" + path + "' is not declared");
}

bool RegisterSceneModule(SceneModule module) {
  std::vector<SceneModule>& modules = AllModules();
  std::set<std::string> own;
  for (const SceneKey& k : module.keys) own.insert(k.path);
  for (const SceneModule& m : modules) {
    if (m.name == module.name) {
      throw std::logic_error("scene module '" + module.name + "' is registered twice");
    }
    for (const SceneKey& k : m.keys) {
      if (own.count(k.path)) {
        throw std::logic_error("scene module '" + module.name + "' declares '" + k.path +
                               "', which module '" + m.name + "' declares already");
      }
    }
  }
  modules.push_back(std::move(module));
  return true;
}

std::string SceneKeysMarkdown() {
  std::ostringstream out;
  out << "# Scene keys\n\n"
         "Generated from the modules' declarations (scene/scene_keys.h) by `ehd_sim keys "
         "--markdown`;\nthe test `SceneKeysDoc.MatchesTheDeclarations` fails when this file and "
         "the code disagree.\nThe rules every key follows are in docs/scenes.md. *when*: where "
         "the row applies (a condition\non the keys above it; of several rows of one key the "
         "first that holds is read); where none\napplies the key is refused, or accepted only "
         "with the value in *otherwise*. Units: `1`\ndimensionless, `a` the radius, `cells` the "
         "lattice spacing h, `steps` lattice steps. T is the\nscene's tension scale (membrane "
         "section).\n";
  std::map<std::string, const SceneKey*> last;  // a path's last declaration refuses
  for (const SceneModule& m : SceneModules()) {
    for (const SceneKey& k : m.keys) last[k.path] = &k;
  }
  for (const SceneModule& m : SceneModules()) {
    out << "\n## " << m.name << "\n\n" << m.doc << "\n\n";
    if (!m.stages.empty()) {
      out << "Stages:";
      for (std::size_t i = 0; i < m.stages.size(); ++i) out << (i ? ", " : " ") << m.stages[i];
      out << ". ";
    }
    if (!m.publishes.empty()) {
      out << "Publishes:";
      for (std::size_t i = 0; i < m.publishes.size(); ++i) {
        out << (i ? "; " : " ") << m.publishes[i];
      }
      out << '.';
    }
    if (!m.stages.empty() || !m.publishes.empty()) out << "\n\n";
    out << "| key | when | type | default | otherwise | units | meaning |\n"
           "|---|---|---|---|---|---|---|\n";
    for (const SceneKey& k : m.keys) {
      std::string otherwise;
      if (last.at(k.path) != &k) {
        otherwise = "next row";
      } else if (!k.when.text.empty()) {
        otherwise = k.otherwise ? ValueText(k, *k.otherwise) : "refused";
      }
      out << "| `" << k.path << "` | " << Cell(k.when.text) << " | " << Cell(k.TypeText()) << " | "
          << Cell(k.DefaultText()) << " | " << otherwise << " | " << Cell(k.units) << " | "
          << Cell(k.doc) << " |\n";
    }
  }
  return out.str();
}

}  // namespace ehd
