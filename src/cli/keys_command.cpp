// ehd_sim keys: the scene keys the modules declare (scene/scene_keys.h), as text or as the
// Markdown of docs/scene_keys.md.
#include <iostream>

#include "command.h"
#include "ehd_capsule/scene/scene.h"

namespace ehd::cli {
namespace {

int RunKeys(const std::vector<std::string>& args) {
  bool markdown = false;
  for (const std::string& a : args) {
    if (a == "--markdown") {
      markdown = true;
    } else {
      throw UsageError("unknown option '" + a + "'");
    }
  }
  if (markdown) {
    std::cout << SceneKeysMarkdown();
    return 0;
  }
  for (const SceneModule& m : SceneModules()) {
    std::cout << m.name << ": " << m.doc << '\n';
    for (const SceneKey& k : m.keys) {
      std::cout << "  " << k.path;
      if (!k.when.text.empty()) std::cout << " [" << k.when.text << "]";
      std::cout << ": " << k.TypeText() << ", " << k.DefaultText();
      if (!k.units.empty() && k.units != "1") std::cout << ", in " << k.units;
      std::cout << " - " << k.doc << '\n';
    }
  }
  return 0;
}

const CommandRegistration kKeys(
    {"keys", "the scene keys: type, range, default, units, where each applies",
     "usage: ehd_sim keys [--markdown]\n"
     "Prints every scene key as its module declares it (scene/scene_keys.h): the type and range,\n"
     "the default or 'required', the units, where it applies and its meaning. --markdown prints\n"
     "the table of docs/scene_keys.md (a test checks that file against this output).\n",
     RunKeys});

}  // namespace
}  // namespace ehd::cli
