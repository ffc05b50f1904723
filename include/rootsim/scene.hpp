#pragma once
// Scene files (TOML, SPEC.md): parsing, validation against the key schema, overrides, and the fully
// resolved scene text written into every run directory.
#include <string>
#include <vector>

#include "rootsim/errors.hpp"
#include "rootsim/model.hpp"

namespace rootsim {

struct Scene {
  Model model;
  std::string path;          // file it came from ("" for text)
  std::string resolvedToml;  // every key with its value, defaults filled in
};

// reads and validates a scene; overrides are "section.key=value" (TOML value syntax; bare words are
// taken as strings); throws SceneError naming the file, the line and the key
Scene loadScene(const std::string& path, const std::vector<std::string>& overrides = {});
Scene parseScene(const std::string& text, const std::string& sourceName,
                 const std::vector<std::string>& overrides = {});

}  // namespace rootsim
