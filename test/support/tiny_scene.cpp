#include "tiny_scene.h"

#include <yaml-cpp/yaml.h>

#include <cstdio>
#include <cstdlib>
#include <sstream>

namespace ehd::test {

std::string ExactNumber(double value) {
  char text[40];
  for (int digits = 1; digits <= 17; ++digits) {
    std::snprintf(text, sizeof text, "%.*g", digits, value);
    if (std::strtod(text, nullptr) == value) break;
  }
  return text;
}

TinyScene::TinyScene(int dimension) : dimension_(dimension) {
  if (dimension == 3) {
    entries_ = {{"name", "tiny_sphere"},
                {"dimension", "3"},
                {"Ca", "0.05"},
                {"Re", "0.1"},
                {"E_b", "0"},
                {"V", "1"},
                {"N", "24"},
                {"mesh_subdivisions", "3"},
                {"law", "neo_hookean"},
                {"geometry.shape", "sphere"},
                {"geometry.half_width", "3"},
                {"membrane", "capsule"},
                {"flow", "shear"}};
  } else {
    entries_ = {{"name", "tiny_capsule"},
                {"Ca", "0.1"},
                {"Re", "0.1"},
                {"E_b", "0"},
                {"eta", "0"},
                {"V", "1"},
                {"N", "32"},
                {"M", "32"},
                {"geometry.shape", "circle"},
                {"geometry.half_width", "4"},
                {"membrane", "capsule"},
                {"flow", "shear"}};
  }
}

TinyScene& TinyScene::With(const std::string& path, double value) {
  return With(path, ExactNumber(value));
}

TinyScene& TinyScene::With(const std::string& path, const std::string& value) {
  for (auto& entry : entries_) {
    if (entry.first == path) {
      entry.second = value;
      return *this;
    }
  }
  entries_.emplace_back(path, value);
  return *this;
}

TinyScene& TinyScene::Without(const std::string& path) {
  std::vector<std::pair<std::string, std::string>> kept;
  for (const auto& entry : entries_) {
    if (entry.first != path && entry.first.rfind(path + ".", 0) != 0) kept.push_back(entry);
  }
  entries_ = kept;
  return *this;
}

TinyScene& TinyScene::Grid(int n) {
  With("N", n);
  if (dimension_ == 2) With("M", n);
  return *this;
}

TinyScene& TinyScene::Field(double ca_e, double sigma_r, double eps_r) {
  return With("Ca_E", ca_e).With("sigma_r", sigma_r).With("eps_r", eps_r).With("electric", "{}");
}

TinyScene TinyScene::SmallCaCapsule(double ca) {
  return TinyScene(2)
      .Name("small_ca_capsule")
      .With("Ca", ca)
      .With("Re", 0.2)
      .With("numerics.threads", 1);
}

TinyScene& TinyScene::Drop() {
  return With("membrane", "drop").Without("E_b").Without("eta").Without("law");
}

TinyScene& TinyScene::AtRest(double oh) {
  return With("flow", "none").Without("Ca").Without("Re").With("Oh", oh);
}

std::string TinyScene::Yaml() const {
  YAML::Node root(YAML::NodeType::Map);
  for (const auto& [path, value] : entries_) {
    std::vector<std::string> parts;
    std::stringstream in(path);
    for (std::string part; std::getline(in, part, '.');) parts.push_back(part);
    YAML::Node node = root;
    for (std::size_t i = 0; i + 1 < parts.size(); ++i) {
      if (!node[parts[i]].IsMap()) node[parts[i]] = YAML::Node(YAML::NodeType::Map);
      node.reset(node[parts[i]]);
    }
    node[parts.back()] = YAML::Load(value);
  }
  YAML::Emitter out;
  out << root;
  return std::string(out.c_str()) + "\n";
}

Scene TinyScene::Build(const std::vector<std::string>& overrides) const {
  return ParseScene(Yaml(), overrides);
}

}  // namespace ehd::test
