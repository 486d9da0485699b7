// docs/scene_keys.md is the key table generated from the modules' declarations (every module
// linked into ehd_core, force terms included): the file and the code must agree.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "ehd_capsule/scene/scene.h"

namespace ehd {
namespace {

TEST(SceneKeysDoc, MatchesTheDeclarations) {
  const std::string path = std::string(EHD_SOURCE_DIR) + "/docs/scene_keys.md";
  std::ifstream in(path);
  ASSERT_TRUE(in) << "cannot read " << path;
  std::stringstream text;
  text << in.rdbuf();
  EXPECT_TRUE(text.str() == SceneKeysMarkdown())
      << path << " differs from the declarations: regenerate it with\n"
      << "  build/bin/ehd_sim keys --markdown > docs/scene_keys.md";
}

TEST(SceneKeysDoc, EveryKeyHasADocLineAndEveryNumberItsUnits) {
  for (const SceneModule& m : SceneModules()) {
    EXPECT_FALSE(m.doc.empty()) << m.name;
    for (const SceneKey& k : m.keys) {
      EXPECT_FALSE(k.doc.empty()) << k.path;
      if (k.type == KeyType::kNumber || k.type == KeyType::kInteger) {
        EXPECT_FALSE(k.units.empty()) << k.path;
      }
      EXPECT_FALSE(k.required && (k.fallback || k.fallback_from)) << k.path;
    }
  }
}

}  // namespace
}  // namespace ehd
