#pragma once
// internal: the plate tables of a scene (docs/plate.md, Scenes): [plate], [population], [[seedling]]
#include <string>
#include <vector>

#include <toml++/toml.h>

#include "rootsim/plate.hpp"
#include "scene_schema.hpp"

namespace rootsim::detail {

// true for the top-level tables plate scenes add
bool isPlateTable(const std::string& section);

struct PlateTables {
  PlateSpec spec;                  // no seedlings: the scene has none of the tables
  std::string toml;                // their resolved text: [plate] and every [[seedling]] with its final values
  std::vector<std::string> rootToml;  // each seedling's own: [plate] and that [[seedling]] alone
};

// reads and checks the plate tables against the plate-wide values (after --set) and the scene's
// obstacles (plate coordinates); each seedling's model is base's keys, its [seedling.set] overrides and
// the values [population] draws for it, with the obstacles in its own frame. Throws SceneError naming
// file:line and the key.
PlateTables parsePlateTables(const toml::table& root, const std::string& sourceName, const std::string& text,
                             const Values& base, const std::string& name, const std::vector<Obstacle>& obstacles);

// the resolved text of the plate's tables: [plate], [laterals], and a root's [[seedling]] table (its
// place, angle, set-point and the keys of its model that differ from the plate-wide model base's)
std::string plateTableToml(const PlateParams& pp);
std::string lateralsToml(const LateralParams& lp);
std::string seedlingToml(const Seedling& sd, const Model& base);

}  // namespace rootsim::detail
