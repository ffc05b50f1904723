#pragma once
// internal: what the scene readers (scene.cpp, plate_scene.cpp) share of toml++
#include <string>

#include <toml++/toml.h>

#include "scene_schema.hpp"

namespace rootsim::detail {

// "the string \"x\"", "the number 3", "a table", ...: what a message says a node is
std::string describeNode(const toml::node& n);
// converts a TOML node to a value of the key's type, or returns the reason it cannot ("must be a
// number (got ...)"); src is the text toml++ parsed n from
std::string convert(const KeySpec& k, const toml::node& n, Value& out, const std::string& src);
// a key's value from its node, converted to the key's type and checked (range, choices, rule), with loc
// as its origin; throws SceneError "loc: shown why" (shown: the key as the message names it). The one
// reader of a scene file's values (the sections, the plate's tables, a seedling's set)
Value readValue(const KeySpec& k, const toml::node& n, const std::string& loc, const std::string& shown,
                const std::string& src);
// "file:line" of a region
std::string where(const std::string& source, const toml::source_region& r);
// the key of the schema, or nullptr
const KeySpec* findKey(const std::string& section, const std::string& key);

}  // namespace rootsim::detail
