#pragma once
// internal: a scene's plate (docs/plate.md, Scenes): [[seedling]] tables, [population.spread], and each
// seedling's model and laterals from the plate's keys (plateSchema, read with the model's by scene.cpp)
#include <string>
#include <vector>

#include <toml++/toml.h>

#include "rootsim/plate.hpp"
#include "scene_schema.hpp"

namespace rootsim::detail {

// the plate's top-level tables whose keys plateSchema holds ([[seedling]] aside: an array of tables)
bool isPlateSection(const std::string& section);

struct PlateTables {
  PlateSpec spec;                  // no seedlings: the scene has none of the tables
  std::string toml;                // their resolved text: [plate] and every [[seedling]] with its final values
  std::vector<std::string> rootToml;  // each seedling's own: [plate] and that [[seedling]] alone
};

// the plate of a scene: plate holds the values of [plate], [population] and [laterals] (plateSchema's
// keys but the seedling's, defaults filled in, each with its origin), base the plate-wide model keys
// (after --set); the [[seedling]] array and [population.spread] are read from root. Each seedling's model
// and laterals are base's and plate's keys, its [seedling.set] overrides and the values [population]
// draws for it, with the obstacles in its own frame. Throws SceneError naming file:line and the key.
PlateTables readPlate(const toml::table& root, const std::string& sourceName, const std::string& text,
                      const Values& base, const Values& plate, const std::string& name,
                      const std::vector<Obstacle>& obstacles);

// the resolved text of the plate's tables: [plate], [laterals], and a root's [[seedling]] table (its
// place, angle, set-point and the keys of its model that differ from the plate-wide model base's; with
// plateLaterals, also its lateral keys that differ from those: the whole plate's text, where [laterals]
// precedes it)
std::string plateTableToml(const PlateParams& pp);
std::string lateralsToml(const LateralParams& lp);
std::string seedlingToml(const Seedling& sd, const Model& base, const LateralParams* plateLaterals = nullptr);

}  // namespace rootsim::detail
