#pragma once
// Scene files (TOML, docs/cli.md): parsing, validation against the key schema, overrides, and the fully
// resolved scene text written into every run directory.
#include <string>
#include <vector>

#include "rootsim/errors.hpp"
#include "rootsim/model.hpp"
#include "rootsim/output_params.hpp"
#include "rootsim/plate.hpp"

namespace rootsim {

// most elements a scene may ask for, at the start (root.initial_length_mm / root.element_length_mm)
// and after growing: memory and time per step grow with it (a 600-element fig2b run takes minutes)
inline constexpr double kMaxElements = 20000;

struct Scene {
  // the root's model; for a plate ([[seedling]] tables, docs/plate.md) the plate-wide keys' model, or
  // the seedling's model when the plate has one seedling (a plate run's roots/NAME/scene.toml)
  Model model;
  OutputParams output;       // what the run writes ([output]; a plate's for all its roots)
  PlateSpec plate;           // the seedlings (none: a scene of one root alone)
  std::string path;          // file it came from ("" for text)
  std::string resolvedToml;  // every key with its value, defaults filled in
  std::vector<std::string> rootToml;  // a plate's: each seedling's own resolved scene (the plate with that
                                      // seedling alone), its roots/NAME/scene.toml
  bool isPlate() const { return !plate.seedlings.empty(); }
};

// reads and validates a scene; overrides are "section.key=value" (TOML value syntax; bare words are
// taken as strings); throws SceneError naming the file, the line and the key
Scene loadScene(const std::string& path, const std::vector<std::string>& overrides = {});
// the text of a scene (or sweep) file: a regular file of at most 1 MiB (a device or FIFO would be read forever or
// block); throws SceneError
std::string readSceneFile(const std::string& path, const std::string& kind = "scene file");
// the model of a scene that holds one root (a single-root scene, or a plate of one seedling); throws
// SceneError naming `what` for a plate of several roots ("render: RUN is a plate of 6 roots: ...")
const Model& singleRootModel(const Scene& sc, const std::string& what);
Scene parseScene(const std::string& text, const std::string& sourceName,
                 const std::vector<std::string>& overrides = {});
// the type of a scene key "section.key" as messages name it ("a number", "an integer", "true or false",
// "a string", "an array of 3 numbers"), or "" when the schema has no such key
std::string sceneKeyType(const std::string& key);
// the scene of a model built in code (the figure cases), without text: every key read from the model
// through the schema, checked like a scene file's (ranges, relations, obstacles clear of the root), and
// the resolved text a run directory holds, the same text a scene file with these values resolves to.
// The scene's model is what that text loads to: the model's fields the schema maps (bitwise, when
// each is a scene value times its unit, as every model built from scene values is), its obstacles, and
// defaults for the rest. Throws SceneError naming the key ("model NAME: tropism.beta must be ...")
// output: what the run writes ([output])
Scene sceneOf(const Model& model, const OutputParams& output);

// the keys "section.key" a scene file's text sets itself (not those it leaves to their defaults), in the
// file's order; SceneError as loadScene for a file that does not parse
std::vector<std::string> sceneFileKeys(const std::string& path);

// one key of the scene a model resolves to, and its value as Scene::resolvedToml writes it
struct SceneValue {
  std::string key;   // "section.key"; an obstacle's "obstacle[k].key" (k from 1, as in messages)
  std::string text;  // the value in TOML syntax: 0.2, true, "local", [0.0, 0.0, 0.0]
};
// every key of the scene of a model and what its run writes: the sections' keys in the order of the
// resolved text, then each obstacle's
std::vector<SceneValue> sceneValues(const Model& model, const OutputParams& output);

// the markdown table of the plate's keys of one table ("plate", "population", "seedling", "laterals"):
// each key's default, range and meaning, as the scene schema declares them (docs/plate.md's generated
// tables)
std::string plateKeysMarkdown(const std::string& section);
// the keys of one of the plate's tables, as the scene schema declares them ("seedling": name, genotype, ...)
std::vector<std::string> plateKeys(const std::string& section);

}  // namespace rootsim
